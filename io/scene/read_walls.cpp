// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>

#include "contact/contact_laws.hpp"
#include "io/scene/toml_reader.hpp"

namespace femdem::scene {

std::vector<VelocityPoint> Reader::read_velocity_history(const toml::table& t,
                                                         const std::string& p) const {
  std::vector<VelocityPoint> history;
  const toml::node* hn = t.get("velocity_history");
  if (!hn) return history;
  const std::string hk = dotted(p, "velocity_history");
  if (t.contains("velocity"))
    fail(hn, hk,
         "give either 'velocity' (constant) or 'velocity_history' (piecewise linear), not both");
  const toml::array* rows = hn->as_array();
  if (!rows || rows->empty())
    fail(hn, hk,
         "expected a non-empty array of rows [t, vx, vy, vz], e.g. [[0, 0, 0, 0], [1e-3, 0, 0, "
         "-0.1]], got " +
             (rows ? std::string("an empty array") : type_name(*hn)));
  for (std::size_t i = 0; i < rows->size(); ++i) {
    const toml::node& rn = *rows->get(i);
    const std::string row = "row " + std::to_string(i + 1);
    const toml::array* r = rn.as_array();
    if (!r || r->size() != 4)
      fail(&rn, hk,
           row + " must be [t, vx, vy, vz] (4 numbers), got " +
               (r ? std::to_string(r->size()) + " numbers" : type_name(rn)));
    double v[4];
    for (std::size_t j = 0; j < 4; ++j) {
      const toml::node& e = *r->get(j);
      if (!e.is_number())
        fail(&e, hk,
             row + " must be [t, vx, vy, vz] (4 numbers), element " + std::to_string(j + 1) +
                 " is " + type_name(e));
      v[j] = e.value<double>().value();
      if (!std::isfinite(v[j])) fail(&e, hk, row + " must hold finite numbers");
    }
    if (i == 0 && v[0] != 0.0)
      fail(&rn, hk, "the first row must be at t = 0, got t = " + format_number(v[0]));
    if (i > 0 && !(v[0] > history.back().time))
      fail(&rn, hk,
           "times must increase strictly: " + row + " has t = " + format_number(v[0]) +
               " after t = " + format_number(history.back().time));
    history.push_back({v[0], Vec3(v[1], v[2], v[3])});
  }
  return history;
}

toml::array velocity_history_rows(const std::vector<VelocityPoint>& history) {
  toml::array rows;
  for (const VelocityPoint& q : history)
    rows.push_back(toml::array{q.time, q.velocity.x(), q.velocity.y(), q.velocity.z()});
  return rows;
}

Reader::WallSurface Reader::read_wall_surface(const toml::table& t, const std::string& p) const {
  WallSurface w;
  w.friction = number(t, "friction", p, 0.0, &t);
  if (w.friction < 0.0)
    fail(t.get("friction"), dotted(p, "friction"),
         "must not be negative, got " + format_number(w.friction));
  const std::optional<double> given = opt_penalty_factor(t, p);
  w.penalty_factor = !given ? 0.0 : *given > 0.0 ? *given : -1.0;
  w.damping = number(t, "damping", p, 0.0, &t);
  if (w.damping < 0.0 || w.damping > 1.0)
    fail(t.get("damping"), dotted(p, "damping"),
         "must be a fraction of critical damping in [0, 1], got " + format_number(w.damping));
  return w;
}

void Reader::WallSurface::write(toml::table& out) const {
  out.insert_or_assign("friction", friction);
  if (penalty_factor > 0.0) out.insert_or_assign("penalty_factor", penalty_factor);
  if (penalty_factor < 0.0) out.insert_or_assign("penalty_factor", "auto");
  out.insert_or_assign("damping", damping);
}

int Reader::read_polygon_sides(const toml::table& t, const std::string& p) const {
  const std::int64_t sides = opt_integer(t, "sides", p).value_or(24);
  if (sides < 3 || sides > 1024)
    fail(t.get("sides"), dotted(p, "sides"),
         "must be an integer in [3, 1024], got " + std::to_string(sides));
  return static_cast<int>(sides);
}

void Reader::read_walls(const toml::table& root, ModelSpec& spec, toml::array& out,
                        std::set<std::string>& names) const {
  int index = 0;
  for (const auto& [tp, p] : entries(root, "walls")) {
    const toml::table& t = *tp;
    ++index;
    check_keys(
        t, p,
        {"name", "point", "normal", "velocity", "velocity_history", "friction",
         "rolling_resistance", "penalty_factor", "damping", "force_history", "mass", "bumps"});
    WallSpec w;
    w.name = entry_name(t, p, names, "wall", "wall" + std::to_string(index));
    w.point = opt_vec3(t, "point", p).value_or(Vec3::Zero());
    if (auto n = opt_vec3(t, "normal", p)) {
      if (!(n->norm() > 0.0))
        fail(t.get("normal"), dotted(p, "normal"), "must not be the zero vector");
      w.normal = n->normalized();
    }
    w.velocity = opt_vec3(t, "velocity", p).value_or(Vec3::Zero());
    w.velocity_history = read_velocity_history(t, p);
    if (const toml::node* fn = t.get("force_history")) {
      const std::string fk = dotted(p, "force_history");
      if (t.contains("velocity_history"))
        fail(fn, fk,
             "give either 'velocity_history' (prescribed motion) or 'force_history' (prescribed "
             "load), not both");
      const toml::array* rows = fn->as_array();
      if (!rows || rows->empty())
        fail(fn, fk,
             "expected a non-empty array of rows [t, F] (F in N along the normal, towards the "
             "bodies), e.g. [[0, 0], [1e-3, 500]], got " +
                 (rows ? std::string("an empty array") : type_name(*fn)));
      for (std::size_t i = 0; i < rows->size(); ++i) {
        const toml::node& rn = *rows->get(i);
        const std::string row = "row " + std::to_string(i + 1);
        const toml::array* r = rn.as_array();
        if (!r || r->size() != 2 || !(*r)[0].is_number() || !(*r)[1].is_number())
          fail(&rn, fk, row + " must be [t, F] (2 numbers)");
        const double tt = (*r)[0].value<double>().value(), f = (*r)[1].value<double>().value();
        if (!std::isfinite(tt) || !std::isfinite(f))
          fail(&rn, fk, row + " must hold finite numbers");
        if (i == 0 && tt != 0.0)
          fail(&rn, fk, "the first row must be at t = 0, got t = " + format_number(tt));
        if (i > 0 && !(tt > w.force_history.back().time))
          fail(&rn, fk,
               "times must increase strictly: " + row + " has t = " + format_number(tt) +
                   " after t = " + format_number(w.force_history.back().time));
        w.force_history.push_back({tt, f});
      }
      w.mass = number(t, "mass", p, std::nullopt, &t);
      if (!(w.mass > 0.0))
        fail(t.get("mass"), dotted(p, "mass"),
             "must be positive (the punch's mass, kg), got " + format_number(w.mass));
    } else if (t.contains("mass")) {
      fail(t.get("mass"), dotted(p, "mass"),
           "only a force-driven wall has a mass: give 'force_history' too, or remove 'mass'");
    }
    w.friction = number(t, "friction", p, 0.0, &t);
    if (w.friction < 0.0)
      fail(t.get("friction"), dotted(p, "friction"),
           "must not be negative, got " + format_number(w.friction));
    if (t.contains("rolling_resistance")) {
      w.rolling_resistance = number(t, "rolling_resistance", p, std::nullopt, &t);
      if (!(w.rolling_resistance >= 0.0 && w.rolling_resistance <= 1.0))
        fail(t.get("rolling_resistance"), dotted(p, "rolling_resistance"),
             "must be a coefficient in [0, 1] (the lever arm over the rolling radius), got " +
                 format_number(w.rolling_resistance));
    }
    if (const auto pf = opt_penalty_factor(t, p)) w.penalty_factor = *pf > 0.0 ? *pf : -1.0;
    if (const toml::node* bn = t.get("bumps")) {
      const std::string bp = dotted(p, "bumps");
      const toml::table* b = bn->as_table();
      if (!b)
        fail(bn, bp,
             "expected a table { diameter = D, spacing = S } (hemispheres of diameter D on a "
             "hexagonal lattice of spacing S, S = D when absent), got " +
                 type_name(*bn));
      check_keys(*b, bp, {"diameter", "spacing"});
      w.bump_diameter = positive(*b, "diameter", bp, std::nullopt, bn);
      w.bump_spacing = positive(*b, "spacing", bp, w.bump_diameter, bn);
    }
    toml::table o;
    o.insert_or_assign("name", w.name);
    o.insert_or_assign("point", toml::array{w.point.x(), w.point.y(), w.point.z()});
    o.insert_or_assign("normal", toml::array{w.normal.x(), w.normal.y(), w.normal.z()});
    if (w.velocity_history.empty()) {
      o.insert_or_assign("velocity", toml::array{w.velocity.x(), w.velocity.y(), w.velocity.z()});
    } else {
      o.insert_or_assign("velocity_history", velocity_history_rows(w.velocity_history));
    }
    o.insert_or_assign("friction", w.friction);
    if (w.rolling_resistance >= 0.0) o.insert_or_assign("rolling_resistance", w.rolling_resistance);
    if (w.penalty_factor > 0.0) o.insert_or_assign("penalty_factor", w.penalty_factor);
    if (w.penalty_factor < 0.0) o.insert_or_assign("penalty_factor", "auto");
    if (w.bump_diameter > 0.0)
      o.insert_or_assign("bumps",
                         toml::table{{"diameter", w.bump_diameter}, {"spacing", w.bump_spacing}});
    w.damping = number(t, "damping", p, 0.0, &t);
    if (w.damping < 0.0 || w.damping > 1.0)
      fail(t.get("damping"), dotted(p, "damping"),
           "must be a fraction of critical damping in [0, 1], got " + format_number(w.damping));
    o.insert_or_assign("damping", w.damping);
    if (!w.force_history.empty()) {
      toml::array rows;
      for (const ForcePoint& q : w.force_history) rows.push_back(toml::array{q.time, q.force});
      o.insert_or_assign("force_history", std::move(rows));
      o.insert_or_assign("mass", w.mass);
    }
    out.push_back(std::move(o));
    spec.walls.push_back(w);
  }
}

RegionSpec Reader::read_region(const toml::table& c, const std::string& cp,
                               toml::table& out) const {
  RegionSpec r;
  const std::string p = dotted(cp, "region");
  const toml::node* n = c.get("region");
  if (!n || (n->is_string() && n->as_string()->get() == "all")) {
    r.kind = RegionSpec::Kind::All;
    out.insert_or_assign("region", "all");
    return r;
  }
  if (n->is_string())
    fail(n, p,
         "unknown region '" + n->as_string()->get() +
             "': use \"all\", { box_min = [...], box_max = [...] }, { plane_point = [...], "
             "plane_normal = [...] } or { physical = \"NAME\" }");
  if (!n->is_table())
    fail(n, p,
         "expected \"all\" or a table (box_min/box_max or plane_point/plane_normal), got " +
             type_name(*n));
  const toml::table& t = *n->as_table();
  if (t.contains("physical")) {
    // a node set of the body's mesh file, resolved by read_constraints
    check_keys(t, p, {"physical"}, "for a physical group of the body's mesh file");
    r.kind = RegionSpec::Kind::Nodes;
    r.node_set = string(t, "physical", p, &t);
    toml::table o;
    o.insert_or_assign("physical", r.node_set);
    out.insert_or_assign("region", std::move(o));
    return r;
  }
  const bool box = t.contains("box_min") || t.contains("box_max");
  const bool plane = t.contains("plane_point") || t.contains("plane_normal");
  if (box && plane) fail(n, p, "mixes a box (box_min/box_max) and a plane (plane_point/...)");
  if (!box && !plane) {
    check_keys(t, p, {"box_min", "box_max", "plane_point", "plane_normal", "tolerance"});
    fail(n, p, "needs box_min and box_max, or plane_point and plane_normal");
  }
  toml::table o;
  if (box) {
    check_keys(t, p, {"box_min", "box_max"}, "for a box region");
    auto lo = opt_vec3(t, "box_min", p), hi = opt_vec3(t, "box_max", p);
    if (!lo) fail(n, dotted(p, "box_min"), "required value is missing (box_max is given)");
    if (!hi) fail(n, dotted(p, "box_max"), "required value is missing (box_min is given)");
    for (int i = 0; i < 3; ++i)
      if ((*lo)[i] > (*hi)[i])
        fail(t.get("box_max"), dotted(p, "box_max"),
             std::string("is below box_min in ") + "xyz"[i]);
    r.kind = RegionSpec::Kind::Box;
    r.box_min = *lo;
    r.box_max = *hi;
    o.insert_or_assign("box_min", toml::array{lo->x(), lo->y(), lo->z()});
    o.insert_or_assign("box_max", toml::array{hi->x(), hi->y(), hi->z()});
  } else {
    check_keys(t, p, {"plane_point", "plane_normal", "tolerance"}, "for a plane region");
    auto pt = opt_vec3(t, "plane_point", p), nr = opt_vec3(t, "plane_normal", p);
    if (!pt) fail(n, dotted(p, "plane_point"), "required value is missing");
    if (!nr) fail(n, dotted(p, "plane_normal"), "required value is missing");
    if (!(nr->norm() > 0.0))
      fail(t.get("plane_normal"), dotted(p, "plane_normal"), "must not be the zero vector");
    r.kind = RegionSpec::Kind::Plane;
    r.plane_point = *pt;
    r.plane_normal = nr->normalized();
    r.tolerance = positive(t, "tolerance", p, 0.0, n);
    o.insert_or_assign("plane_point", toml::array{pt->x(), pt->y(), pt->z()});
    o.insert_or_assign("plane_normal",
                       toml::array{r.plane_normal.x(), r.plane_normal.y(), r.plane_normal.z()});
    if (r.tolerance > 0.0) o.insert_or_assign("tolerance", r.tolerance);
  }
  out.insert_or_assign("region", std::move(o));
  return r;
}

void Reader::read_constraints(const toml::table& root, ModelSpec& spec, toml::array& out) const {
  std::vector<std::string> body_names;
  for (const auto& b : spec.bodies) body_names.push_back(b.name);
  std::set<std::string> names;
  int index = 0;
  for (const auto& [tp, p] : entries(root, "constraints")) {
    const toml::table& t = *tp;
    ++index;
    check_keys(t, p, {"name", "body", "region", "fix", "velocity"});
    if (t.contains("name"))
      entry_name(t, p, names, "constraint", "constraint" + std::to_string(index));
    ConstraintSpec c;
    const std::string body = string(t, "body", p, &t);
    for (std::size_t i = 0; i < spec.bodies.size(); ++i)
      if (spec.bodies[i].name == body) c.body = static_cast<int>(i);
    if (c.body < 0)
      fail(t.get("body"), dotted(p, "body"),
           "unknown body '" + body + "'" + did_you_mean(body, body_names) +
               "; bodies: " + join(body_names));
    toml::table o;
    if (t.contains("name")) o.insert_or_assign("name", t.get("name")->as_string()->get());
    o.insert_or_assign("body", body);
    c.region = read_region(t, p, o);
    if (c.region.kind == RegionSpec::Kind::Nodes) {
      const NodeSets& sets = body_node_sets_[body];
      std::vector<std::string> labels;
      for (const auto& [label, nodes] : sets) {
        labels.push_back(label);
        if (label == c.region.node_set) c.region.nodes = nodes;
      }
      if (c.region.nodes.empty()) {
        const toml::node* rn = t.get("region")->as_table()->get("physical");
        fail(rn, dotted(p, "region.physical"),
             "body '" + body + "' has no node set '" + c.region.node_set + "'" +
                 did_you_mean(c.region.node_set, labels) +
                 (labels.empty() ? "; its mesh defines none (node sets are the physical points, "
                                   "curves and surfaces of a gmsh .msh file)"
                                 : "; its node sets: " + join(labels)));
      }
    }
    bool any_fix = false;
    if (const toml::node* f = t.get("fix")) {
      const std::string fk = dotted(p, "fix");
      const toml::array* a = f->as_array();
      if (!a) fail(f, fk, "expected an array of components, e.g. [\"x\", \"z\"]");
      toml::array fo;
      for (const auto& e : *a) {
        const std::string comp = e.is_string() ? e.as_string()->get() : std::string();
        const int axis = comp == "x" ? 0 : comp == "y" ? 1 : comp == "z" ? 2 : -1;
        if (axis < 0)
          fail(&e, fk,
               (e.is_string() ? "unknown component '" + comp + "'"
                              : "expected a component name, got " + type_name(e)) +
                   ": use any of \"x\", \"y\", \"z\"");
        if (!c.fix[axis]) fo.push_back(comp);
        c.fix[axis] = true;
        any_fix = true;
      }
      o.insert_or_assign("fix", std::move(fo));
    }
    c.velocity = opt_vec3(t, "velocity", p);
    if (!any_fix && !c.velocity)
      fail(t.contains("fix") ? t.get("fix") : &t, p,
           "does nothing: give 'fix' (a non-empty list of \"x\", \"y\", \"z\") or 'velocity'");
    if (any_fix && c.velocity)
      fail(t.get("velocity"), dotted(p, "velocity"),
           "give either 'fix' or 'velocity', not both (velocity prescribes all three "
           "components; use velocity = [0, 0, v] to hold x and y)");
    if (c.velocity)
      o.insert_or_assign("velocity",
                         toml::array{c.velocity->x(), c.velocity->y(), c.velocity->z()});
    out.push_back(std::move(o));
    spec.constraints.push_back(c);
  }
}

std::string Reader::law_name(const toml::table& t, std::string_view key, std::string_view fallback,
                             const std::vector<std::string>& laws) const {
  const std::string name = opt_string(t, key, "contact").value_or(std::string(fallback));
  if (std::find(laws.begin(), laws.end(), name) == laws.end())
    fail(t.get(key), dotted("contact", key),
         "unknown law '" + name + "'" + did_you_mean(name, laws) + "; laws: " + join(laws));
  return name;
}

void Reader::read_contact(const toml::table& root, ModelSpec& spec, toml::table& out) const {
  ContactSettings& c = spec.contact;
  if (const toml::node* n = root.get("contact")) {
    const toml::table& t = require_table(n, "contact");
    check_keys(t, "contact",
               {"law", "wall_law", "penalty_factor", "friction", "impact_damping",
                "rolling_resistance", "initial_overlap", "pairs"});
    c.law = registered_name<BodyPairLaw>(law_name(t, "law", c.law, body_pair_law_names()));
    c.wall_law = registered_name<WallLaw>(law_name(t, "wall_law", c.wall_law, wall_law_names()));
    c.penalty_factor = opt_penalty_factor(t, "contact").value_or(c.penalty_factor);
    c.friction = number(t, "friction", "contact", c.friction, &t);
    if (c.friction < 0.0)
      fail(t.get("friction"), "contact.friction",
           "must not be negative, got " + format_number(c.friction));
    c.impact_damping = number(t, "impact_damping", "contact", c.impact_damping, &t);
    if (!(c.impact_damping >= 0.0 && c.impact_damping < 1.0))
      fail(t.get("impact_damping"), "contact.impact_damping",
           "must be a fraction of critical damping in [0, 1), got " +
               format_number(c.impact_damping));
    c.rolling_resistance = number(t, "rolling_resistance", "contact", c.rolling_resistance, &t);
    if (!(c.rolling_resistance >= 0.0 && c.rolling_resistance <= 1.0))
      fail(t.get("rolling_resistance"), "contact.rolling_resistance",
           "must be a coefficient in [0, 1] (the lever arm over the rolling radius), got " +
               format_number(c.rolling_resistance));
    c.initial_overlap = number(t, "initial_overlap", "contact", c.initial_overlap, &t);
    if (!(c.initial_overlap >= 0.0 && c.initial_overlap <= 1.0))
      fail(t.get("initial_overlap"), "contact.initial_overlap",
           "must be a fraction of the element size in [0, 1], got " +
               format_number(c.initial_overlap));
    std::vector<std::string> body_names;
    for (const auto& b : spec.bodies) body_names.push_back(b.name);
    toml::array pairs_out;
    for (const auto& [pt, short_prefix] : entries(t, "pairs")) {
      const toml::table& pair = *pt;
      const std::string p = "contact." + short_prefix;
      check_keys(pair, p, {"bodies", "friction"});
      const toml::node* bn = pair.get("bodies");
      if (!bn) fail(&pair, dotted(p, "bodies"), "required value is missing (two body names)");
      const toml::array* ba = bn->as_array();
      if (!ba || ba->size() != 2 || !(*ba)[0].is_string() || !(*ba)[1].is_string())
        fail(bn, dotted(p, "bodies"), "expected two body names, e.g. [\"ball\", \"plate\"]");
      ContactPairSpec cp;
      int* ids[2] = {&cp.body_a, &cp.body_b};
      for (int k = 0; k < 2; ++k) {
        const std::string name = (*ba)[k].as_string()->get();
        for (std::size_t i = 0; i < spec.bodies.size(); ++i)
          if (spec.bodies[i].name == name) *ids[k] = static_cast<int>(i);
        if (*ids[k] < 0)
          fail(bn, dotted(p, "bodies"),
               "unknown body '" + name + "'" + did_you_mean(name, body_names) +
                   "; bodies: " + join(body_names));
      }
      if (cp.body_a == cp.body_b)
        fail(bn, dotted(p, "bodies"), "names the same body twice: contact is between two bodies");
      for (const ContactPairSpec& q : c.pairs)
        if ((q.body_a == cp.body_a && q.body_b == cp.body_b) ||
            (q.body_a == cp.body_b && q.body_b == cp.body_a))
          fail(bn, dotted(p, "bodies"), "this pair of bodies is already listed");
      cp.friction = number(pair, "friction", p, std::nullopt, &pair);
      if (cp.friction < 0.0)
        fail(pair.get("friction"), dotted(p, "friction"),
             "must not be negative, got " + format_number(cp.friction));
      c.pairs.push_back(cp);
      toml::table o;
      o.insert_or_assign("bodies",
                         toml::array{spec.bodies[cp.body_a].name, spec.bodies[cp.body_b].name});
      o.insert_or_assign("friction", cp.friction);
      pairs_out.push_back(std::move(o));
    }
    if (!pairs_out.empty()) out.insert_or_assign("pairs", std::move(pairs_out));
  }
  out.insert_or_assign("law", std::string(c.law));
  out.insert_or_assign("wall_law", std::string(c.wall_law));
  if (c.penalty_factor > 0.0)
    out.insert_or_assign("penalty_factor", c.penalty_factor);
  else
    out.insert_or_assign("penalty_factor", "auto");
  out.insert_or_assign("friction", c.friction);
  out.insert_or_assign("impact_damping", c.impact_damping);
  // written only when set, so that the scenes before it keep their resolved text (and the
  // digest their checkpoints carry)
  if (c.rolling_resistance > 0.0) out.insert_or_assign("rolling_resistance", c.rolling_resistance);
  out.insert_or_assign("initial_overlap", c.initial_overlap);
}

}  // namespace femdem::scene

// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>

#include "io/scene/polygon_walls.hpp"
#include "io/scene/toml_reader.hpp"

namespace femdem::scene {

void Reader::read_compaction(const toml::table& root, ModelSpec& spec, toml::table& out,
                             std::set<std::string>& names) const {
  const toml::node* n = root.get("compaction");
  if (!n) return;
  const toml::table& t = require_table(n, "compaction");
  const std::string p = "compaction";
  check_keys(t, p,
             {"punch", "bottom", "die", "die_walls", "die_area", "die_perimeter", "powder",
              "fit_min_pressure", "fit_max_pressure"});
  CompactionSpec c;
  std::vector<std::string> wall_names, body_names;
  for (const auto& w : spec.walls) wall_names.push_back(w.name);
  for (const auto& b : spec.bodies) body_names.push_back(b.name);
  auto wall_index = [&](const toml::node* node, const std::string& key, const std::string& name) {
    for (std::size_t i = 0; i < spec.walls.size(); ++i)
      if (spec.walls[i].name == name) return static_cast<int>(i);
    fail(
        node, key,
        "unknown wall '" + name + "'" + did_you_mean(name, wall_names) +
            (wall_names.empty() ? "; the scene has no [[walls]]" : "; walls: " + join(wall_names)));
  };
  const std::string punch = string(t, "punch", p, &t), bottom = string(t, "bottom", p, &t);
  c.punch = wall_index(t.get("punch"), dotted(p, "punch"), punch);
  c.bottom = wall_index(t.get("bottom"), dotted(p, "bottom"), bottom);
  if (c.punch == c.bottom)
    fail(t.get("bottom"), dotted(p, "bottom"), "the punch and the bottom must be two walls");
  const Vec3 axis = spec.walls[c.bottom].normal;  // into the powder
  if (spec.walls[c.punch].normal.dot(axis) > -0.999)
    fail(t.get("punch"), dotted(p, "punch"),
         "the punch wall '" + punch + "' must face the bottom wall '" + bottom +
             "' (opposite normals along the die axis)");
  toml::table o;
  o.insert_or_assign("punch", punch);
  o.insert_or_assign("bottom", bottom);

  const toml::node* dn = t.get("die");
  const toml::node* dwn = t.get("die_walls");
  if (dn && dwn)
    fail(dwn, dotted(p, "die_walls"),
         "give either 'die' (a polygonal die made into walls) or 'die_walls' (with die_area), "
         "not both");
  if (!dn && !dwn)
    fail(&t, p,
         "needs a die: 'die = { radius = r, sides = N }' (N plane walls around the axis) or "
         "'die_walls = [...]' naming walls, with 'die_area' (and 'die_perimeter')");
  if (dn) {
    const std::string dp = dotted(p, "die");
    const toml::table& d = require_table(dn, dp);
    check_keys(d, dp,
               {"radius", "sides", "friction", "penalty_factor", "damping", "height", "angle"});
    if (t.contains("die_area") || t.contains("die_perimeter"))
      fail(t.contains("die_area") ? t.get("die_area") : t.get("die_perimeter"), p,
           "die_area and die_perimeter follow from 'die' (give them only with 'die_walls')");
    const double r = positive(d, "radius", dp, std::nullopt, &d);
    const int sides = read_polygon_sides(d, dp);
    const WallSurface surface = read_wall_surface(d, dp);
    const auto height = opt_number(d, "height", dp);
    if (height && !(*height > 0.0))
      fail(d.get("height"), dotted(dp, "height"),
           "must be positive, got " + format_number(*height));
    const double angle = number(d, "angle", dp, 0.0, &d);
    PolygonPrism die;
    die.centre = spec.walls[c.bottom].point;
    die.axis = axis;
    die.radius = r;
    die.sides = sides;
    die.angle = angle;
    die.to = height;  // open at the bottom's side: the bottom wall closes it
    for (WallSpec& w : polygon_walls("die", die)) {
      if (!names.insert(w.name).second)
        fail(dn, dp,
             "makes walls named die_1 ... die_" + std::to_string(sides) + ", but '" + w.name +
                 "' is already the name of a body or wall");
      w.friction = surface.friction;
      w.penalty_factor = surface.penalty_factor;
      w.damping = surface.damping;
      c.die_walls.push_back(static_cast<int>(spec.walls.size()));
      spec.walls.push_back(w);
    }
    c.area = polygon_area(r, die.sides);
    c.perimeter = polygon_side(r, die.sides) * static_cast<double>(sides);
    toml::table od;
    od.insert_or_assign("radius", r);
    od.insert_or_assign("sides", sides);
    surface.write(od);
    if (height) od.insert_or_assign("height", *height);
    od.insert_or_assign("angle", angle);
    o.insert_or_assign("die", std::move(od));
  } else {
    const std::string dk = dotted(p, "die_walls");
    const toml::array* a = dwn->as_array();
    if (!a || a->empty()) fail(dwn, dk, "expected a non-empty array of wall names");
    toml::array ow;
    for (const auto& e : *a) {
      if (!e.is_string()) fail(&e, dk, "expected a wall name, got " + type_name(e));
      const std::string name = e.as_string()->get();
      const int wi = wall_index(&e, dk, name);
      if (wi == c.punch || wi == c.bottom)
        fail(&e, dk, "'" + name + "' is the punch or the bottom, not a die wall");
      for (int q : c.die_walls)
        if (q == wi) fail(&e, dk, "'" + name + "' is listed twice");
      c.die_walls.push_back(wi);
      ow.push_back(name);
    }
    c.area = positive(t, "die_area", p, std::nullopt, &t);
    c.perimeter = number(t, "die_perimeter", p, 0.0, &t);
    if (c.perimeter < 0.0)
      fail(t.get("die_perimeter"), dotted(p, "die_perimeter"),
           "must not be negative, got " + format_number(c.perimeter));
    o.insert_or_assign("die_walls", std::move(ow));
    o.insert_or_assign("die_area", c.area);
    o.insert_or_assign("die_perimeter", c.perimeter);
  }

  if (const toml::node* pn = t.get("powder")) {
    const std::string pk = dotted(p, "powder");
    const toml::array* a = pn->as_array();
    if (!a || a->empty()) fail(pn, pk, "expected a non-empty array of body names");
    toml::array ob;
    for (const auto& e : *a) {
      if (!e.is_string()) fail(&e, pk, "expected a body name, got " + type_name(e));
      const std::string name = e.as_string()->get();
      int bi = -1;
      for (std::size_t i = 0; i < spec.bodies.size(); ++i)
        if (spec.bodies[i].name == name) bi = static_cast<int>(i);
      if (bi < 0)
        fail(&e, pk,
             "unknown body '" + name + "'" + did_you_mean(name, body_names) +
                 "; bodies: " + join(body_names));
      for (int q : c.powder)
        if (q == bi) fail(&e, pk, "'" + name + "' is listed twice");
      c.powder.push_back(bi);
      ob.push_back(name);
    }
    o.insert_or_assign("powder", std::move(ob));
  } else {
    bool any = false;
    for (const auto& b : spec.bodies) any = any || !b.fixed;
    if (!any) fail(&t, p, "every body is fixed: there is no powder to compact");
  }
  c.fit_min_pressure = number(t, "fit_min_pressure", p, 0.0, &t);
  c.fit_max_pressure = number(t, "fit_max_pressure", p, 0.0, &t);
  if (c.fit_min_pressure < 0.0)
    fail(t.get("fit_min_pressure"), dotted(p, "fit_min_pressure"),
         "must not be negative, got " + format_number(c.fit_min_pressure));
  if (c.fit_max_pressure < 0.0 ||
      (c.fit_max_pressure > 0.0 && c.fit_max_pressure <= c.fit_min_pressure))
    fail(t.get("fit_max_pressure"), dotted(p, "fit_max_pressure"),
         "must be 0 (the largest pressure) or above fit_min_pressure, got " +
             format_number(c.fit_max_pressure));
  o.insert_or_assign("fit_min_pressure", c.fit_min_pressure);
  o.insert_or_assign("fit_max_pressure", c.fit_max_pressure);
  out = std::move(o);
  spec.compaction = c;
}

}  // namespace femdem::scene

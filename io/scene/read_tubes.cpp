// SPDX-License-Identifier: GPL-3.0-or-later
// [[tubes]]: a regular polygonal tube of `sides` plane walls around an axis, of finite length,
// moving as a whole: the cylinder a granular column is poured into and then lifted off
// (Lajeunesse et al. 2004). Each side is a rigid plate (engine/model.hpp, Wall::push): bounded
// along the axis by the tube's ends, which travel with it, so lifting the tube releases the
// grains below its lower end without cutting into them; and `thickness` thick, so grains that
// flow out under the tube and pile up against its outside are pushed outwards, not pulled in.
#include <cmath>

#include "io/scene/polygon_walls.hpp"
#include "io/scene/toml_reader.hpp"

namespace femdem::scene {

void Reader::read_tubes(const toml::table& root, ModelSpec& spec, toml::array& out,
                        std::set<std::string>& names) const {
  int index = 0;
  for (const auto& [tp, p] : entries(root, "tubes")) {
    const toml::table& t = *tp;
    ++index;
    check_keys(t, p,
               {"name", "centre", "axis", "radius", "sides", "height", "thickness", "angle",
                "friction", "penalty_factor", "damping", "velocity", "velocity_history"});
    const std::string name = entry_name(t, p, names, "wall", "tube" + std::to_string(index));
    PolygonPrism tube;
    const auto centre = opt_vec3(t, "centre", p);
    if (!centre)
      fail(&t, dotted(p, "centre"),
           "required value is missing (the point on the tube's axis at its lower end)");
    tube.centre = *centre;
    if (auto a = opt_vec3(t, "axis", p)) {
      if (!(a->norm() > 0.0)) fail(t.get("axis"), dotted(p, "axis"), "must not be the zero vector");
      tube.axis = a->normalized();
    }
    tube.radius = positive(t, "radius", p, std::nullopt, &t);
    tube.sides = read_polygon_sides(t, p);
    const double height = positive(t, "height", p, std::nullopt, &t);
    tube.from = 0.0;
    tube.to = height;
    const double thickness = positive(t, "thickness", p, 0.02 * tube.radius, &t);
    tube.angle = number(t, "angle", p, 0.0, &t);
    const WallSurface surface = read_wall_surface(t, p);
    const Vec3 velocity = opt_vec3(t, "velocity", p).value_or(Vec3::Zero());
    const std::vector<VelocityPoint> history = read_velocity_history(t, p);
    for (WallSpec& w : polygon_walls(name, tube)) {
      if (!names.insert(w.name).second)
        fail(t.get("name") ? t.get("name") : &t, dotted(p, "name"),
             "tube '" + name + "' makes walls named " + name + "_1 ... " + name + "_" +
                 std::to_string(tube.sides) + ", but '" + w.name +
                 "' is already the name of a body or wall");
      w.thickness = thickness;
      w.friction = surface.friction;
      w.penalty_factor = surface.penalty_factor;
      w.damping = surface.damping;
      w.velocity = velocity;
      w.velocity_history = history;
      spec.walls.push_back(w);
    }
    toml::table o;
    o.insert_or_assign("name", name);
    o.insert_or_assign("centre", toml::array{tube.centre.x(), tube.centre.y(), tube.centre.z()});
    o.insert_or_assign("axis", toml::array{tube.axis.x(), tube.axis.y(), tube.axis.z()});
    o.insert_or_assign("radius", tube.radius);
    o.insert_or_assign("sides", tube.sides);
    o.insert_or_assign("height", height);
    o.insert_or_assign("thickness", thickness);
    o.insert_or_assign("angle", tube.angle);
    surface.write(o);
    if (history.empty())
      o.insert_or_assign("velocity", toml::array{velocity.x(), velocity.y(), velocity.z()});
    else
      o.insert_or_assign("velocity_history", velocity_history_rows(history));
    out.push_back(std::move(o));
  }
}

}  // namespace femdem::scene

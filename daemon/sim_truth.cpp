#include "daemon/sim_truth.hpp"

#include "drivers/sim/cone_geometry.hpp"
#include "drivers/sim/virtual_car.hpp"

namespace fsd {

web::TruthState truth_state(const sim::VirtualCar& car) {
  const sim::VehicleTruth& t = car.truth();
  web::TruthState s;
  s.t = t.t;
  s.pose = t.pose;
  s.speed = t.speed();
  s.vx = t.vx;
  s.vy = t.vy;
  s.yaw_rate = t.yaw_rate;
  s.ax = t.ax;
  s.ay = t.ay;
  s.sideslip = t.sideslip();
  s.steering = t.steering;
  s.cones_hit = car.cones_hit();
  return s;
}

std::vector<web::TruthCone> truth_cones(const sim::World& world) {
  std::vector<web::TruthCone> out;
  out.reserve(world.cones().size());
  for (const auto& c : world.cones()) {
    const sim::ConeShape& shape = sim::cone_shape(c.big);
    web::TruthCone k;
    k.colour = c.colour;
    k.base_width = 2 * shape.base_radius;
    k.top_width = 2 * shape.top_radius;
    k.height = shape.height;
    k.knocked = c.knocked;
    k.base = world.cone_pose(c);  // the world's own placement, upright or fallen
    out.push_back(k);
  }
  return out;
}

}  // namespace fsd

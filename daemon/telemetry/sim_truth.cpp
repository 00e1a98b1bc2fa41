#include "daemon/telemetry/sim_truth.hpp"

#include "drivers/sim/virtual_car.hpp"
#include "drivers/sim/world/cone_geometry.hpp"

namespace fsd {

web::TruthState truth_state(const sim::VirtualCar& car) { return truth_state(car.truth(), car.cones_hit()); }

web::TruthState truth_state(const sim::VehicleTruth& t, int cones_hit) {
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
  s.cones_hit = cones_hit;
  return s;
}

std::vector<web::TruthCone> truth_cones(const std::vector<Cone>& standing) {
  std::vector<web::TruthCone> out;
  out.reserve(standing.size());
  for (const auto& c : standing) {
    const sim::ConeShape& shape = sim::cone_shape(c.colour == ConeColour::BigOrange);
    web::TruthCone k;
    k.colour = c.colour;
    k.base_width = 2 * shape.base_radius;
    k.top_width = 2 * shape.top_radius;
    k.height = shape.height;
    k.base = Pose3::Identity();
    k.base.translation() = c.position;
    out.push_back(k);
  }
  return out;
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

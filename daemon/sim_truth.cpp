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
  // The same placement as the world's bodies (World::cone_body): upright along the ground normal, or tilted
  // so that one side lies on the ground with the tip towards fall_yaw.
  const Eigen::Matrix3d ground = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), world.ground_normal()).toRotationMatrix();
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
    k.base.linear() = c.knocked ? Eigen::Matrix3d(ground * sim::lying_cone_rotation(shape, c.fall_yaw)) : ground;
    k.base.translation() = c.knocked ? Vec3(c.base + world.ground_normal() * sim::lying_cone_axis_height(shape)) : c.base;
    out.push_back(k);
  }
  return out;
}

}  // namespace fsd

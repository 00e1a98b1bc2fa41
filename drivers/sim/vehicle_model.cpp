#include "drivers/sim/vehicle_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "drivers/sim/vehicle_forces.hpp"
#include "drivers/sim/vehicle_tyre.hpp"

namespace fsd::sim {

namespace {

using State = VehicleModel::State;

constexpr double kMaxSubstep = 0.005;  // s: RK4 is well inside its stability limit for the tyre modes here
constexpr double kKinematicRelaxation = 0.02;  // s: how fast the kinematic model pulls vy and yaw rate onto it

State operator+(const State& a, const State& b) {
  return {a.x + b.x, a.y + b.y, a.yaw + b.yaw, a.vx + b.vx, a.vy + b.vy, a.yaw_rate + b.yaw_rate,
          a.distance + b.distance};
}
State operator*(double k, const State& a) {
  return {k * a.x, k * a.y, k * a.yaw, k * a.vx, k * a.vy, k * a.yaw_rate, k * a.distance};
}

// Held over one step: the wheel angle, the VCU's force requests and the lagged acceleration for load transfer.
struct Inputs {
  double steering = 0;
  LongitudinalRequest request;
  double ax_lagged = 0;
};

struct Derivative {
  State d;
  double drive_applied = 0;  // N at the ground after the tyre limit
  double brake_applied = 0;  // N at the ground after the tyre limit
};

// Weight of the dynamic model: 0 at and below kinematic_speed, 1 at and above dynamic_speed.
double dynamic_weight(const VehicleParams& p, double vx) {
  return std::clamp((vx - p.kinematic_speed) / (p.dynamic_speed - p.kinematic_speed), 0.0, 1.0);
}

MagicFormula front_tyre(const VehicleParams& p) { return {p.tyre_front_b, p.tyre_front_c, p.tyre_front_e}; }
MagicFormula rear_tyre(const VehicleParams& p) { return {p.tyre_rear_b, p.tyre_rear_c, p.tyre_rear_e}; }

// Dynamic single-track model at the CoG (valid for vx well above 0): returns dvx, dvy, dr and applied forces.
Derivative dynamic_model(const VehicleParams& p, const State& s, const Inputs& u, const AxleLoads& fz,
                         double fx_front_demand, double fx_rear_demand) {
  const double lr = p.cog_to_rear_axle, lf = p.cog_to_front_axle();
  const double alpha_front = u.steering - std::atan2(s.vy + lf * s.yaw_rate, s.vx);
  const double alpha_rear = -std::atan2(s.vy - lr * s.yaw_rate, s.vx);
  const double front_limit = p.mu * fz.front, rear_limit = p.mu * fz.rear;
  const AxleForce front = friction_circle(fx_front_demand, lateral_force(front_tyre(p), alpha_front, front_limit),
                                          front_limit);
  const AxleForce rear = friction_circle(fx_rear_demand, lateral_force(rear_tyre(p), alpha_rear, rear_limit),
                                         rear_limit);
  const double c = std::cos(u.steering), sn = std::sin(u.steering);
  const double fx = rear.fx + front.fx * c - front.fy * sn - drag_force(p, s.vx) - rolling_resistance_force(p);
  const double fy = rear.fy + front.fx * sn + front.fy * c;
  const double mz = lf * (front.fy * c + front.fx * sn) - lr * rear.fy;
  Derivative out;
  out.d.vx = fx / p.mass + s.yaw_rate * s.vy;
  out.d.vy = fy / p.mass - s.yaw_rate * s.vx;
  out.d.yaw_rate = mz / p.yaw_inertia;
  out.drive_applied = std::max(rear.fx, 0.0);
  out.brake_applied = -front.fx - std::min(rear.fx, 0.0);
  return out;
}

// Kinematic single-track model: the rear axle rolls without side slip and the yaw rate is vx·tan δ / L; vy and
// the yaw rate relax onto it. Brakes and rolling resistance hold the car at standstill; it never rolls backwards.
Derivative kinematic_model(const VehicleParams& p, const State& s, const Inputs& u, const AxleLoads& fz,
                           double fx_front_demand, double fx_rear_demand) {
  const double front = std::clamp(fx_front_demand, -p.mu * fz.front, p.mu * fz.front);
  const double rear = std::clamp(fx_rear_demand, -p.mu * fz.rear, p.mu * fz.rear);
  Derivative out;
  out.drive_applied = std::max(rear, 0.0);
  out.brake_applied = -front - std::min(rear, 0.0);
  const double net = out.drive_applied - drag_force(p, s.vx) - out.brake_applied - rolling_resistance_force(p);
  const double force = s.vx > 0.0 ? net : std::max(net, 0.0);
  const double tan_delta = std::tan(u.steering);
  const double curvature = tan_delta / p.wheelbase;
  const double yaw_rate_kin = s.vx * curvature;
  const double vy_kin = p.cog_to_rear_axle * yaw_rate_kin;
  out.d.vx = force / p.mass;
  out.d.yaw_rate = out.d.vx * curvature + (yaw_rate_kin - s.yaw_rate) / kKinematicRelaxation;
  out.d.vy = p.cog_to_rear_axle * out.d.vx * curvature + (vy_kin - s.vy) / kKinematicRelaxation;
  return out;
}

Derivative derivative(const VehicleParams& p, const State& s, const Inputs& u) {
  const AxleLoads fz = axle_loads(p, s.vx, u.ax_lagged);
  const double fx_front_demand = -p.brake_front_share * u.request.brake;
  const double fx_rear_demand = u.request.drive - (1.0 - p.brake_front_share) * u.request.brake;

  const double w = dynamic_weight(p, s.vx);
  Derivative out;
  if (w > 0.0) {
    const Derivative dyn = dynamic_model(p, s, u, fz, fx_front_demand, fx_rear_demand);
    out.d = w * dyn.d;
    out.drive_applied = w * dyn.drive_applied;
    out.brake_applied = w * dyn.brake_applied;
  }
  if (w < 1.0) {
    const Derivative kin = kinematic_model(p, s, u, fz, fx_front_demand, fx_rear_demand);
    out.d = out.d + (1.0 - w) * kin.d;
    out.drive_applied += (1.0 - w) * kin.drive_applied;
    out.brake_applied += (1.0 - w) * kin.brake_applied;
  }
  // Pose of the rear axle: its velocity is the CoG's minus the yaw rate times the lever arm.
  const double vy_rear = s.vy - p.cog_to_rear_axle * s.yaw_rate;
  const double c = std::cos(s.yaw), sn = std::sin(s.yaw);
  out.d.x = s.vx * c - vy_rear * sn;
  out.d.y = s.vx * sn + vy_rear * c;
  out.d.yaw = s.yaw_rate;
  out.d.distance = std::hypot(s.vx, vy_rear);
  return out;
}

}  // namespace

VehicleModel::VehicleModel(const VehicleParams& p) : p_(p), steering_(p), vcu_(p) {
  if (const std::string why = validate(p); !why.empty()) throw std::invalid_argument("sim.vehicle: " + why);
  reset(Pose2{});
}

void VehicleModel::reset(const Pose2& rear_axle_pose, double speed, Stamp t) {
  s_ = State{};
  s_.x = rear_axle_pose.x;
  s_.y = rear_axle_pose.y;
  s_.yaw = wrap_angle(rear_axle_pose.yaw);
  s_.vx = std::isfinite(speed) ? std::clamp(speed, 0.0, p_.max_speed) : 0.0;
  t_ = t;
  ax_lagged_ = ay_lagged_ = 0;
  steering_.reset();
  vcu_.reset();
  update_truth(0.0, 0.0, 0.0, 0.0);
}

void VehicleModel::step(double dt, const ActuatorCommand& cmd) {
  if (!(dt > 0.0 && dt <= 1.0)) {
    ++rejected_steps_;
    return;
  }
  const int n = std::max(1, static_cast<int>(std::ceil(dt / kMaxSubstep - 1e-9)));
  const double h = dt / n;
  for (int i = 0; i < n; ++i) substep(h, cmd);
}

void VehicleModel::substep(double dt, const ActuatorCommand& cmd) {
  Inputs u;
  u.steering = steering_.step(t_, dt, cmd.steering);
  const AxleLoads fz = axle_loads(p_, s_.vx, ax_lagged_);
  u.request = vcu_.step(dt, cmd, s_.vx, {p_.mu * fz.rear, p_.mu * (fz.front + fz.rear)});
  u.ax_lagged = ax_lagged_;

  const State k1 = derivative(p_, s_, u).d;
  const State k2 = derivative(p_, s_ + (0.5 * dt) * k1, u).d;
  const State k3 = derivative(p_, s_ + (0.5 * dt) * k2, u).d;
  const State k4 = derivative(p_, s_ + dt * k3, u).d;
  s_ = s_ + (dt / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  s_.yaw = wrap_angle(s_.yaw);
  t_ += dt;

  // No reverse gear: a car braked to a stop stays stopped, and standing still it neither yaws nor slides.
  if (s_.vx <= 0.0) {
    s_.vx = s_.vy = s_.yaw_rate = 0.0;
  }

  // Accelerations at the end of the step, as an IMU at the CoG measures them (body frame, with centripetal).
  const Derivative end = derivative(p_, s_, u);
  const double ax = end.d.vx - s_.yaw_rate * s_.vy;
  const double ay = end.d.vy + s_.yaw_rate * s_.vx;
  const double tau = p_.load_transfer_time_constant;
  const double follow = dt / (tau + dt);
  ax_lagged_ += follow * (ax - ax_lagged_);
  ay_lagged_ += follow * (ay - ay_lagged_);
  update_truth(end.drive_applied, end.brake_applied, ax, ay);
}

void VehicleModel::update_truth(double drive_applied, double brake_applied, double ax, double ay) {
  VehicleTruth& tr = truth_;
  tr.t = t_;
  tr.pose = Pose2{s_.x, s_.y, s_.yaw};
  tr.vx = s_.vx;
  tr.vy = s_.vy;
  tr.yaw_rate = s_.yaw_rate;
  tr.ax = ax;
  tr.ay = ay;
  // Load transfer tilts the sprung body: braking (ax < 0) pitches the nose down (+), a left turn (ay > 0) rolls
  // the body to the right (+). The CoG height is the lever arm (roll and pitch centres on the ground).
  tr.pitch = -p_.mass * ax_lagged_ * p_.cog_height / p_.pitch_stiffness;
  tr.roll = p_.mass * ay_lagged_ * p_.cog_height / p_.roll_stiffness;
  tr.steering = steering_.angle();
  // Wheels roll without slip at their contact patch's speed along the wheel (traction control and ABS).
  const double half_track = 0.5 * p_.track_width;
  const double vy_rear = s_.vy - p_.cog_to_rear_axle * s_.yaw_rate;
  const double c = std::cos(tr.steering), sn = std::sin(tr.steering);
  const double vy_front = vy_rear + p_.wheelbase * s_.yaw_rate;
  auto front_wheel = [&](double y) { return (s_.vx - s_.yaw_rate * y) * c + vy_front * sn; };
  tr.wheel_speeds = {front_wheel(half_track), front_wheel(-half_track), s_.vx - s_.yaw_rate * half_track,
                     s_.vx + s_.yaw_rate * half_track};
  tr.motor_torque = drive_applied * p_.wheel_radius;
  tr.brake_force = brake_applied;
  tr.distance = s_.distance;
}

std::array<Vec2, 4> VehicleModel::footprint() const {
  const double rear = -p_.rear_overhang, front = p_.body_length - p_.rear_overhang, half = 0.5 * p_.body_width;
  const Pose2 pose{s_.x, s_.y, s_.yaw};
  return {pose.transform({rear, -half}), pose.transform({front, -half}), pose.transform({front, half}),
          pose.transform({rear, half})};
}

}  // namespace fsd::sim

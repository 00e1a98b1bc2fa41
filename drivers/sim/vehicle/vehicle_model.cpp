#include "drivers/sim/vehicle/vehicle_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "drivers/sim/vehicle/vehicle_forces.hpp"
#include "drivers/sim/vehicle/vehicle_tyre.hpp"

namespace fsd::sim {

namespace {

using State = VehicleModel::State;

constexpr double kMaxSubstep = 0.005;          // s: RK4 is well inside its stability limit for the tyre modes here
constexpr double kKinematicRelaxation = 0.02;  // s: how fast the kinematic model pulls vy and yaw rate onto it

State operator+(const State& a, const State& b) {
  return {
      a.x + b.x, a.y + b.y, a.yaw + b.yaw, a.vx + b.vx, a.vy + b.vy, a.yaw_rate + b.yaw_rate, a.distance + b.distance};
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
  double drive_applied = 0;         // N at the ground after the tyre limit
  double brake_applied = 0;         // N at the ground after the tyre limit
  double kinematic_resistance = 0;  // N, brakes and rolling resistance of the kinematic model's share
};

// How the kinematic model's brakes and rolling resistance enter: they act like dry friction (oppose the motion,
// hold the car up to their full force at a standstill), which a Runge-Kutta step cannot integrate across zero
// speed. The step therefore integrates without them and applies their impulse afterwards (Excluded); the
// accelerometer reading includes them (Included).
enum class Resistance { Excluded, Included };

// Weight of the dynamic model by the CoG speed: 0 at and below kinematic_speed, 1 at and above dynamic_speed.
double dynamic_weight(const VehicleParams& p, const State& s) {
  const double speed = std::hypot(s.vx, s.vy);
  return std::clamp((speed - p.kinematic_speed) / (p.dynamic_speed - p.kinematic_speed), 0.0, 1.0);
}

// Direction a resistive force (brake, rolling resistance) opposes: the sign of the rolling speed, smoothed
// over ±0.2 m/s so that a wheel sliding sideways does not chatter.
double rolling_direction(double u) { return std::clamp(u / 0.2, -1.0, 1.0); }

MagicFormula front_tyre(const VehicleParams& p) { return {p.tyre_front_b, p.tyre_front_c, p.tyre_front_e}; }
MagicFormula rear_tyre(const VehicleParams& p) { return {p.tyre_rear_b, p.tyre_rear_c, p.tyre_rear_e}; }

// Dynamic single-track model at the CoG: Pacejka lateral forces from the slip angles, the longitudinal forces
// in the wheel frames, each axle on its friction circle. Holds for any direction of motion at speed (a spin).
Derivative dynamic_model(const VehicleParams& p, const State& s, const Inputs& u, const AxleLoads& fz) {
  const double lr = p.cog_to_rear_axle, lf = p.cog_to_front_axle();
  const double c = std::cos(u.steering), sn = std::sin(u.steering);
  // Contact patch velocities in the wheel frames.
  const double vy_front = s.vy + lf * s.yaw_rate, vy_rear = s.vy - lr * s.yaw_rate;
  const double u_front = s.vx * c + vy_front * sn, w_front = -s.vx * sn + vy_front * c;
  const double u_rear = s.vx;

  const double brake_front = p.brake_front_share * u.request.brake;
  const double brake_rear = u.request.brake - brake_front;
  const double fx_front_demand = -brake_front * rolling_direction(u_front);
  const double fx_rear_demand = u.request.drive - brake_rear * rolling_direction(u_rear);
  const double front_limit = p.mu * fz.front, rear_limit = p.mu * fz.rear;
  const double fy_front_tyre = lateral_force(front_tyre(p), slip_angle(u_front, w_front), front_limit);
  const double fy_rear_tyre = lateral_force(rear_tyre(p), slip_angle(u_rear, vy_rear), rear_limit);
  const double k_front = friction_circle_scale(fx_front_demand, fy_front_tyre, front_limit);
  const double k_rear = friction_circle_scale(fx_rear_demand, fy_rear_tyre, rear_limit);
  const double fx_front = k_front * fx_front_demand, fy_front = k_front * fy_front_tyre;
  const double fx_rear = k_rear * fx_rear_demand, fy_rear = k_rear * fy_rear_tyre;

  const double resist = drag_force(p, s.vx) + rolling_resistance_force(p) * rolling_direction(s.vx);
  const double fx = fx_rear + fx_front * c - fy_front * sn - resist;
  const double fy = fy_rear + fx_front * sn + fy_front * c;
  const double mz = lf * (fy_front * c + fx_front * sn) - lr * fy_rear;
  Derivative out;
  out.d.vx = fx / p.mass + s.yaw_rate * s.vy;
  out.d.vy = fy / p.mass - s.yaw_rate * s.vx;
  out.d.yaw_rate = mz / p.yaw_inertia;
  out.drive_applied = k_rear * u.request.drive;
  out.brake_applied = k_front * brake_front + k_rear * brake_rear;
  return out;
}

// Kinematic single-track model: the rear axle rolls without side slip and the yaw rate is vx·tan δ / L; vy and
// the yaw rate relax onto it. The accelerations this asks of the tyres stay inside the friction circle, so a car
// still sliding after a spin slows its sideways motion no faster than the tyres allow.
Derivative kinematic_model(const VehicleParams& p, const State& s, const Inputs& u, const AxleLoads& fz,
                           Resistance mode) {
  const double brake_front = p.brake_front_share * u.request.brake;
  const double front = std::min(brake_front, p.mu * fz.front);
  const double rear = std::clamp(u.request.drive - (u.request.brake - brake_front), -p.mu * fz.rear, p.mu * fz.rear);
  Derivative out;
  out.drive_applied = std::max(rear, 0.0);
  out.brake_applied = front - std::min(rear, 0.0);
  // Brakes and rolling resistance oppose the motion and, standing, hold up to their full force.
  const double propulsion = out.drive_applied - drag_force(p, s.vx);
  const double resistance = out.brake_applied + rolling_resistance_force(p);
  const double longitudinal = s.vx > 0.0   ? propulsion - resistance
                              : s.vx < 0.0 ? propulsion + resistance
                                           : std::max(propulsion - resistance, 0.0);
  out.kinematic_resistance = resistance;

  const double curvature = std::tan(u.steering) / p.wheelbase;
  const double yaw_rate_kin = s.vx * curvature;
  const double vy_kin = p.cog_to_rear_axle * yaw_rate_kin;
  const double grip = p.mu * kGravity;
  const double lateral_grip = std::sqrt(std::max(grip * grip - std::pow(longitudinal / p.mass, 2), 0.0));
  const double yaw_grip = grip * p.mass * std::max(p.cog_to_rear_axle, p.cog_to_front_axle()) / p.yaw_inertia;
  // Body-frame derivatives hold the rotation terms (as in the dynamic model) only for the part of the motion the
  // kinematic model does not explain, so that on its own path the model is exactly kinematic.
  const double force = mode == Resistance::Included ? longitudinal : propulsion;
  out.d.vx = force / p.mass + s.yaw_rate * (s.vy - vy_kin);
  const double lateral_wanted =
      p.cog_to_rear_axle * out.d.vx * curvature + (vy_kin - s.vy) / kKinematicRelaxation + s.yaw_rate * s.vx;
  out.d.vy = std::clamp(lateral_wanted, -lateral_grip, lateral_grip) - s.yaw_rate * s.vx;
  out.d.yaw_rate =
      out.d.vx * curvature + std::clamp((yaw_rate_kin - s.yaw_rate) / kKinematicRelaxation, -yaw_grip, yaw_grip);
  return out;
}

Derivative derivative(const VehicleParams& p, const State& s, const Inputs& u, Resistance mode) {
  const AxleLoads fz = axle_loads(p, s.vx, u.ax_lagged);
  const double w = dynamic_weight(p, s);
  Derivative out;
  if (w > 0.0) {
    const Derivative dyn = dynamic_model(p, s, u, fz);
    out.d = w * dyn.d;
    out.drive_applied = w * dyn.drive_applied;
    out.brake_applied = w * dyn.brake_applied;
  }
  if (w < 1.0) {
    const Derivative kin = kinematic_model(p, s, u, fz, mode);
    out.d = out.d + (1.0 - w) * kin.d;
    out.kinematic_resistance = (1.0 - w) * kin.kinematic_resistance;
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

  constexpr auto kWithout = Resistance::Excluded;
  const double vx_before = s_.vx;
  const Derivative start = derivative(p_, s_, u, kWithout);
  const State& k1 = start.d;
  const State k2 = derivative(p_, s_ + (0.5 * dt) * k1, u, kWithout).d;
  const State k3 = derivative(p_, s_ + (0.5 * dt) * k2, u, kWithout).d;
  const State k4 = derivative(p_, s_ + dt * k3, u, kWithout).d;
  s_ = s_ + (dt / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  s_.yaw = wrap_angle(s_.yaw);
  t_ += dt;

  // The kinematic share of brakes and rolling resistance as dry friction: it slows the car by at most its
  // impulse and never pushes it through zero speed, so a braked car stops exactly and a stopped car stays (no
  // reverse gear, flat ground). Sideways motion left over from a slide decays in the kinematic model; below a
  // trace it is zeroed so that a stopped car stands exactly still.
  const double impulse = dt * start.kinematic_resistance / p_.mass;
  if (impulse > 0.0) {
    const double v = std::abs(s_.vx);
    // Distance the friction took off the step, which the Runge-Kutta step ran without it: ½·Δv·dt while still
    // rolling, v·dt − v²/2a when it stopped within the step.
    double lost = 0.0;
    if (v <= impulse) {
      lost = v * dt - v * v * dt / (2.0 * impulse);
      s_.vx = 0.0;
      constexpr double kAtRest = 1e-3;  // m/s and rad/s
      if (std::abs(s_.vy) < kAtRest && std::abs(s_.yaw_rate) < kAtRest) s_.vy = s_.yaw_rate = 0.0;
    } else {
      lost = 0.5 * impulse * dt;
      s_.vx -= std::copysign(impulse, s_.vx);
    }
    s_.x -= std::copysign(lost, vx_before) * std::cos(s_.yaw);
    s_.y -= std::copysign(lost, vx_before) * std::sin(s_.yaw);
    s_.distance -= lost;
  }

  // Accelerations at the end of the step, as an IMU at the CoG measures them (body frame, with centripetal).
  const Derivative end = derivative(p_, s_, u, Resistance::Included);
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

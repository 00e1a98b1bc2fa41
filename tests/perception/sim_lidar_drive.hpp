#pragma once
// Scans as the virtual car's VLP-16 renders them while the car drives round a track's true centre line at constant
// speed (a kinematic bicycle steered onto it), decoded by the real Vlp16ScanBuilder, with the true body pose at any
// time and the world's true cones: the independent truth of the LiDAR perception and odometry tests.
#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/track.hpp"
#include "common/types.hpp"
#include "drivers/sim/sensors/lidar_model.hpp"
#include "drivers/sim/world/reference_line.hpp"
#include "drivers/sim/world/world.hpp"
#include "drivers/vlp16/config.hpp"
#include "drivers/vlp16/scan_builder.hpp"

namespace fsd::test {

// Body pose (map ← body, rear axle on the ground) of a car driving round a closed polyline at constant speed from arc
// length s0: a kinematic bicycle with the virtual car's wheelbase, steering lock and steering rate, steered onto the
// line by pure pursuit and integrated at 1 kHz as far as it is asked. Its yaw turns as a car's does, never in the
// steps the polyline's kinks would give a pose taken off the line itself.
class CarDrive {
 public:
  static constexpr double kWheelbase = 1.53, kLock = 0.5, kSteerRate = 1.2;  // m, rad, rad/s (car.*)
  static constexpr double kDt = 1e-3;                                         // s

  CarDrive(std::vector<Vec2> line, double speed, double s0) : line_(std::move(line)), speed_(speed) {
    s_.push_back(0);
    for (std::size_t i = 0; i < line_.size(); ++i)
      s_.push_back(s_.back() + (line_[(i + 1) % line_.size()] - line_[i]).norm());
    const Vec2 p = at(s0), d = at(s0 + 1.0) - at(s0 - 1.0);
    state_ = {p.x(), p.y(), std::atan2(d.y(), d.x()), 0.0, s0};
    poses_.push_back(pose(state_));
  }
  // The line's point `s` metres along it (wrapping).
  Vec2 at(double s) const {
    s = std::fmod(std::fmod(s, s_.back()) + s_.back(), s_.back());
    std::size_t i = 0;
    while (s_[i + 1] < s) ++i;
    const Vec2 a = line_[i], b = line_[(i + 1) % line_.size()];
    const double f = (s - s_[i]) / std::max(1e-9, s_[i + 1] - s_[i]);
    return a + f * (b - a);
  }
  Pose3 operator()(Stamp t) const {
    const double k = std::max(0.0, t) / kDt;
    const auto i = static_cast<std::size_t>(k);
    while (poses_.size() < i + 2) {
      step();
      poses_.push_back(pose(state_));
    }
    const Pose2 &a = poses_[i], &b = poses_[i + 1];
    const double f = k - static_cast<double>(i);
    return Pose2{a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), a.yaw + f * wrap_angle(b.yaw - a.yaw)}.to_pose3();
  }
  double length() const { return s_.back(); }

 private:
  struct State {
    double x, y, yaw, steer, s;  // s: arc length of the line's point nearest the car
  };
  static Pose2 pose(const State& q) { return {q.x, q.y, q.yaw}; }
  void step() const {
    State& q = state_;
    const Vec2 p(q.x, q.y);
    // The nearest point of the line, looked for a little ahead of the last.
    double best = (at(q.s) - p).squaredNorm();
    for (double ds = 0.05; ds < 2.0; ds += 0.05)
      if (const double d = (at(q.s + ds) - p).squaredNorm(); d < best) best = d, q.s += ds, ds = 0.0;
    const double lookahead = std::max(3.0, 0.3 * speed_);
    const Vec2 g = at(q.s + lookahead) - p;
    const double alpha = wrap_angle(std::atan2(g.y(), g.x()) - q.yaw);
    const double want = std::clamp(std::atan(2 * kWheelbase * std::sin(alpha) / g.norm()), -kLock, kLock);
    q.steer += std::clamp(want - q.steer, -kSteerRate * kDt, kSteerRate * kDt);
    q.x += speed_ * std::cos(q.yaw) * kDt;
    q.y += speed_ * std::sin(q.yaw) * kDt;
    q.yaw = wrap_angle(q.yaw + speed_ / kWheelbase * std::tan(q.steer) * kDt);
  }

  std::vector<Vec2> line_;
  std::vector<double> s_;
  double speed_;
  mutable State state_{};
  mutable std::vector<Pose2> poses_;  // every kDt from t = 0
};

struct SimLidarSetup {
  std::string track = "../shared/tracks/epfl_track_1.csv";
  sim::WorldConfig world;       // distractors on by default
  sim::LidarConfig lidar;       // the virtual car's mount by default
  double speed = 8.0;           // m/s
  double start_fraction = 0.0;  // where on the lap the drive starts
  std::uint64_t seed = 1;
};

// Renders scan after scan; the first (partial) revolution is skipped.
class SimLidarDrive {
 public:
  explicit SimLidarDrive(const SimLidarSetup& setup)
      : setup_(setup),
        track_(load_track(setup.track)),
        world_(track_, setup.world, setup.seed),
        drive_(sim::ReferenceLine(track_).points(), setup.speed,
               setup.start_fraction * sim::ReferenceLine(track_).length()),
        lidar_(setup.lidar, world_, setup.seed) {
    Vlp16Config vc;
    vc.mount = {setup.lidar.x, setup.lidar.y, setup.lidar.z, setup.lidar.roll, setup.lidar.pitch, setup.lidar.yaw};
    mount_ = vc.body_from_sensor();
    builder_ = std::make_unique<Vlp16ScanBuilder>(vc, [this](Scan&& s) {
      if (++emitted_ > 1) scans_.push_back(std::move(s));
    });
  }

  Scan next() {
    while (scans_.empty()) {
      t_ += 0.01;
      lidar_.advance_to(t_, std::cref(drive_),
                        [this](Stamp t, std::span<const std::uint8_t> p) { builder_->on_data_packet(t, p); });
    }
    Scan s = std::move(scans_.front());
    scans_.pop_front();
    return s;
  }

  Pose3 body_pose(Stamp t) const { return drive_(t); }
  const Pose3& mount() const { return mount_; }  // body ← sensor
  const sim::World& world() const { return world_; }
  const Track& track() const { return track_; }
  const CarDrive& drive() const { return drive_; }
  // The standing cones in the map frame with their true colours.
  std::vector<Cone> true_cones() const {
    std::vector<Cone> out;
    for (const auto& c : world_.cones()) {
      if (c.knocked) continue;
      Cone k;
      k.position = c.base;
      k.colour = c.colour;
      out.push_back(k);
    }
    return out;
  }

 private:
  SimLidarSetup setup_;
  Track track_;
  sim::World world_;
  CarDrive drive_;
  sim::LidarModel lidar_;
  Pose3 mount_;
  std::unique_ptr<Vlp16ScanBuilder> builder_;
  std::deque<Scan> scans_;
  int emitted_ = 0;
  Stamp t_ = 0;
};

}  // namespace fsd::test

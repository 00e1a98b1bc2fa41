#include "daemon/scoring/sim_scoring.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "control/missions/missions.hpp"
#include "daemon/scoring/map_score.hpp"
#include "daemon/stack/stack.hpp"

namespace fsd {

double stop_zone(Mission m) {
  switch (m) {
    case Mission::Trackdrive:
    case Mission::Autocross:
    case Mission::Skidpad:
      return 30.0;
    default:
      return 100.0;
  }
}

VehicleState state_from_truth(const sim::VehicleTruth& t) {
  VehicleState s;
  s.stamp = t.t;
  s.pose = t.pose;
  s.vx = t.vx;
  s.vy = t.vy;
  s.yaw_rate = t.yaw_rate;
  s.ax = t.ax;
  s.ay = t.ay;
  s.steering = t.steering;
  return s;
}

sim::VehicleTruth truth_from_state(const VehicleState& s) {
  sim::VehicleTruth t;
  t.t = s.stamp;
  t.pose = s.pose;
  t.vx = s.vx;
  t.vy = s.vy;
  t.yaw_rate = s.yaw_rate;
  t.ax = s.ax;
  t.ay = s.ay;
  t.steering = s.steering;
  return t;
}

SimScoring::SimScoring(const Track& track, Mission mission, const RunSettings& run, Stack& stack)
    : track_(track), run_(run), stack_(stack) {
  card_ = std::make_unique<Scorecard>(track, mission, timed_laps(mission, run.laps), stop_zone(mission), run.seed);
  // The limits the stack plans with (the scorecard's "vehicle" object).
  const SpeedConfig& sp = stack.autopilot().config().speed;
  card_->set_vehicle_limits({sp.mu, sp.a_accel_max, sp.a_brake_max, sp.v_max});
  // Scored against the true pose at the detections' instant, not the one the stack placed them by.
  stack.on_detections([this](const ConeDetections& det, const Pose2&) {
    const Pose2 pose = truth_poses_.at(det.stamp).value_or(last_pose_);
    if (!visibility_.known()) {
      perception_.add_frame(det, truth_cones_, pose);
      return;
    }
    const auto visible = visibility_.visible_at(det.stamp);
    perception_.add_frame(det, truth_cones_, pose, &visible);
  });
  // Each loop closure with the pose's error against the truth at its instant, before and after the correction.
  stack.on_loop_closure([this](const LoopClosureRecord& r) {
    // (PoseHistory::at clamps to its oldest pose: a late solve was scored against a pose of seconds later.)
    const PoseHistory* history = truth_poses_.reaches_back_to(r.t)   ? &truth_poses_
                                 : truth_track_.reaches_back_to(r.t) ? &truth_track_
                                                                     : nullptr;
    const auto truth = history ? history->at(r.t) : std::nullopt;
    if (!truth) {  // older than two minutes of simulated time: no figure rather than a wrong one
      loop_closures_.push_back({r, std::nan(""), std::nan("")});
      return;
    }
    const Vec2 p = truth->position();
    loop_closures_.push_back(
        {r, (r.estimate.position() - p).norm(), ((r.correction * r.estimate).position() - p).norm()});
  });
  stack.on_odometry([this](const lidar_odometry::OdometryOutput& out) {
    odometry_.add_lidar(truth_poses_.at(out.stamp).value_or(last_pose_), to_pose2(out.pose));
  });
}

void SimScoring::on_truth(const sim::VehicleTruth& truth) {
  truth_poses_.add(truth.t, truth.pose);
  if (const auto newest = truth_track_.newest(); !newest || truth.t - *newest >= 0.05)
    truth_track_.add(truth.t, truth.pose);
  last_pose_ = truth.pose;
  card_->on_truth(truth);
}

namespace {

nlohmann::json map_section(const Track& track, const std::vector<Cone>& map, const RunSettings& run) {
  auto out = to_json(score_map(track.cones, map));
  out["source"] = run.perception_source;
  out["localization_source"] = run.localization_source;
  return out;
}

}  // namespace

void SimScoring::after_step(AsState as, int cones_hit) {
  card_->set_as_state(as);
  card_->set_cones_hit(cones_hit);
  if (map_lap1_.is_null() && card_->laps_completed() >= 1) {
    map_lap1_ = map_section(track_, stack_.cone_map(), run_);
  }
  if (const auto& s = stack_.state()) {
    odometry_.add_state(truth_poses_.at(s->stamp).value_or(last_pose_), s->pose);
  }
}

void SimScoring::finish(double wall_time_s) {
  card_->set_wall_time(wall_time_s);
  card_->set_latencies(stack_.latencies());
  for (const auto& f : stack_.faults()) card_->add_fault(f);
  // Each section says where its figures came from (DESIGN.md §8): the sources the stack ran on.
  card_->set_section("map", map_section(track_, stack_.cone_map(), run_));
  if (!map_lap1_.is_null()) card_->set_section("map_lap1", map_lap1_);
  auto perception = perception_.to_json();
  perception["source"] = run_.perception_source;
  card_->set_section("perception", perception);
  auto odometry = odometry_.to_json(run_.localization_source);
  if (run_.localization_source == "lidar_odometry") {
    auto m = [](double v) { return std::round(v * 1e3) / 1e3; };  // 1 mm, 1 µs in ms
    odometry["loop_closures"] = nlohmann::json::array();
    for (const auto& [r, before, after] : loop_closures_)
      odometry["loop_closures"].push_back(
          {{"time_s", m(r.t)},
           {"lap", r.lap},
           {"correction", {{"x_m", m(r.correction.x)}, {"y_m", m(r.correction.y)}, {"yaw_rad", m(r.correction.yaw)}}},
           {"pairs", r.pairs},
           {"rms_m", m(r.rms)},
           {"keyframes", r.keyframes},
           {"cones_merged", r.cones_merged},
           {"solve_ms", m(r.solve_s * 1e3)},
           {"control_ms", m(r.control_s * 1e3)},
           {"error_before_m", m(before)},
           {"error_after_m", m(after)}});
  }
  card_->set_section("odometry", odometry);
}

}  // namespace fsd

#include "control/missions/mission_run.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

namespace fsd {

std::string to_string(const LapLineBuilt& l) {
  char buf[200];
  std::snprintf(
      buf, sizeof buf,
      "lap path built: %.1f m, closed within %.2f m, moved %.2f m (RMS) onto the centre line, the body at least %.2f m "
      "from every cone",
      l.length, l.closure_gap, l.recentre_rms, l.clearance);
  return buf;
}

std::string_view to_string(PathSource s) {
  switch (s) {
    case PathSource::None:
      return "none";
    case PathSource::Planner:
      return "planner";
    case PathSource::Recorded:
      return "recorded";
    case PathSource::Skidpad:
      return "skidpad";
    case PathSource::Straight:
      return "straight";
  }
  return "none";
}

void MissionRun::start(const MissionInput& in) {
  started_ = true;
  start_time_ = in.now;
  if (in.state) start_pose_ = in.state->pose;
}

void MissionRun::finish(const MissionInput& in, double stop_distance) {
  if (finished_) return;
  finished_ = true;
  finish_speed_ = in.state ? in.state->speed() : 0.0;
  finish_odometer_ = in.odometer;
  stop_distance_ = stop_distance;
}

double MissionRun::stop_cap(const MissionInput& in, double decel) const {
  if (!finished_) return std::numeric_limits<double>::infinity();
  return stop_speed(finish_speed_, in.odometer - finish_odometer_, decel, stop_distance_);
}

void MissionRun::limit(const MissionInput& in, ControlCommand& command) const {
  if (finished()) command.target_speed = std::min(command.target_speed, stop_cap(in, config_.mission.stop_decel));
}

}  // namespace fsd

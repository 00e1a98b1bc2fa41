#pragma once
// Trackdrive and autocross: lap 1 on the real-time planner's path, timed at the line; from shortly before the
// end of lap 1 (trackdrive only) the recorded lap-1 line, smoothed, recentred and profiled, followed on a good
// GNSS fix, with the real-time plan as the fallback. An open layout (its boundaries do not close) ends at its finish
// line (timing cones on both sides ahead, away from the start line) or, without one, where the planner's path runs
// out with no cone beyond: one run, then straight on to a stop.
#include <optional>
#include <vector>

#include "control/missions/lap_build_service.hpp"
#include "control/missions/lap_counter.hpp"
#include "control/missions/mission_run.hpp"
#include "control/planning/recorded_trajectory.hpp"

namespace fsd {

class TrackdriveMission final : public MissionRun {
 public:
  // `mission`: Trackdrive (control.mission.laps laps) or Autocross (one lap, no recorded lap).
  TrackdriveMission(const AutopilotConfig& config, Mission mission, ColourConvention convention);

  bool uses_planner() const override { return true; }
  // The stored lap's speeds follow the car's limits as they are tuned.
  void set_config(const AutopilotConfig& config) override;
  // The timing line from the timing cones ahead of the start (a line across the start pose without them).
  void start(const MissionInput& in) override;
  MissionPath update_path(const MissionInput& in) override;
  MissionEvents progress(const MissionInput& in, const FollowResult* follow) override;
  // The recorded lap-1 poses move with the correction; a lap path already built from them (or being built) is
  // dropped and built again from the moved poses (the real-time plan drives meanwhile).
  void relocate(const std::function<Pose2(Stamp)>& correction, Stamp now) override;

  // Lap 2's path built by `service` (which must outlive the mission) instead of inside progress(); null: inside.
  void set_lap_builder(LapBuildService* service) { lap_builder_ = service; }
  int target_laps() const;
  const Path* lap_path() const { return lap_path_ ? &*lap_path_ : nullptr; }
  bool open_end_seen() const { return run_out_.has_value(); }  // an open layout's end is in sight
  const LapCounter* lap_counter() const { return lap_counter_ ? &*lap_counter_ : nullptr; }

 private:
  // An open layout's end in the plan of this cycle: the plan, then straight on to a stop (run_out_). True when
  // found now.
  bool detect_open_end(const MissionInput& in);
  // Lap 1 on real-time plans, on a fresh view: when an open layout's end (or finish line) is looked for.
  bool watching_for_the_end(const MissionInput& in) const;
  // Whether what is in sight now has stayed so over open_end_confirm driven (`since`: where it came into sight).
  bool stayed_in_sight(bool in_sight, std::optional<double>& since, double odometer) const;
  bool open_end_in_sight(const MissionInput& in) const;  // this cycle's plan ends short with no cone beyond
  // An open layout's finish line on this cycle's plan: the plan to the line, then straight on to a stop (run_out_).
  // True when found now.
  bool detect_finish_line(const MissionInput& in);
  std::optional<TimingLine> finish_line_in_sight(const MissionInput& in) const;
  // run_out_: `path`, its end line at its last point, then straight on along `dir` to a stop.
  void run_out(const MissionInput& in, Path path, const Vec2& dir);
  SpeedLimits lap2_limits() const;
  // Lap 2's path from lap 1's poses up to t1 (and the plan `ahead` of an early build): built now, or handed to
  // the lap builder and taken by take_lap_build() once ready.
  void build_lap(const MissionInput& in, Stamp t1, std::vector<Vec2> ahead, MissionEvents& out);
  void take_lap_build(const MissionInput& in, MissionEvents& out);
  void use_lap_build(const MissionInput& in, const TrajectoryResult& built, MissionEvents& out);

  Mission mission_;
  ColourConvention convention_;
  RecordedTrajectory trajectory_;
  std::optional<LapCounter> lap_counter_;
  std::optional<Stamp> lap1_start_;  // lap 1's first crossing (or the start, when it began just past the line)
  std::optional<Stamp> lap1_end_;    // lap 1's last crossing, once it happened
  std::optional<Path> lap_path_;
  LapBuildService* lap_builder_ = nullptr;
  bool build_pending_ = false;            // a job is out with the lap builder
  bool pending_early_ = false;            // the pending build is the early one (before the line)
  bool discard_build_ = false;            // the pending build is from poses a loop closure has moved since
  bool rebuild_ = false;                  // the lap path was dropped by a loop closure: build it again
  std::optional<double> open_end_since_;  // odometer where the end came into sight, on every plan since
  std::optional<double> finish_since_;    // odometer where a finish line came into sight, on every plan since
  std::optional<Path> run_out_;           // open layout: the last plan, then straight on to a stop past the end line
  double open_end_s_ = 0;                 // arc length of the end line on run_out_
};

}  // namespace fsd

#pragma once
// The scorecard of a simulated run (DESIGN.md §8): what happened, measured against the virtual car's truth —
// laps by the timekeeper's gates, cross-track error against the true centre line, cones hit, the stop after the
// finish — plus the stack's own latencies and faults. Keys are a contract relied on by tests and CI.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/latency_stats.hpp"
#include "common/types.hpp"
#include "daemon/stack/fault_record.hpp"
#include "drivers/sim/vehicle/vehicle_truth.hpp"
#include "drivers/sim/world/reference_line.hpp"
#include "drivers/sim/world/timing_gates.hpp"

namespace fsd {

// Radius of the skid pad's driving circles: 18.25 m diameter by the Formula Student rules (the shared files' cones
// stand at 7.47-7.62 m inside and 10.6-10.8 m outside it).
inline constexpr double kSkidpadRadius = 9.125;

struct LapRecord {
  int lap = 0;
  double time_s = 0;
  double cte_rms_m = 0, cte_max_m = 0, v_max_m_s = 0;
};

struct VehicleLimits {
  double mu = 0, a_accel_max = 0, a_brake_max = 0, v_max = 0;
};

// The report's figures rounded to what they mean: milliseconds, millimetres, mm/s (docs/scorecard.md).
double milli(double v);

// {"<stage>": {"p50", "p99", "max" (ms), "n"}, ...}: the report's "latency_ms", on the car and in the simulator.
nlohmann::json latency_json(const std::map<std::string, LatencyStats>& stages);

class Scorecard {
 public:
  // `laps_to_finish`: timed laps of the mission (trackdrive N, autocross 1, acceleration 1, skid pad 4).
  // `stop_zone_m`: how far past the last timing line the car must come to rest.
  // An open layout (trackdrive or autocross on boundaries that do not close, docs/control.md) is one run: timed
  // from the car's first motion to the line across the last pair of boundary cones, whatever `laps_to_finish`.
  // The EBS test is over when the AS goes to Emergency after the start line; it must stop on the lane.
  Scorecard(const Track& track, Mission mission, int laps_to_finish, double stop_zone_m, int seed);

  // Called at every simulation step with the true state (monotonic time).
  void on_truth(const sim::VehicleTruth& truth);
  void set_as_state(AsState s) { as_state_ = s; }
  void set_cones_hit(int n) { cones_hit_ = n; }
  void add_fault(const FaultRecord& f) { faults_.push_back(f); }
  void set_vehicle_limits(const VehicleLimits& v) { limits_ = v; }
  void set_wall_time(double s) { wall_time_s_ = s; }
  // The stack's compute-time figures per stage (the "latency_ms" section).
  void set_latencies(const std::map<std::string, LatencyStats>& stages);
  // Extra sections measured elsewhere (map, perception, odometry).
  void set_section(const std::string& key, const nlohmann::json& value);

  bool finished() const { return finished_; }
  bool open_layout() const { return open_; }
  bool stopped_after_finish() const { return stopped_after_finish_; }
  int laps_completed() const { return static_cast<int>(laps_.size()); }
  const std::vector<LapRecord>& laps() const { return laps_; }
  // Success of the run as `fsd run` reports it in its exit status.
  bool mission_succeeded() const;
  // Why the run failed (empty: it passed): cones hit, not finished, no stop, the AS state; the report's "verdict".
  std::vector<std::string> failures() const;
  // A reason the stack gave that the figures do not show (e.g. "only one boundary found"); makes the verdict fail.
  void add_failure(const std::string& why) { extra_reasons_.push_back(why); }
  void clear_faults() { faults_.clear(); }
  nlohmann::json to_json() const;

 private:
  Track track_;
  Mission mission_;
  int laps_to_finish_;
  double stop_zone_m_;
  int seed_;
  sim::ReferenceLine ref_;
  sim::TimingGates gates_;
  bool open_ = false;
  bool start_past_line_ = false;  // the car stands just past a timing line: lap 1 from its first motion
  sim::Gate end_gate_;            // open layouts: across the last left and right boundary cones
  // Skid pad: its centre line is two circles (and the entry/exit axis), not a loop between the boundaries.
  std::vector<Vec2> skidpad_centres_;
  sim::Gate skidpad_gate_;
  double centre_distance(const Vec2& p) const;
  sim::Gate finish_;  // the gate the finish was crossed at
  double ebs_trigger_speed_ = 0;
  std::optional<Vec2> ebs_trigger_at_;
  double ebs_stop_distance_ = 0;
  std::optional<sim::VehicleTruth> last_;
  std::optional<Stamp> lap_start_;
  double cte_sq_ = 0, cte_max_ = 0, v_max_ = 0;
  std::size_t cte_n_ = 0;
  std::vector<LapRecord> laps_;
  bool finished_ = false, stopped_after_finish_ = false, left_stop_zone_ = false;
  double sim_time_ = 0, wall_time_s_ = 0;
  int cones_hit_ = 0;
  AsState as_state_ = AsState::Off;
  VehicleLimits limits_;
  std::vector<FaultRecord> faults_;
  std::vector<std::string> extra_reasons_;
  std::shared_ptr<const nlohmann::json> latency_ms_;
  std::map<std::string, std::shared_ptr<const nlohmann::json>> sections_;
};

}  // namespace fsd

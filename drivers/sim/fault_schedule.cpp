#include "drivers/sim/fault_schedule.hpp"

#include <cmath>
#include <limits>

namespace fsd::sim {

std::string_view to_string(FaultKind k) {
  switch (k) {
    case FaultKind::Gnss:
      return "gnss";
    case FaultKind::Lidar:
      return "lidar";
    case FaultKind::VcuLink:
      return "vcu_link";
    case FaultKind::PlannerStall:
      return "planner_stall";
    case FaultKind::Camera:
      return "camera";
  }
  return "?";
}

namespace {

// The three keys every fault has, under sim.faults.<name>.
template <class S>
ConfigSection<S> trigger_section(const std::string& name, const std::string& what, double default_duration) {
  S defaults;
  defaults.duration_s = default_duration;
  return ConfigSection<S>("sim.faults." + name, defaults)
      .integer("lap", &FaultTrigger::lap, 0, 1000, "",
               "Lap whose start " + what + " counts from (timekeeper's gates); 0: at_s is simulated time.")
      .number("at_s", &FaultTrigger::at_s, -1.0, 1e6, "s",
              "When " + what + " starts, after the start of `lap` (or of the run); negative: never.")
      .number("duration_s", &FaultTrigger::duration_s, 0.0, 1e6, "s",
              "How long " + what + " lasts; 0: until the end of the run.");
}

const ConfigSection<GnssFaultTrigger>& gnss_fault_section() {
  static const auto s = trigger_section<GnssFaultTrigger>("gnss", "the GNSS-INS outage", 10.0)
                            .string("mode", &GnssFaultTrigger::mode, {"no_fix", "silent"},
                                    "During the outage the receiver reports no fix (quality 0) or sends nothing.");
  return s;
}
const ConfigSection<FaultTrigger>& lidar_fault_section() {
  static const auto s = trigger_section<FaultTrigger>("lidar", "the LiDAR outage (no packets)", 1.0);
  return s;
}
const ConfigSection<FaultTrigger>& vcu_link_fault_section() {
  static const auto s = trigger_section<FaultTrigger>("vcu_link", "the cut of the VCU link (both ways)", 0.0);
  return s;
}
const ConfigSection<FaultTrigger>& planner_stall_fault_section() {
  static const auto s = trigger_section<FaultTrigger>("planner_stall", "the stall of the real-time planner", 0.0);
  return s;
}

const ConfigSection<FaultTrigger>& camera_fault_section() {
  static const auto s = trigger_section<FaultTrigger>("camera", "the camera outage (no frames)", 0.0);
  return s;
}

}  // namespace

const FaultTrigger& FaultScheduleConfig::trigger(FaultKind k) const {
  switch (k) {
    case FaultKind::Gnss:
      return gnss;
    case FaultKind::Lidar:
      return lidar;
    case FaultKind::VcuLink:
      return vcu_link;
    case FaultKind::PlannerStall:
      return planner_stall;
    case FaultKind::Camera:
      return camera;
  }
  return gnss;
}

void describe_fault_schedule(ConfigSchema& schema) {
  gnss_fault_section().describe(schema);
  lidar_fault_section().describe(schema);
  vcu_link_fault_section().describe(schema);
  planner_stall_fault_section().describe(schema);
  camera_fault_section().describe(schema);
}

FaultScheduleConfig read_fault_schedule(const Config& cfg) {
  FaultScheduleConfig c;
  c.gnss = gnss_fault_section().read(cfg);
  c.lidar = lidar_fault_section().read(cfg);
  c.vcu_link = vcu_link_fault_section().read(cfg);
  c.planner_stall = planner_stall_fault_section().read(cfg);
  c.camera = camera_fault_section().read(cfg);
  return c;
}

FaultSchedule::FaultSchedule(const FaultScheduleConfig& config, const Track& track) : config_(config), gates_(track) {}

void FaultSchedule::on_truth(Stamp t, const Vec2& position) {
  if (!last_position_) {
    // The scorecard's rule: a car starting just past a timing line (some layouts) has begun lap 1 at the start.
    for (std::size_t g = 0; g < gates_.gates().size(); ++g) {
      const Gate& gate = gates_.gates()[g];
      const double past = gates_.past(g, position);
      const Vec2 lat(-gate.forward.y(), gate.forward.x());
      if (past > 0.0 && past < 10.0 && std::fabs((position - gate.centre).dot(lat)) <= gate.half_width) {
        lap_starts_.push_back(t);
        break;
      }
    }
  } else if (const auto g = gates_.crossed(*last_position_, position)) {
    const double da = gates_.past(*g, *last_position_), db = gates_.past(*g, position);
    lap_starts_.push_back(last_t_ + (t - last_t_) * (da / (da - db)));
  }
  last_position_ = position;
  last_t_ = t;
}

std::optional<FaultWindow> FaultSchedule::window(FaultKind k) const {
  const FaultTrigger& tr = config_.trigger(k);
  if (!tr.enabled()) return std::nullopt;
  Stamp origin = 0;
  if (tr.lap > 0) {
    if (lap_starts_.size() < static_cast<std::size_t>(tr.lap)) return std::nullopt;
    origin = lap_starts_[static_cast<std::size_t>(tr.lap) - 1];
  }
  const Stamp start = origin + tr.at_s;
  const Stamp end = tr.duration_s > 0.0 ? start + tr.duration_s : std::numeric_limits<double>::infinity();
  return FaultWindow{start, end};
}

bool FaultSchedule::active(FaultKind k, Stamp t) const {
  const auto w = window(k);
  return w && w->contains(t);
}

bool FaultSchedule::any_enabled() const {
  for (const FaultKind k : kFaultKinds)
    if (config_.trigger(k).enabled()) return true;
  return false;
}

}  // namespace fsd::sim

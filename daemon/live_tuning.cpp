#include "daemon/live_tuning.hpp"

#include <nlohmann/json.hpp>

#include "common/params.hpp"
#include "control/control_config.hpp"

namespace fsd {

AutopilotConfig tuned_control(Config& tuned, const ParamRegistry& params, int laps) {
  for (const auto& p : params.list()) {
    if (p.entry->type == ValueType::Boolean) tuned.set(p.entry->key, p.value != 0.0, "parameter");
    else if (p.entry->type == ValueType::Integer) tuned.set(p.entry->key, static_cast<long long>(p.value), "parameter");
    else tuned.set(p.entry->key, p.value, "parameter");
  }
  AutopilotConfig ac = read_control(tuned);
  ac.mission.laps = laps;
  return ac;
}

}  // namespace fsd

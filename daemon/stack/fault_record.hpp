#pragma once
// One fault as the report, the log and the dashboard show it: the supervisor's and the VCU link's alike.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/time.hpp"

namespace fsd {

struct FaultRecord {
  Stamp t = 0;
  std::string source, what, action;
  std::optional<Stamp> cleared;  // when the condition ended; empty: it lasted to the end
};

// [{"t", "source", "what", "action"[, "cleared_t"]}, ...]: the report's "faults".
nlohmann::json faults_json(const std::vector<FaultRecord>& faults);

}  // namespace fsd

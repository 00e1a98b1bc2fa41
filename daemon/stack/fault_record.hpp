#pragma once
// One fault as the report, the log and the dashboard show it: the supervisor's and the VCU link's alike.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/time.hpp"

namespace fsd {

struct FaultRecord {
  Stamp t = 0;
  std::string source, what, action;
};

// [{"t", "source", "what", "action"}, ...]: the report's "faults".
nlohmann::json faults_json(const std::vector<FaultRecord>& faults);

}  // namespace fsd

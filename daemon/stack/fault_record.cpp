#include "daemon/stack/fault_record.hpp"

#include <nlohmann/json.hpp>

namespace fsd {

nlohmann::json faults_json(const std::vector<FaultRecord>& faults) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& f : faults) j.push_back({{"t", f.t}, {"source", f.source}, {"what", f.what}, {"action", f.action}});
  return j;
}

}  // namespace fsd

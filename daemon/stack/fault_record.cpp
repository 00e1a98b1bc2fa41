#include "daemon/stack/fault_record.hpp"

#include <nlohmann/json.hpp>

namespace fsd {

nlohmann::json faults_json(const std::vector<FaultRecord>& faults) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& f : faults) {
    nlohmann::json e = {{"t", f.t}, {"source", f.source}, {"what", f.what}, {"action", f.action}};
    if (f.cleared) e["cleared_t"] = *f.cleared;
    j.push_back(e);
  }
  return j;
}

}  // namespace fsd

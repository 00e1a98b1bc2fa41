#pragma once
// The daemon as a systemd service (`service.*`, docs/operations.md): where recordings go and how much of the disk
// they may take, and the control-loop stall that tests inject to see the watchdog stop.
#include <string>

#include "common/config.hpp"

namespace fsd {

struct ServiceSettings {
  std::string recordings_dir = "";   // every `fsd run` records here when set (no --record): fsd-<date>-<time>.mcap
  double recordings_max_mb = 20000;  // the folder's .mcap files are pruned, oldest first, to stay under this
  double test_stall_at_s = -1;       // tests: the control loop hangs this long after its first cycle (< 0: never)
  double test_stall_s = 5;           // for this long
};
const ConfigSection<ServiceSettings>& service_section();

}  // namespace fsd

#include "daemon/service/service_settings.hpp"

namespace fsd {

const ConfigSection<ServiceSettings>& service_section() {
  static const auto s =
      ConfigSection<ServiceSettings>("service")
          .string("recordings_dir", &ServiceSettings::recordings_dir, {},
                  "Every fsd run without --record records to this folder (fsd-YYYYmmdd-HHMMSS.mcap); empty: only "
                  "--record records. The service's configuration sets /var/lib/fsd/recordings.")
          .number("recordings_max_mb", &ServiceSettings::recordings_max_mb, 1, 1e8, "MiB",
                  "Size cap of service.recordings_dir: its oldest .mcap files are deleted at start and at the end "
                  "of each run until the rest fit (a run's own parts split at record.split_mb).")
          .number("test_stall_at_s", &ServiceSettings::test_stall_at_s, -1, 86400, "s",
                  "Fault injection (tests): the control loop hangs this long after its first cycle, for "
                  "service.test_stall_s, so that the systemd watchdog sees it stop; negative: never.")
          .number("test_stall_s", &ServiceSettings::test_stall_s, 0, 3600, "s",
                  "Fault injection (tests): how long the control loop hangs.");
  return s;
}

}  // namespace fsd

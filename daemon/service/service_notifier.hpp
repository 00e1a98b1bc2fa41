#pragma once
// The systemd notify protocol (sd_notify(3), libsystemd) for `Type=notify` units: READY=1 once the run's drivers
// are up, WATCHDOG=1 from the control loop at half the unit's WatchdogSec (WATCHDOG_USEC), STOPPING=1 on the way
// out. The pings come from the loop itself, so a loop that hangs stops them and systemd restarts the daemon.
// Without NOTIFY_SOCKET (not under systemd) every call does nothing. The fault injection service.test_stall_*
// hangs the loop for real, inside on_cycle().
#include <chrono>
#include <string>

#include "daemon/service/service_settings.hpp"

namespace fsd {

class ServiceNotifier {
 public:
  explicit ServiceNotifier(const ServiceSettings& settings);
  // The control loop's pass, each cycle (its thread): READY at the first, WATCHDOG when due; cheap otherwise.
  void on_cycle();
  void stopping();
  bool under_systemd() const { return notify_; }
  std::chrono::microseconds watchdog_interval() const { return watchdog_; }

 private:
  using Steady = std::chrono::steady_clock;
  ServiceSettings settings_;
  bool notify_ = false;
  std::chrono::microseconds watchdog_{0};  // 0: no watchdog
  bool ready_sent_ = false, stalled_ = false;
  Steady::time_point first_cycle_{}, last_ping_{};
};

}  // namespace fsd

#include "daemon/service/service_notifier.hpp"

#include <systemd/sd-daemon.h>

#include <cstdlib>
#include <thread>

#include "common/logging.hpp"

namespace fsd {

ServiceNotifier::ServiceNotifier(const ServiceSettings& settings) : settings_(settings) {
  const char* socket = std::getenv("NOTIFY_SOCKET");
  notify_ = socket && *socket;
  std::uint64_t usec = 0;
  // > 0 only when WATCHDOG_USEC is set (and WATCHDOG_PID, if set, is this process).
  if (notify_ && sd_watchdog_enabled(0, &usec) > 0) watchdog_ = std::chrono::microseconds(usec);
  if (notify_)
    logger("service")->info("under systemd: READY at the first control cycle, WATCHDOG every {:.0f} ms",
                            watchdog_.count() / 2e3);
}

void ServiceNotifier::on_cycle() {
  const auto now = Steady::now();
  if (!ready_sent_) {
    ready_sent_ = true;
    first_cycle_ = last_ping_ = now;
    if (notify_) sd_notify(0, "READY=1\nSTATUS=driving: control loop running");
  }
  if (settings_.test_stall_at_s >= 0 && !stalled_ &&
      now - first_cycle_ >= std::chrono::duration<double>(settings_.test_stall_at_s)) {
    stalled_ = true;
    logger("service")->warn("fault injection: the control loop hangs for {:.1f} s (service.test_stall_s)",
                            settings_.test_stall_s);
    std::this_thread::sleep_for(std::chrono::duration<double>(settings_.test_stall_s));
  }
  if (!notify_ || watchdog_.count() == 0 || now - last_ping_ < watchdog_ / 2) return;
  last_ping_ = now;
  sd_notify(0, "WATCHDOG=1");
}

void ServiceNotifier::stopping() {
  if (notify_) sd_notify(0, "STOPPING=1");
}

}  // namespace fsd

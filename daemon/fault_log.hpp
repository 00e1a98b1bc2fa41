#pragma once
// Writes each fault the supervisor records to the log once, as it happens: the safety officer reading the
// daemon's log (or the dashboard's log panel) sees why the car stopped, not only that the AS changed.
#include <memory>
#include <vector>

#include <spdlog/spdlog.h>

#include "control/as_supervisor.hpp"

namespace fsd {

class FaultLog {
 public:
  explicit FaultLog(std::shared_ptr<spdlog::logger> log) : log_(std::move(log)) {}
  // Called after each control step with the supervisor's whole list (it only grows).
  void update(const std::vector<Fault>& faults) {
    for (; logged_ < faults.size(); ++logged_) {
      const Fault& f = faults[logged_];
      log_->warn("fault at t = {:.2f} s: {}: {} -> {}", f.t, f.source, f.what, f.action);
    }
  }

 private:
  std::shared_ptr<spdlog::logger> log_;
  std::size_t logged_ = 0;
};

}  // namespace fsd

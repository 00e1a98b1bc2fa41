#pragma once
// What a control step has to say in the log, the same on the car and in the simulator: the lap path when it is
// built, each lap's time as the stack timed it, and each fault the supervisor records, once, as it happens. The
// safety officer reading the log (or the dashboard's log panel) sees why the car stopped, not only that the AS
// changed.
#include <memory>
#include <vector>

#include <spdlog/spdlog.h>

#include "control/autopilot.hpp"

namespace fsd {

class StepLog {
 public:
  explicit StepLog(std::shared_ptr<spdlog::logger> log) : log_(std::move(log)) {}
  // After each control step: its output, and the supervisor's whole fault list (it only grows).
  void update(const ControlOutput& out, const std::vector<Fault>& faults) {
    if (out.lap_line) log_->info("{}", to_string(*out.lap_line));
    if (out.lap) log_->info("lap {} in {:.2f} s (stack's timing)", out.lap->lap, out.lap->time_s);
    for (; logged_faults_ < faults.size(); ++logged_faults_) {
      const Fault& f = faults[logged_faults_];
      log_->warn("fault at t = {:.2f} s: {}: {} -> {}", f.t, f.source, f.what, f.action);
    }
  }

 private:
  std::shared_ptr<spdlog::logger> log_;
  std::size_t logged_faults_ = 0;
};

}  // namespace fsd

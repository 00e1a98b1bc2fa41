#pragma once
// Where a slow, once-a-lap job runs (lap 2's build, the loop closure's solve: tens to hundreds of ms) for a caller
// that must not wait for it, the control thread: it hands the job over and polls for the result each step. The
// daemon's Stack owns the workers (daemon/stack/job_thread.hpp); without one the caller runs the job itself, as headless
// runs and replay do to stay repeatable.
#include <functional>
#include <optional>

namespace fsd {

template <class Result>
class JobService {
 public:
  // A job holds copies of its inputs, so that it is safe to run on any thread.
  using Job = std::function<Result()>;
  virtual ~JobService() = default;
  // Takes the job to run elsewhere; false when it cannot (the caller then runs it itself). One job at a time.
  virtual bool submit(Job job) = 0;
  // The submitted job's result, once, when it is ready; nullopt while it is still running.
  virtual std::optional<Result> poll() = 0;
};

}  // namespace fsd

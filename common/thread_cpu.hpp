#pragma once
// CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID): what a piece of work cost, without the time the thread
// waited for a core. For figures of work (plan costs, benchmarks), never for the run's time (common/clock.hpp).
#include <ctime>

namespace fsd {

inline double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace fsd

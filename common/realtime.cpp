#include "common/realtime.hpp"

#include <pthread.h>
#include <sched.h>

#include <cstring>

namespace fsd {

std::optional<std::string> set_realtime(int priority, std::thread::native_handle_type thread) {
  if (priority < sched_get_priority_min(SCHED_FIFO) || priority > sched_get_priority_max(SCHED_FIFO))
    return "SCHED_FIFO priority " + std::to_string(priority) + " out of range";
  sched_param p{};
  p.sched_priority = priority;
  if (const int e = pthread_setschedparam(thread, SCHED_FIFO, &p); e != 0)
    return "SCHED_FIFO " + std::to_string(priority) + ": " + std::strerror(e);
  return std::nullopt;
}

std::optional<std::string> set_realtime(int priority) { return set_realtime(priority, pthread_self()); }

}  // namespace fsd

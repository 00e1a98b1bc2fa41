#pragma once
// Real-time scheduling of a thread (SCHED_FIFO): the control thread's period must not depend on what else the
// computer runs (a browser with the dashboard, a build). Needs CAP_SYS_NICE or an RLIMIT_RTPRIO at least the
// priority (the service unit's LimitRTPRIO); without either the thread stays at normal scheduling and the caller
// says so.
#include <optional>
#include <string>
#include <thread>

namespace fsd {

// Puts `thread` (the calling thread by default) under SCHED_FIFO at `priority` (1–99). What failed, or nothing.
std::optional<std::string> set_realtime(int priority, std::thread::native_handle_type thread);
std::optional<std::string> set_realtime(int priority);

}  // namespace fsd

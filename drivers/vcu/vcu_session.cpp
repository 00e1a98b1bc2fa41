#include "drivers/vcu/vcu_session.hpp"

#include <cmath>

#include <fmt/format.h>

namespace fsd {

using wire::vcu::AsRequest;

std::string_view to_string(VcuLinkEventKind k) {
  switch (k) {
    case VcuLinkEventKind::StatusTimeout:
      return "status_timeout";
    case VcuLinkEventKind::StatusRestored:
      return "status_restored";
    case VcuLinkEventKind::CommandStale:
      return "command_stale";
    case VcuLinkEventKind::PortLost:
      return "port_lost";
    case VcuLinkEventKind::PortRestored:
      return "port_restored";
  }
  return "?";
}

std::string describe(const VcuLinkEvent& e) {
  std::string s(to_string(e.kind));
  if (!e.what.empty()) s += ": " + e.what;
  return s;
}

VcuSession::VcuSession(const VcuLinkConfig& cfg, Stamp start, EventHandler on_event)
    : cfg_(cfg),
      on_event_(std::move(on_event)),
      decoder_(wire::vcu::Decoder::Handlers{nullptr,
                                            // Runs inside on_bytes() with m_ held.
                                            [this](const VcuStatus& s, std::uint16_t) {
                                              status_ = s;
                                              status_->stamp = rx_now_;
                                              ++counters_.statuses;
                                              if (timed_out_) {
                                                timed_out_ = false;
                                                pending_.push_back({VcuLinkEventKind::StatusRestored, rx_now_,
                                                                    rx_now_ - last_status_at_,
                                                                    "VCU status frames back"});
                                              }
                                              last_status_at_ = rx_now_;
                                            },
                                            nullptr}),
      last_status_at_(start),
      schedule_(cfg.rate_hz, start) {}

void VcuSession::set_command(const ControlCommand& c, Stamp now) {
  std::lock_guard lock(m_);
  command_ = c;
  command_at_ = now;
  command_stale_ = false;
}

void VcuSession::set_as_request(AsRequest r) {
  std::lock_guard lock(m_);
  request_ = r;
}

void VcuSession::set_mission(Mission m) {
  std::lock_guard lock(m_);
  mission_ = m;
}

void VcuSession::enter_safe_stop() {
  std::lock_guard lock(m_);
  stopping_ = true;
}

std::vector<std::uint8_t> VcuSession::command_frame(Stamp now) {
  std::vector<VcuLinkEvent> events;
  std::vector<std::uint8_t> frame;
  {
    std::lock_guard lock(m_);
    ControlCommand c = command_.value_or(ControlCommand{});
    const bool stale = command_ && now - command_at_ > cfg_.command_timeout;
    if (stale && !command_stale_ && !stopping_) {
      command_stale_ = true;
      events.push_back({VcuLinkEventKind::CommandStale, now, now - command_at_,
                        fmt::format("no control command for {:.3f} s: commanding a stop", now - command_at_)});
    }
    if (!command_ || stale || stopping_ || !std::isfinite(c.target_speed) || !std::isfinite(c.steering)) {
      // Hold the wheel angle (a sudden centring while braking would upset the car), stop with the brake.
      if (!std::isfinite(c.steering)) c.steering = 0;
      c.target_speed = 0;
      c.brake_hard = true;
      ++counters_.safe_commands_sent;
    }
    frame = wire::vcu::encode(wire::vcu::make_command(c, request_, mission_), seq_.next());
    ++counters_.commands_sent;
  }
  emit(events);
  return frame;
}

void VcuSession::check_timeout(Stamp now) {
  std::vector<VcuLinkEvent> events;
  {
    std::lock_guard lock(m_);
    const Duration age = now - last_status_at_;
    if (!timed_out_ && age > cfg_.timeout) {
      timed_out_ = true;
      ++counters_.status_timeouts;
      events.push_back({VcuLinkEventKind::StatusTimeout, now, age,
                        status_ ? fmt::format("no VCU status for {:.3f} s", age)
                                : fmt::format("no VCU status since start ({:.3f} s)", age)});
    }
  }
  emit(events);
}

Stamp VcuSession::tick(Stamp now, const Writer& write) {
  bool due = false;
  Stamp next = 0;
  {
    std::lock_guard lock(m_);
    due = schedule_.due(now);
    next = schedule_.next();
  }
  if (due && write) write(command_frame(now));
  check_timeout(now);
  return next;
}

void VcuSession::on_bytes(Stamp now, std::span<const std::uint8_t> bytes) {
  std::vector<VcuLinkEvent> events;
  {
    std::lock_guard lock(m_);
    rx_now_ = now;
    decoder_.feed(bytes);
    events.swap(pending_);
  }
  emit(events);
}

void VcuSession::on_stream_reset() {
  std::lock_guard lock(m_);
  decoder_.reset();
}

std::optional<VcuStatus> VcuSession::status() const {
  std::lock_guard lock(m_);
  return status_;
}

bool VcuSession::status_ok() const {
  std::lock_guard lock(m_);
  return status_ && !timed_out_;
}

VcuSessionCounters VcuSession::counters() const {
  std::lock_guard lock(m_);
  VcuSessionCounters c = counters_;
  c.rx = decoder_.counters();
  return c;
}

void VcuSession::emit(std::vector<VcuLinkEvent>& events) {
  if (!on_event_) return;
  for (const auto& e : events) on_event_(e);
}

}  // namespace fsd

#include "drivers/vcu/vcu_link.hpp"

#include <chrono>
#include <stdexcept>

#include "common/clock.hpp"
#include "common/logging.hpp"

namespace fsd {

namespace {
VcuLink::Handlers checked(VcuLink::Handlers h) {
  if (!h.on_rx_bytes) throw std::invalid_argument("VcuLink: on_rx_bytes must hand the received bytes to the session");
  return h;
}
}  // namespace

VcuLink::VcuLink(const VcuLinkConfig& cfg, VcuSession& session, const Clock& clock, Handlers h)
    : cfg_(cfg),
      clock_(clock),
      h_(checked(std::move(h))),
      session_(session),
      port_({.device = cfg_.device, .baud = cfg_.baud, .reopen_interval_ms = cfg_.reopen_ms},
            {[this](std::span<const std::uint8_t> b) { h_.on_rx_bytes(clock_.now(), b); },
             [this] { session_.on_stream_reset(); },
             [this](Stamp t, const std::string& why) {
               session_.on_stream_reset();
               event({VcuLinkEventKind::PortLost, t, 0, why});
             },
             [this](const SerialGap& g) {
               event({VcuLinkEventKind::PortRestored, g.end, g.duration(), "serial port reopened after " + g.reason});
             }},
            &clock) {}

VcuLink::~VcuLink() { stop(); }

void VcuLink::start() {
  if (sender_.joinable()) return;
  {
    std::lock_guard lock(m_);
    stop_requested_ = false;
  }
  port_.start();
  sender_ = std::thread([this] { run_sender(); });
}

void VcuLink::stop() {
  if (!sender_.joinable()) return;
  {
    std::lock_guard lock(m_);
    stop_requested_ = true;
  }
  cv_.notify_all();
  sender_.join();
  // The last word to the VCU is a controlled stop, repeated so one corrupted frame cannot lose it.
  session_.enter_safe_stop();
  const auto period = std::chrono::duration<double>(1.0 / cfg_.rate_hz);
  for (int i = 0; i < cfg_.stop_frames; ++i) {
    if (i > 0) std::this_thread::sleep_for(period);
    send_one();
  }
  port_.stop();
  logger("vcu")->info("VCU link stopped after {} safe commands", cfg_.stop_frames);
}

void VcuLink::set_command(const ControlCommand& c) { session_.set_command(c, clock_.now()); }

void VcuLink::send_one() {
  const Stamp now = clock_.now();
  auto frame = session_.command_frame(now);
  if (h_.on_tx_bytes) h_.on_tx_bytes(now, frame);
  port_.write(std::move(frame));
}

void VcuLink::run_sender() {
  using steady = std::chrono::steady_clock;
  const auto period = std::chrono::duration_cast<steady::duration>(std::chrono::duration<double>(1.0 / cfg_.rate_hz));
  auto next = steady::now();
  std::unique_lock lock(m_);
  while (!stop_requested_) {
    lock.unlock();
    send_one();
    session_.check_timeout(clock_.now());
    lock.lock();
    next += period;
    if (next < steady::now()) next = steady::now();  // overran: skip rather than burst
    cv_.wait_until(lock, next, [this] { return stop_requested_; });
  }
}

void VcuLink::event(const VcuLinkEvent& e) {
  auto log = logger("vcu");
  switch (e.kind) {
    case VcuLinkEventKind::StatusRestored:
    case VcuLinkEventKind::PortRestored:
      log->info("{}: {} (gap {:.3f} s)", to_string(e.kind), e.what, e.gap);
      break;
    default:
      log->warn("{}: {}", to_string(e.kind), e.what);
      break;
  }
  if (h_.on_event) h_.on_event(e);
}

}  // namespace fsd

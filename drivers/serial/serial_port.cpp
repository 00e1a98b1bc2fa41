#include "drivers/serial/serial_port.hpp"

#include <termios.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/serial_port.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/write.hpp>

#include "common/clock.hpp"
#include "common/logging.hpp"
#include "drivers/serial/tty_baud.hpp"

namespace fsd {

namespace asio = boost::asio;
using boost::system::error_code;

struct SerialPort::Impl {
  Impl(SerialPortConfig c, Handlers hs, const Clock* clk)
      : cfg(std::move(c)), h(std::move(hs)), clock(clk), port(io), reopen_timer(io), log(logger("serial")) {
    if (!clock) {
      own_clock = std::make_unique<RealClock>();
      clock = own_clock.get();
    }
    if (cfg.write_queue == 0) cfg.write_queue = 1;
    if (cfg.read_buffer == 0) cfg.read_buffer = 1;
    rbuf.resize(cfg.read_buffer);
  }

  SerialPortConfig cfg;
  Handlers h;
  std::unique_ptr<RealClock> own_clock;
  const Clock* clock;
  asio::io_context io;
  asio::serial_port port;
  asio::steady_timer reopen_timer;
  std::optional<asio::executor_work_guard<asio::io_context::executor_type>> guard;
  std::thread thread;
  std::shared_ptr<spdlog::logger> log;
  std::vector<std::uint8_t> rbuf;

  // Shared with writers on other threads.
  mutable std::mutex m;
  std::condition_variable drained;
  std::deque<std::vector<std::uint8_t>> queue;
  bool open = false;
  bool writing = false;  // an async_write is in flight (its buffer is `inflight`)
  SerialCounters counters;

  // I/O thread only.
  std::vector<std::uint8_t> inflight;
  std::optional<Stamp> lost_at;
  std::string lost_reason;
  std::string last_error;  // why the last open/configure failed
  bool stopping = false;

  void try_open() {
    if (stopping) return;
    error_code ec;
    port.open(cfg.device, ec);
    if (ec)
      last_error = ec.message();
    else
      ec = configure();
    if (ec) {
      port.close(ec);  // ignore: it may not have opened
      {
        std::lock_guard lock(m);
        ++counters.open_failures;
      }
      if (!lost_at) begin_gap("open " + cfg.device + ": " + last_error);
      schedule_reopen();
      return;
    }
    // A freshly opened line may hold bytes from before the gap: they are stale, drop them.
    ::tcflush(port.native_handle(), TCIOFLUSH);
    {
      std::lock_guard lock(m);
      open = true;
      ++counters.opens;
    }
    if (lost_at) {
      SerialGap gap{*lost_at, clock->now(), lost_reason};
      lost_at.reset();
      {
        std::lock_guard lock(m);
        ++counters.gaps;
      }
      log->info("{} back after {:.3f} s ({})", cfg.device, gap.duration(), gap.reason);
      if (h.on_gap) h.on_gap(gap);
    } else {
      log->info("{} open at {} baud", cfg.device, cfg.baud);
    }
    if (h.on_open) h.on_open();
    start_read();
    start_write();
  }

  error_code configure() {
    error_code ec;
    port.set_option(asio::serial_port_base::character_size(8), ec);
    if (!ec) port.set_option(asio::serial_port_base::parity(asio::serial_port_base::parity::none), ec);
    if (!ec) port.set_option(asio::serial_port_base::stop_bits(asio::serial_port_base::stop_bits::one), ec);
    if (!ec) port.set_option(asio::serial_port_base::flow_control(asio::serial_port_base::flow_control::none), ec);
    if (ec) {
      last_error = ec.message();
      return ec;
    }
    if (auto err = set_tty_baud(port.native_handle(), cfg.baud); !err.empty()) {
      last_error = err;
      return asio::error::invalid_argument;
    }
    return {};
  }

  void begin_gap(const std::string& reason) {
    lost_at = clock->now();
    lost_reason = reason;
    log->warn("{} lost: {}; retrying every {} ms", cfg.device, reason, cfg.reopen_interval_ms);
    if (h.on_lost) h.on_lost(*lost_at, reason);
  }

  void schedule_reopen() {
    reopen_timer.expires_after(std::chrono::milliseconds(cfg.reopen_interval_ms));
    reopen_timer.async_wait([this](error_code ec) {
      if (!ec) try_open();
    });
  }

  // A read or write failed: the device is gone or broken. Close, drop what was queued, retry later.
  void fail(const error_code& ec, const char* what) {
    if (stopping || !port.is_open()) return;
    error_code ignored;
    port.close(ignored);
    {
      std::lock_guard lock(m);
      open = false;
      writing = false;
      ++counters.errors;
      counters.writes_dropped += queue.size();
      queue.clear();
    }
    drained.notify_all();
    begin_gap(std::string(what) + ": " + ec.message());
    schedule_reopen();
  }

  void start_read() {
    port.async_read_some(asio::buffer(rbuf), [this](error_code ec, std::size_t n) {
      if (ec) {
        fail(ec, "read");
        return;
      }
      {
        std::lock_guard lock(m);
        counters.bytes_in += n;
      }
      if (h.on_bytes) h.on_bytes(std::span<const std::uint8_t>(rbuf.data(), n));
      start_read();
    });
  }

  void start_write() {
    {
      std::lock_guard lock(m);
      if (writing || !open || queue.empty()) return;
      inflight = std::move(queue.front());
      queue.pop_front();
      writing = true;
    }
    asio::async_write(port, asio::buffer(inflight), [this](error_code ec, std::size_t n) {
      if (ec) {
        fail(ec, "write");
        return;
      }
      {
        std::lock_guard lock(m);
        counters.bytes_out += n;
        writing = false;
      }
      drained.notify_all();
      start_write();
    });
  }
};

SerialPort::SerialPort(SerialPortConfig cfg, Handlers h, const Clock* clock)
    : impl_(std::make_unique<Impl>(std::move(cfg), std::move(h), clock)) {}

SerialPort::~SerialPort() { stop(); }

void SerialPort::start() {
  auto& d = *impl_;
  if (d.thread.joinable()) return;
  d.io.restart();  // allows start() after stop()
  d.stopping = false;
  d.guard.emplace(d.io.get_executor());
  asio::post(d.io, [&d] { d.try_open(); });
  d.thread = std::thread([&d] { d.io.run(); });
}

void SerialPort::stop() {
  auto& d = *impl_;
  if (!d.thread.joinable()) return;
  {
    std::unique_lock lock(d.m);
    d.drained.wait_for(lock, std::chrono::milliseconds(d.cfg.drain_timeout_ms),
                       [&] { return !d.open || (d.queue.empty() && !d.writing); });
  }
  asio::post(d.io, [&d] {
    d.stopping = true;
    d.reopen_timer.cancel();
    error_code ignored;
    d.port.close(ignored);  // completes pending operations with operation_aborted
    std::lock_guard lock(d.m);
    d.open = false;
    d.counters.writes_dropped += d.queue.size();
    d.queue.clear();
  });
  d.guard.reset();
  d.thread.join();
}

bool SerialPort::write(std::vector<std::uint8_t> bytes) {
  auto& d = *impl_;
  bool kept_all = true;
  {
    std::lock_guard lock(d.m);
    if (!d.open) {
      ++d.counters.writes_dropped;  // nothing is sent late: a stale command is worse than none
      return false;
    }
    if (d.queue.size() >= d.cfg.write_queue) {
      d.queue.pop_front();
      ++d.counters.writes_dropped;
      kept_all = false;
    }
    d.queue.push_back(std::move(bytes));
  }
  asio::post(d.io, [&d] { d.start_write(); });
  return kept_all;
}

bool SerialPort::is_open() const {
  std::lock_guard lock(impl_->m);
  return impl_->open;
}

SerialCounters SerialPort::counters() const {
  std::lock_guard lock(impl_->m);
  return impl_->counters;
}

const SerialPortConfig& SerialPort::config() const { return impl_->cfg; }

}  // namespace fsd

#pragma once
// A serial port (RS-232, USB serial adapter or pseudo-terminal) on Boost.Asio with its own I/O thread: raw 8N1
// at any baud, asynchronous reads handed to a callback, a bounded write queue, and recovery by itself: when the
// device errors or disappears the port is closed, reopened every `reopen_interval_ms`, and the gap is reported.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/time.hpp"

namespace fsd {

class Clock;

struct SerialPortConfig {
  std::string device;             // e.g. /dev/ttyUSB0, a udev symlink, or a pty slave path
  int baud = 115200;              // any rate; non-standard rates go through termios2 (BOTHER)
  int reopen_interval_ms = 200;   // retry period while the device is missing
  std::size_t write_queue = 64;   // pending writes; beyond this the oldest is dropped
  std::size_t read_buffer = 512;  // bytes per read
  int drain_timeout_ms = 100;     // stop() waits this long at most for queued writes to leave
};

// A period without a usable device: from the error (or a failed first open) until the port is open again.
struct SerialGap {
  Stamp start = 0;
  Stamp end = 0;
  std::string reason;
  Duration duration() const { return end - start; }
};

struct SerialCounters {
  std::uint64_t bytes_in = 0;
  std::uint64_t bytes_out = 0;
  std::uint64_t writes_dropped = 0;  // queue overflow, or written while the port was down
  std::uint64_t opens = 0;
  std::uint64_t open_failures = 0;
  std::uint64_t errors = 0;  // read/write errors that closed the port
  std::uint64_t gaps = 0;    // completed gaps
};

class SerialPort {
 public:
  // All handlers run on the port's I/O thread; keep them short.
  struct Handlers {
    std::function<void(std::span<const std::uint8_t>)> on_bytes;
    std::function<void()> on_open;                                    // every (re)open, before the first read
    std::function<void(Stamp t, const std::string& reason)> on_lost;  // a gap starts
    std::function<void(const SerialGap&)> on_gap;                     // a gap ended: the port is back
  };

  // `clock` stamps the gaps (the daemon's clock); without one, seconds since construction.
  SerialPort(SerialPortConfig cfg, Handlers h, const Clock* clock = nullptr);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  void start();  // opens (or keeps retrying) on the I/O thread; may follow a stop()
  // Lets queued writes drain (bounded by drain_timeout_ms), closes the port and joins the thread. Idempotent.
  void stop();
  // Thread-safe, never blocks. Returns false when the bytes or an older queued write were dropped.
  bool write(std::vector<std::uint8_t> bytes);
  bool is_open() const;
  SerialCounters counters() const;
  const SerialPortConfig& config() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd

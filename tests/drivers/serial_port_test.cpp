// SerialPort and PseudoTerminal over real pseudo-terminals. The waits below are bounded polls for a condition,
// not timing assertions.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <numeric>
#include <thread>

#include "drivers/serial/pseudo_terminal.hpp"
#include "drivers/serial/serial_port.hpp"
#include "drivers/serial/tty_baud.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/wait_until.hpp"

namespace fsd {
namespace {

using Bytes = std::vector<std::uint8_t>;
namespace fs = std::filesystem;

using test::wait_until;

// Everything SerialPort reports, collected thread-safely.
struct Recorder {
  std::mutex m;
  Bytes bytes;
  std::vector<SerialGap> gaps;
  std::vector<std::string> lost;
  int opens = 0;
  SerialPort::Handlers handlers() {
    return {[this](std::span<const std::uint8_t> b) {
              std::lock_guard l(m);
              bytes.insert(bytes.end(), b.begin(), b.end());
            },
            [this] {
              std::lock_guard l(m);
              ++opens;
            },
            [this](Stamp, const std::string& why) {
              std::lock_guard l(m);
              lost.push_back(why);
            },
            [this](const SerialGap& g) {
              std::lock_guard l(m);
              gaps.push_back(g);
            }};
  }
  std::size_t size() {
    std::lock_guard l(m);
    return bytes.size();
  }
  template <class F>
  auto with(F f) {
    std::lock_guard l(m);
    return f(*this);
  }
};

Bytes read_master(PseudoTerminal& pty, std::size_t want, double timeout_s = 5.0) {
  Bytes out;
  std::vector<std::uint8_t> buf(4096);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (out.size() < want && std::chrono::steady_clock::now() < end) {
    const auto n = pty.read(buf, 0.05);
    out.insert(out.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
  }
  return out;
}

Bytes all_byte_values() {
  Bytes b(256);
  std::iota(b.begin(), b.end(), 0);
  return b;
}

// A device path the test can point at a pty and take away again, like the udev symlink on the car.
struct DeviceLink {
  fs::path path;
  DeviceLink() {
    static std::atomic<int> n{0};
    path = test::scratch_path("device_" + std::to_string(n++));
  }
  ~DeviceLink() { remove(); }
  void point_to(const std::string& target) {
    remove();
    fs::create_symlink(target, path);
  }
  void remove() {
    std::error_code ec;
    fs::remove(path, ec);
  }
};

TEST(PseudoTerminal, IsRawBothWays) {
  PseudoTerminal pty;
  ASSERT_TRUE(pty.is_open());
  const int slave = ::open(pty.slave_path().c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(slave, 0);
  const Bytes all = all_byte_values();  // includes NUL, CR, LF, ^C, ^S/^Q, DEL that a cooked tty would alter
  EXPECT_EQ(pty.write(all), all.size());
  Bytes got(all.size());
  std::size_t n = 0;
  while (n < got.size()) {
    const ssize_t r = ::read(slave, got.data() + n, got.size() - n);
    ASSERT_GT(r, 0);
    n += static_cast<std::size_t>(r);
  }
  EXPECT_EQ(got, all);
  ASSERT_EQ(::write(slave, all.data(), all.size()), static_cast<ssize_t>(all.size()));
  EXPECT_EQ(read_master(pty, all.size()), all);
  ::close(slave);
}

TEST(PseudoTerminal, CloseRemovesTheDevice) {
  PseudoTerminal pty;
  const std::string path = pty.slave_path();
  EXPECT_TRUE(fs::exists(path));
  pty.close();
  EXPECT_FALSE(pty.is_open());
  EXPECT_EQ(pty.write(Bytes{1, 2, 3}), 0u);
  EXPECT_EQ(pty.dropped(), 3u);
}

TEST(SerialPort, CarriesEveryByteValueBothWays) {
  PseudoTerminal pty;
  Recorder rec;
  SerialPort port({.device = pty.slave_path()}, rec.handlers());
  port.start();
  ASSERT_TRUE(wait_until([&] { return port.is_open(); }));
  const Bytes all = all_byte_values();
  pty.write(all);
  ASSERT_TRUE(wait_until([&] { return rec.size() >= all.size(); }));
  EXPECT_EQ(rec.with([](Recorder& r) { return r.bytes; }), all);
  EXPECT_TRUE(port.write(all));
  EXPECT_EQ(read_master(pty, all.size()), all);
  port.stop();
  const auto c = port.counters();
  EXPECT_EQ(c.bytes_in, 256u);
  EXPECT_EQ(c.bytes_out, 256u);
  EXPECT_EQ(c.opens, 1u);
  EXPECT_EQ(c.gaps, 0u);
}

TEST(SerialPort, SetsAnyBaudRate) {
  for (int baud : {9600, 115200, 250000, 1000000}) {
    PseudoTerminal pty;
    SerialPort port({.device = pty.slave_path(), .baud = baud}, {});
    port.start();
    ASSERT_TRUE(wait_until([&] { return port.is_open(); })) << baud;
    const int fd = ::open(pty.slave_path().c_str(), O_RDWR | O_NOCTTY);
    ASSERT_GE(fd, 0);
    EXPECT_EQ(tty_baud(fd), baud);
    ::close(fd);
    port.stop();
  }
}

TEST(SerialPort, StopDeliversQueuedWritesFirst) {
  PseudoTerminal pty;
  SerialPort port({.device = pty.slave_path()}, {});
  port.start();
  ASSERT_TRUE(wait_until([&] { return port.is_open(); }));
  const Bytes last = {0xde, 0xad, 0xbe, 0xef};
  port.write(last);
  port.stop();
  EXPECT_EQ(read_master(pty, last.size(), 1.0), last);
  EXPECT_FALSE(port.is_open());
  port.stop();   // idempotent
  port.start();  // and startable again
  ASSERT_TRUE(wait_until([&] { return port.is_open(); }));
  port.write(last);
  EXPECT_EQ(read_master(pty, last.size(), 1.0), last);
  port.stop();
}

TEST(SerialPort, WriteQueueIsBoundedAndKeepsTheNewest) {
  PseudoTerminal pty;  // nobody reads the master until the end: the tty buffer fills, then the queue
  SerialPort port({.device = pty.slave_path(), .write_queue = 4, .drain_timeout_ms = 0}, {});
  port.start();
  ASSERT_TRUE(wait_until([&] { return port.is_open(); }));
  constexpr int kChunks = 300;
  constexpr std::size_t kChunk = 1000;
  for (int i = 0; i < kChunks; ++i) port.write(Bytes(kChunk, static_cast<std::uint8_t>(i)));
  ASSERT_TRUE(wait_until([&] { return port.counters().writes_dropped > 0; }));
  // Drain the master: the bytes that arrive end with the newest chunk.
  const auto c0 = port.counters();
  const auto expected = (kChunks - c0.writes_dropped) * kChunk;
  const Bytes got = read_master(pty, expected);
  ASSERT_EQ(got.size(), expected);
  EXPECT_EQ(got.back(), static_cast<std::uint8_t>(kChunks - 1));
  EXPECT_EQ(got[got.size() - kChunk], static_cast<std::uint8_t>(kChunks - 1));
  EXPECT_LE(c0.writes_dropped, static_cast<std::uint64_t>(kChunks - 4));
  port.stop();
}

TEST(SerialPort, WritesWhileTheDeviceIsMissingAreDroppedNotDelayed) {
  DeviceLink dev;  // points nowhere yet
  Recorder rec;
  SerialPort port({.device = dev.path.string(), .reopen_interval_ms = 10}, rec.handlers());
  port.start();
  EXPECT_FALSE(port.write(Bytes{1, 2, 3}));
  ASSERT_TRUE(wait_until([&] { return port.counters().open_failures >= 2; }));
  EXPECT_EQ(port.counters().writes_dropped, 1u);
  EXPECT_EQ(rec.with([](Recorder& r) { return r.lost.size(); }), 1u);  // one gap, not one per retry

  // The device appears: the gap that began at start() ends, and nothing queued before shows up late.
  PseudoTerminal pty;
  dev.point_to(pty.slave_path());
  ASSERT_TRUE(wait_until([&] { return port.is_open(); }));
  ASSERT_TRUE(wait_until([&] { return rec.with([](Recorder& r) { return r.gaps.size(); }) == 1u; }));
  EXPECT_TRUE(read_master(pty, 1, 0.1).empty());
  port.stop();
}

TEST(SerialPort, RecoversWhenTheDeviceDisappearsAndReportsTheGap) {
  DeviceLink dev;
  auto pty = std::make_unique<PseudoTerminal>();
  dev.point_to(pty->slave_path());
  Recorder rec;
  SerialPort port({.device = dev.path.string(), .reopen_interval_ms = 20}, rec.handlers());
  port.start();
  ASSERT_TRUE(wait_until([&] { return port.is_open(); }));
  pty->write(Bytes{1, 2, 3});
  ASSERT_TRUE(wait_until([&] { return rec.size() == 3; }));

  // Unplug: the pty goes away with its path.
  const auto t_unplug = std::chrono::steady_clock::now();
  pty.reset();
  dev.remove();
  ASSERT_TRUE(wait_until([&] { return !port.is_open(); }));
  ASSERT_TRUE(wait_until([&] { return rec.with([](Recorder& r) { return r.lost.size(); }) == 1u; }));
  ASSERT_TRUE(wait_until([&] { return port.counters().open_failures >= 2; }));
  EXPECT_FALSE(port.write(Bytes{9}));

  // Plug back in (a new pty behind the same path): the port reopens by itself and reports the gap.
  pty = std::make_unique<PseudoTerminal>();
  dev.point_to(pty->slave_path());
  ASSERT_TRUE(wait_until([&] { return port.is_open(); }));
  const double outage = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_unplug).count();
  ASSERT_TRUE(wait_until([&] { return rec.with([](Recorder& r) { return r.gaps.size(); }) == 1u; }));
  const SerialGap gap = rec.with([](Recorder& r) { return r.gaps[0]; });
  EXPECT_GT(gap.duration(), 0.0);
  EXPECT_LE(gap.duration(), outage + 0.05);
  EXPECT_FALSE(gap.reason.empty());
  EXPECT_EQ(rec.with([](Recorder& r) { return r.opens; }), 2);

  pty->write(Bytes{4, 5});
  ASSERT_TRUE(wait_until([&] { return rec.size() == 5; }));
  EXPECT_TRUE(port.write(Bytes{7, 8}));
  EXPECT_EQ(read_master(*pty, 2), (Bytes{7, 8}));
  port.stop();
  const auto c = port.counters();
  EXPECT_EQ(c.errors, 1u);
  EXPECT_EQ(c.gaps, 1u);
  EXPECT_EQ(c.opens, 2u);
}

}  // namespace
}  // namespace fsd

// The UDP receiver on loopback: datagrams sent with a plain Asio socket arrive intact and counted, a throwing
// handler does not stop it, bind errors are named, stop() returns at once; the recorded capture replayed over
// UDP gives the same returns as read from the file.
#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "common/clock.hpp"
#include "drivers/vlp16/pcap_reader.hpp"
#include "drivers/vlp16/scan_builder.hpp"
#include "drivers/vlp16/udp_receiver.hpp"

namespace fsd {
namespace {

namespace asio = boost::asio;
using asio::ip::udp;
using namespace std::chrono_literals;

// Thread-safe collection of what the receiver's thread delivers.
struct Inbox {
  std::mutex m;
  std::condition_variable cv;
  std::vector<std::vector<std::uint8_t>> payloads;
  std::vector<Stamp> times;
  void push(Stamp t, std::span<const std::uint8_t> p) {
    std::lock_guard lock(m);
    payloads.emplace_back(p.begin(), p.end());
    times.push_back(t);
    cv.notify_all();
  }
  // Waits (generously: this is a liveness bound, not a timing check) until n datagrams are in.
  bool wait_for(std::size_t n) {
    std::unique_lock lock(m);
    return cv.wait_for(lock, 10s, [&] { return payloads.size() >= n; });
  }
};

struct Sender {
  asio::io_context io;
  udp::socket socket{io, udp::endpoint(udp::v4(), 0)};
  void send(std::uint16_t port, std::span<const std::uint8_t> bytes) {
    socket.send_to(asio::buffer(bytes.data(), bytes.size()), udp::endpoint(asio::ip::make_address("127.0.0.1"), port));
  }
};

UdpReceiver::Options loopback() {
  UdpReceiver::Options o;
  o.address = "127.0.0.1";
  o.port = 0;
  o.name = "test";
  return o;
}

TEST(Vlp16Udp, ReceivesCountsAndStops) {
  RealClock clock;
  Inbox inbox;
  UdpReceiver rx(loopback(), clock, [&](Stamp t, std::span<const std::uint8_t> p) { inbox.push(t, p); });
  ASSERT_NE(rx.port(), 0);
  EXPECT_GT(rx.receive_buffer_bytes(), 0);
  rx.start();

  Sender tx;
  constexpr std::size_t kCount = 50;
  const Stamp before = clock.now();
  for (std::size_t i = 0; i < kCount; ++i) {
    std::vector<std::uint8_t> p(1206, static_cast<std::uint8_t>(i));
    tx.send(rx.port(), p);
  }
  ASSERT_TRUE(inbox.wait_for(kCount));
  const Stamp after = clock.now();

  {
    std::lock_guard lock(inbox.m);
    for (std::size_t i = 0; i < kCount; ++i) {
      ASSERT_EQ(inbox.payloads[i].size(), 1206u);
      EXPECT_EQ(inbox.payloads[i].front(), static_cast<std::uint8_t>(i));  // loopback keeps the order
      EXPECT_EQ(inbox.payloads[i].back(), static_cast<std::uint8_t>(i));
      EXPECT_GE(inbox.times[i], before);
      EXPECT_LE(inbox.times[i], after);
      if (i > 0) {
        EXPECT_GE(inbox.times[i], inbox.times[i - 1]);
      }
    }
  }
  const auto c = rx.counters();
  EXPECT_EQ(c.datagrams, kCount);
  EXPECT_EQ(c.bytes, kCount * 1206);
  EXPECT_EQ(c.kernel_drops, 0u);
  EXPECT_EQ(c.errors, 0u);

  // Idle socket: stop() must not wait for a datagram.
  const auto t0 = std::chrono::steady_clock::now();
  rx.stop();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 2s);
  rx.stop();  // idempotent
}

TEST(Vlp16Udp, KernelDropsAreCounted) {
  RealClock clock;
  Inbox inbox;
  auto options = loopback();
  options.receive_buffer_bytes = 4096;  // room for a few datagrams only
  UdpReceiver rx(options, clock, [&](Stamp t, std::span<const std::uint8_t> p) { inbox.push(t, p); });
  Sender tx;
  // Not reading yet: the kernel queues what fits and drops the rest.
  std::vector<std::uint8_t> p(1206, 0);
  for (int i = 0; i < 50; ++i) tx.send(rx.port(), p);
  rx.start();
  // The drop count travels with the next datagram queued after the drops: send marked ones until one gets in
  // (the first may still meet a full queue).
  p[0] = 1;
  std::uint64_t sent = 50;
  const auto marked_arrived = [&] {
    std::unique_lock lock(inbox.m);
    return inbox.cv.wait_for(lock, 20ms, [&] { return !inbox.payloads.empty() && inbox.payloads.back()[0] == 1; });
  };
  do {
    tx.send(rx.port(), p);
    ++sent;
  } while (!marked_arrived() && sent < 500);
  const auto c = rx.counters();
  EXPECT_GT(c.kernel_drops, 0u);
  EXPECT_EQ(c.datagrams + c.kernel_drops, sent);
}

TEST(Vlp16Udp, HandlerExceptionsAreCountedAndReceptionGoesOn) {
  RealClock clock;
  Inbox inbox;
  UdpReceiver rx(loopback(), clock, [&](Stamp t, std::span<const std::uint8_t> p) {
    inbox.push(t, p);
    if (p.size() == 1) throw std::runtime_error("bad datagram");
  });
  rx.start();
  Sender tx;
  const std::vector<std::uint8_t> one(1, 0), two(2, 0);
  tx.send(rx.port(), one);
  tx.send(rx.port(), two);
  ASSERT_TRUE(inbox.wait_for(2));
  EXPECT_EQ(rx.counters().handler_errors, 1u);
  EXPECT_EQ(rx.counters().datagrams, 2u);
}

TEST(Vlp16Udp, BindErrorsNameAddressAndPort) {
  RealClock clock;
  const auto noop = [](Stamp, std::span<const std::uint8_t>) {};
  UdpReceiver first(loopback(), clock, noop);
  auto same = loopback();
  same.port = first.port();
  try {
    UdpReceiver second(same, clock, noop);
    ADD_FAILURE() << "second bind to the same port succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(first.port())), std::string::npos) << e.what();
  }
  auto bad = loopback();
  bad.address = "not-an-address";
  EXPECT_THROW(UdpReceiver(bad, clock, noop), std::runtime_error);
}

TEST(Vlp16Udp, RecordedCaptureReplayedOverUdpDecodesLikeTheFile) {
  RealClock clock;
  std::mutex m;
  std::size_t points = 0, packets = 0;
  std::condition_variable cv;
  Vlp16Config config;
  std::uint64_t scans_points = 0;
  Vlp16ScanBuilder builder(config, [&](Scan&& s) { scans_points += s.points.size(); });
  UdpReceiver rx(loopback(), clock, [&](Stamp t, std::span<const std::uint8_t> p) {
    std::lock_guard lock(m);
    builder.on_data_packet(t, p);  // decoding on the receive thread, as the daemon may do
    points += builder.last_returns().size();
    ++packets;
    cv.notify_all();
  });
  rx.start();

  Sender tx;
  PcapReader reader("../shared/data/vlp16/velodyne_vlp16.pcap", {2368});
  UdpDatagram d;
  std::size_t sent = 0;
  while (reader.next(d)) {
    tx.send(rx.port(), d.payload);
    ++sent;
  }
  {
    std::unique_lock lock(m);
    ASSERT_TRUE(cv.wait_for(lock, 10s, [&] { return packets >= sent; }));
  }
  rx.stop();
  builder.flush();  // the receive thread has stopped: the builder is ours now
  EXPECT_EQ(sent, 84u);
  EXPECT_EQ(points, 19579u);
  EXPECT_EQ(scans_points, 19579u);
  EXPECT_EQ(builder.decode_counters().rejected(), 0u);
  EXPECT_EQ(rx.counters().kernel_drops, 0u);
}

}  // namespace
}  // namespace fsd

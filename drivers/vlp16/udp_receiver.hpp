#pragma once
// A UDP receiver for sensor datagrams (VLP-16 data and position packets) on Boost.Asio.
//
// Threading: the receiver owns one thread that runs its own io_context; start() spawns it, stop() (or the
// destructor) stops it and joins, promptly, also when no datagram ever arrives. The handler runs on that thread
// with the receive time read from the given Clock and must return quickly (hand the bytes to a bounded queue or
// decode in place); an exception thrown by it is caught and counted, never propagated.
//
// The socket gets a large receive buffer (SO_RCVBUFFORCE when permitted, else SO_RCVBUF capped by
// net.core.rmem_max) and the kernel's per-socket drop counter (SO_RXQ_OVFL), so drops in the kernel are counted
// exactly. The VLP-16 sends to the broadcast address by default: bind to 0.0.0.0 (or ::) to receive it; a socket
// bound to a unicast address gets only datagrams addressed to it.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>

#include "common/time.hpp"

namespace fsd {

class Clock;

struct UdpReceiverCounters {
  std::uint64_t datagrams = 0;  // delivered to the handler
  std::uint64_t bytes = 0;
  std::uint64_t kernel_drops = 0;    // dropped by the kernel for lack of buffer space (SO_RXQ_OVFL)
  std::uint64_t truncated = 0;       // larger than 64 KiB (cannot happen for UDP over IPv4), not delivered
  std::uint64_t errors = 0;          // socket errors
  std::uint64_t handler_errors = 0;  // exceptions thrown by the handler
};

class UdpReceiver {
 public:
  using Handler = std::function<void(Stamp receive_time, std::span<const std::uint8_t> payload)>;
  struct Options {
    std::string address = "0.0.0.0";
    std::uint16_t port = 0;  // 0 = ephemeral (tests)
    int receive_buffer_bytes = 4 << 20;
    std::string name = "udp";  // for log messages, e.g. "vlp16 data"
  };

  // Opens and binds the socket at once; throws std::runtime_error naming address, port and the reason.
  UdpReceiver(Options options, const Clock& clock, Handler handler);
  ~UdpReceiver();
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;

  void start();  // spawns the receive thread (once)
  void stop();   // idempotent; joins the thread. Not from inside the handler.

  std::uint16_t port() const;            // the bound port (resolves 0)
  int receive_buffer_bytes() const;      // what the kernel granted (Linux reports twice the payload space)
  UdpReceiverCounters counters() const;  // thread-safe snapshot

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd

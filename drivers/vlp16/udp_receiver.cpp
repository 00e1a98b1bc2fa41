#include "drivers/vlp16/udp_receiver.hpp"

#include <sys/socket.h>
#include <sys/types.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <thread>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/address.hpp>
#include <boost/asio/ip/udp.hpp>

#include "common/clock.hpp"
#include "common/logging.hpp"

namespace fsd {

namespace asio = boost::asio;
using asio::ip::udp;

struct UdpReceiver::Impl {
  Options options;
  const Clock& clock;
  Handler handler;
  asio::io_context io;
  udp::socket socket{io};
  std::thread thread;
  std::atomic<bool> started{false};
  int granted_buffer = 0;
  std::array<std::uint8_t, 65536> buffer{};

  std::atomic<std::uint64_t> datagrams{0}, bytes{0}, kernel_drops{0}, truncated{0}, errors{0}, handler_errors{0};

  Impl(Options o, const Clock& c, Handler h) : options(std::move(o)), clock(c), handler(std::move(h)) {}

  std::string where() const { return options.name + " " + options.address + ":" + std::to_string(options.port); }

  void open() {
    boost::system::error_code ec;
    const auto address = asio::ip::make_address(options.address, ec);
    if (ec) throw std::runtime_error(where() + ": invalid address: " + ec.message());
    const udp::endpoint endpoint(address, options.port);
    socket.open(endpoint.protocol(), ec);
    if (!ec) socket.bind(endpoint, ec);
    if (ec) throw std::runtime_error(where() + ": cannot bind: " + ec.message());
    socket.non_blocking(true, ec);
    if (ec) throw std::runtime_error(where() + ": cannot make non-blocking: " + ec.message());

    const int fd = socket.native_handle();
    const int want = options.receive_buffer_bytes;
    if (setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &want, sizeof want) != 0)  // needs CAP_NET_ADMIN
      setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &want, sizeof want);
    socklen_t len = sizeof granted_buffer;
    getsockopt(fd, SOL_SOCKET, SO_RCVBUF, &granted_buffer, &len);
    if (granted_buffer / 2 < want)
      logger("udp")->warn("{}: receive buffer {} B granted of {} B requested; raise net.core.rmem_max", where(),
                          granted_buffer / 2, want);
    const int on = 1;
    setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on);
  }

  void arm() {
    socket.async_wait(udp::socket::wait_read, [this](const boost::system::error_code& ec) {
      if (ec == asio::error::operation_aborted) return;
      if (ec) {
        ++errors;
      } else {
        drain();
      }
      arm();
    });
  }

  // Reads every datagram queued on the socket (non-blocking recvmsg to get the drop counter alongside).
  void drain() {
    const int fd = socket.native_handle();
    for (;;) {
      iovec iov{buffer.data(), buffer.size()};
      alignas(cmsghdr) std::array<char, CMSG_SPACE(sizeof(std::uint32_t))> control{};
      msghdr msg{};
      msg.msg_iov = &iov;
      msg.msg_iovlen = 1;
      msg.msg_control = control.data();
      msg.msg_controllen = control.size();
      const ssize_t n = recvmsg(fd, &msg, MSG_DONTWAIT);
      if (n < 0) {
        if (errno == EINTR) continue;
        if (errno != EAGAIN && errno != EWOULDBLOCK) ++errors;
        return;
      }
      const Stamp now = clock.now();
      for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c)) {
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
          std::uint32_t dropped = 0;
          std::memcpy(&dropped, CMSG_DATA(c), sizeof dropped);
          kernel_drops = dropped;  // cumulative count of the socket
        }
      }
      if (msg.msg_flags & MSG_TRUNC) {
        ++truncated;
        continue;
      }
      ++datagrams;
      bytes += static_cast<std::uint64_t>(n);
      try {
        handler(now, std::span<const std::uint8_t>(buffer.data(), static_cast<std::size_t>(n)));
      } catch (const std::exception& e) {
        if (++handler_errors == 1) logger("udp")->error("{}: handler failed: {}", where(), e.what());
      } catch (...) {
        ++handler_errors;
      }
    }
  }
};

UdpReceiver::UdpReceiver(Options options, const Clock& clock, Handler handler)
    : impl_(std::make_unique<Impl>(std::move(options), clock, std::move(handler))) {
  impl_->open();
}

UdpReceiver::~UdpReceiver() { stop(); }

void UdpReceiver::start() {
  if (impl_->started.exchange(true)) return;
  impl_->arm();
  impl_->thread = std::thread([impl = impl_.get()] { impl->io.run(); });
}

void UdpReceiver::stop() {
  impl_->io.stop();
  if (impl_->thread.joinable() && impl_->thread.get_id() != std::this_thread::get_id()) impl_->thread.join();
}

std::uint16_t UdpReceiver::port() const {
  boost::system::error_code ec;
  const auto ep = impl_->socket.local_endpoint(ec);
  return ec ? 0 : ep.port();
}

int UdpReceiver::receive_buffer_bytes() const { return impl_->granted_buffer; }

UdpReceiverCounters UdpReceiver::counters() const {
  UdpReceiverCounters c;
  c.datagrams = impl_->datagrams;
  c.bytes = impl_->bytes;
  c.kernel_drops = impl_->kernel_drops;
  c.truncated = impl_->truncated;
  c.errors = impl_->errors;
  c.handler_errors = impl_->handler_errors;
  return c;
}

}  // namespace fsd

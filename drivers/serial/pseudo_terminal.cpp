#include "drivers/serial/pseudo_terminal.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <system_error>

namespace fsd {

PseudoTerminal::PseudoTerminal() {
  char name[256] = {};
  termios raw{};
  ::cfmakeraw(&raw);
  raw.c_cflag |= CLOCAL | CREAD;
  if (::openpty(&master_, &slave_, name, &raw, nullptr) != 0)
    throw std::system_error(errno, std::generic_category(), "openpty");
  slave_path_ = name;
  const int flags = ::fcntl(master_, F_GETFL);
  ::fcntl(master_, F_SETFL, flags | O_NONBLOCK);
  ::fcntl(master_, F_SETFD, FD_CLOEXEC);
  ::fcntl(slave_, F_SETFD, FD_CLOEXEC);
}

PseudoTerminal::~PseudoTerminal() { close(); }

void PseudoTerminal::close() {
  if (master_ >= 0) ::close(master_);
  if (slave_ >= 0) ::close(slave_);
  master_ = slave_ = -1;
}

std::size_t PseudoTerminal::write(std::span<const std::uint8_t> bytes) {
  std::size_t done = 0;
  while (master_ >= 0 && done < bytes.size()) {
    const ssize_t n = ::write(master_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;  // EAGAIN: the driver is not reading; EIO: nobody holds the slave
    }
  }
  dropped_ += bytes.size() - done;
  return done;
}

std::size_t PseudoTerminal::read(std::span<std::uint8_t> buf, Duration timeout) {
  if (master_ < 0 || buf.empty()) return 0;
  pollfd p{master_, POLLIN, 0};
  const int ms = timeout <= 0 ? 0 : static_cast<int>(std::ceil(timeout * 1000.0));
  if (::poll(&p, 1, ms) <= 0 || !(p.revents & POLLIN)) return 0;
  const ssize_t n = ::read(master_, buf.data(), buf.size());
  return n > 0 ? static_cast<std::size_t>(n) : 0;
}

}  // namespace fsd

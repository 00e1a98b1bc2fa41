#include "drivers/serial/tty_baud.hpp"

#include <asm/termbits.h>
#include <sys/ioctl.h>

#include <cerrno>
#include <cstring>

namespace fsd {

std::string set_tty_baud(int fd, int baud) {
  if (baud <= 0) return "baud rate must be positive";
  termios2 t{};
  if (ioctl(fd, TCGETS2, &t) != 0) return std::string("TCGETS2: ") + std::strerror(errno);
  t.c_cflag &= ~static_cast<tcflag_t>(CBAUD | (CBAUD << IBSHIFT));
  t.c_cflag |= BOTHER | (BOTHER << IBSHIFT);
  t.c_ispeed = static_cast<speed_t>(baud);
  t.c_ospeed = static_cast<speed_t>(baud);
  if (ioctl(fd, TCSETS2, &t) != 0) return std::string("TCSETS2: ") + std::strerror(errno);
  return {};
}

std::optional<int> tty_baud(int fd) {
  termios2 t{};
  if (ioctl(fd, TCGETS2, &t) != 0) return std::nullopt;
  return static_cast<int>(t.c_ospeed);
}

}  // namespace fsd

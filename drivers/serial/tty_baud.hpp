#pragma once
// Any baud rate on Linux: termios only knows the B* constants, termios2 with BOTHER takes an integer rate.
// Kept in its own file because <asm/termbits.h> cannot share a translation unit with <termios.h> (and Asio).
#include <optional>
#include <string>

namespace fsd {

// Sets input and output speed of an open tty to `baud`. Empty string on success, else the reason.
std::string set_tty_baud(int fd, int baud);
// The output speed the kernel holds for the tty, in baud.
std::optional<int> tty_baud(int fd);

}  // namespace fsd

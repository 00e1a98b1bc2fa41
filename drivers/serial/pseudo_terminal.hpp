#pragma once
// A pseudo-terminal pair (openpty) in raw mode: the virtual car holds the master end and plays the device, the
// driver opens the slave path as if it were a serial port (DESIGN.md §6). The slave end is kept open here too, so
// the pty survives the driver closing and reopening it; close() makes the device disappear for the driver.
#include <cstdint>
#include <span>
#include <string>

#include "common/time.hpp"

namespace fsd {

class PseudoTerminal {
 public:
  PseudoTerminal();  // throws std::system_error when no pty is available
  ~PseudoTerminal();
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;

  int master_fd() const { return master_; }
  const std::string& slave_path() const { return slave_path_; }
  bool is_open() const { return master_ >= 0; }

  // Writes what fits without blocking; the rest is dropped and counted, like a UART with a full FIFO.
  std::size_t write(std::span<const std::uint8_t> bytes);
  // Waits up to `timeout` for bytes from the driver; returns how many were read (0 on timeout or when closed).
  std::size_t read(std::span<std::uint8_t> buf, Duration timeout);
  // Closes both ends: the slave path disappears and the driver's reads fail.
  void close();
  std::uint64_t dropped() const { return dropped_; }

 private:
  int master_ = -1;
  int slave_ = -1;
  std::string slave_path_;
  std::uint64_t dropped_ = 0;
};

}  // namespace fsd

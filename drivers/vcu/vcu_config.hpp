#pragma once
// Configuration of the daemon's VCU link (section "drivers.vcu").
#include <string>

#include "common/config.hpp"

namespace fsd {

struct VcuLinkConfig {
  std::string device = "/dev/ttyVCU";  // serial device (deploy/ udev rule makes this symlink) or a pty slave
  int baud = 115200;
  double rate_hz = 100.0;        // Command/heartbeat frames per second (the VCU needs ≥ 50)
  double timeout = 0.1;          // s without a valid Status before the link is declared lost
  double command_timeout = 0.2;  // s without a new ControlCommand before the link sends safe commands instead
  int reopen_ms = 200;           // retry period while the serial device is missing
  int stop_frames = 3;           // safe Commands (speed 0, brake) sent on stop() before the port closes
};

const ConfigSection<VcuLinkConfig>& vcu_section();

}  // namespace fsd

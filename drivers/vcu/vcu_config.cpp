#include "drivers/vcu/vcu_config.hpp"

namespace fsd {

const ConfigSection<VcuLinkConfig>& vcu_section() {
  static const auto s =
      ConfigSection<VcuLinkConfig>("drivers.vcu")
          .string("device", &VcuLinkConfig::device, {}, "Serial device of the VCU (RS-232; a pty slave in sim).")
          .integer("baud", &VcuLinkConfig::baud, 1200, 4000000, "baud", "Line rate, 8N1; any rate the UART supports.")
          .number("rate_hz", &VcuLinkConfig::rate_hz, 50.0, 1000.0, "Hz",
                  "Rate of Command frames, which are also the heartbeat the VCU watches (≥ 50 Hz).")
          .number("timeout", &VcuLinkConfig::timeout, 0.02, 2.0, "s",
                  "No valid Status from the VCU for this long raises the link-lost fault.")
          .number("command_timeout", &VcuLinkConfig::command_timeout, 0.02, 2.0, "s",
                  "A ControlCommand older than this is not sent: the link commands speed 0 with brake instead.")
          .integer("reopen_ms", &VcuLinkConfig::reopen_ms, 10, 10000, "ms",
                   "Retry period for reopening a lost serial device.")
          .integer("stop_frames", &VcuLinkConfig::stop_frames, 1, 50, "",
                   "Safe Commands (speed 0, brake) sent at the command rate on shutdown before the port closes.");
  return s;
}

}  // namespace fsd

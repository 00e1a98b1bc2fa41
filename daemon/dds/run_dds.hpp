#pragma once
// DDS in a feeder of the Stack (`fsd run --sim` and `fsd run` on the car): the bridge that publishes the run's
// topics when dds.enabled, and with run.perception_source = dds the perception process's frames into the Stack.
// With the virtual car in split mode it also sends what a perception computer would get from the sensors: the
// VLP-16's packets over UDP (dds.sim_lidar_address/port) and the camera's frames on /fsd/camera/image/compressed.
// Everything is called from the feeder's loop thread; nothing here blocks it (the UDP socket is non-blocking, the
// bridge's writes happen on its own thread).
#include <cstdint>
#include <memory>
#include <span>

#include "common/config.hpp"
#include "common/time.hpp"

namespace fsd {
class Stack;
}

namespace fsd::dds {

class RunDds {
 public:
  // Null when the run needs no DDS (dds.enabled false and another perception source). Throws
  // std::invalid_argument naming the dds.* key that is wrong. `simulator`: the virtual car's split-mode senders.
  static std::unique_ptr<RunDds> make(const Config& cfg, bool simulator);
  ~RunDds();

  // Before the first cycle: taps the Stack; `epoch` is the Unix time of the run clock's zero.
  void start(Stack& stack, double epoch);
  // Each cycle before Stack::step: the perception process's frames that arrived.
  void before_step(Stack& stack);
  // The virtual car's sensors (split mode with the simulator).
  void lidar_packet(std::span<const std::uint8_t> bytes);
  void camera_frame(Stamp capture, std::span<const std::uint8_t> jpeg);
  // After the loop: the bridge writes what is queued and stops. Idempotent.
  void stop();
  // The log line of what went over DDS.
  std::string summary() const;

 private:
  struct Impl;
  explicit RunDds(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd::dds

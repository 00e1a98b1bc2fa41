#pragma once
// `fsd run --role perception`: split mode's perception computer (docs/dds.md). The LiDAR and camera stages run
// here, on this computer's sensors, and their frames go to the computer that drives:
//
//   VLP-16 UDP (drivers.vlp16.*) ─► UdpReceiver thread ─┐
//   /fsd/odom (nav_msgs/Odometry) ─► Fast DDS thread ────┼─► bounded queues ─► perception thread: scan builder,
//   camera: /fsd/camera/image/compressed, or the camera ─┘                     LiDAR + camera stages
//           driver when drivers.camera.enabled                                      │
//                          /fsd/perception/detections, cones, cone_markers, /fsd/lidar/points ◄─ the Outbox thread
//
// Each scan waits for a pose past its last firing (the driving side's poses place its points: deskew and
// accumulation), at most kPoseWait; without any pose the scan is dropped (counted). The camera stage runs when the
// camera's calibration is known (drivers.camera.calibration, else the virtual car's camera, sim.camera.*) unless
// run.perception_source = lidar. Stamps go out as Unix time, so the driving side places each frame by its own
// pose of that instant. Runs until SIGINT/SIGTERM.
#include <atomic>
#include <functional>
#include <memory>

#include "common/config.hpp"
#include "daemon/cli/run_options.hpp"

namespace fsd::dds {

class PerceptionRole {
 public:
  // Checks and binds what it can before anything runs (the LiDAR's port, the camera's model and calibration);
  // throws std::invalid_argument naming the key.
  PerceptionRole(const Config& config, const RunOptions& options);
  ~PerceptionRole();
  int run(const std::atomic<bool>& stop);
  // Called by the perception thread after each pass, the drivers up (the service's READY, then WATCHDOG).
  void on_loop(std::function<void()> loop);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd::dds

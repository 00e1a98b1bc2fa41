#pragma once
// The main daemon's DDS bridge (docs/dds.md): a StackTap that publishes what the Stack made of each cycle as ROS 2
// topics, from its own writer thread (Outbox). The control thread only copies shared pointers into the outbox; the
// conversion and the write happen on the bridge's thread, so the loop never waits on DDS (DESIGN.md §4).
//
//   every cycle (100 Hz)      /fsd/odom                      nav_msgs/Odometry (the pose perception places scans by)
//   every snapshot (25 Hz)    /fsd/control/command           ackermann_msgs/AckermannDriveStamped
//                             /fsd/as/status                 fsd_msgs/AsStatus
//   each new scan (10 Hz)     /fsd/lidar/points              sensor_msgs/PointCloud2
//   each perception frame     /fsd/perception/detections     fsd_msgs/ConeDetections
//                             /fsd/perception/cones          eufs_msgs/ConeArrayWithCovariance
//                             /fsd/perception/cone_markers   visualization_msgs/MarkerArray
//   the cone map (2 Hz)       /fsd/map/cones, /fsd/map/cone_markers
//   each lap, each fault      /fsd/laps, /fsd/faults         fsd_msgs/LapEvent, fsd_msgs/Fault
// Nothing is read back: the bridge can neither change a parameter nor command the car.
#include <memory>
#include <set>
#include <string>

#include "daemon/dds/dds_settings.hpp"
#include "daemon/stack/raw_frame.hpp"

namespace fsd {
class Stack;
}

namespace fsd::dds {

class Participant;

struct BridgeCounters {
  std::uint64_t published = 0;  // messages written
  std::uint64_t dropped = 0;    // jobs the outbox dropped (its thread fell behind)
};

class DdsBridge final : public StackTap {
 public:
  // Creates the participant and the writers of the topics in dds.topics; `without`: topics another process
  // publishes (split mode: the perception process's cloud and detections). Throws std::invalid_argument naming
  // the dds.* key that is wrong.
  DdsBridge(const DdsSettings& settings, const std::set<std::string>& without = {});
  ~DdsBridge() override;
  DdsBridge(const DdsBridge&) = delete;
  DdsBridge& operator=(const DdsBridge&) = delete;

  // Taps `stack` (its state after each cycle, its snapshots). `epoch`: the Unix time of the run clock's zero.
  void attach(Stack& stack, double epoch);
  // The virtual car's camera frames for a perception process (split mode): the topic opened before the run, then
  // each frame from the thread that steps the car (nothing before the topic is open).
  void open_camera_topic();
  void publish_camera(std::shared_ptr<const std::vector<std::uint8_t>> jpeg, Stamp capture);
  Participant& participant();
  BridgeCounters counters() const;
  // Writes what is queued and stops the thread (before the Stack goes). Idempotent.
  void stop();

  void on_frame(const RawFrame&) override {}
  void on_cycle(Stamp) override {}
  void on_output(Stamp now, const ControlCommand& command, wire::vcu::AsRequest request) override;
  bool wants_snapshots() const override { return true; }
  void on_snapshot(const std::shared_ptr<const TelemetrySnapshot>& snapshot) override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fsd::dds

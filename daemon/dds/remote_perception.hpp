#pragma once
// Split mode, the driving side (run.perception_source = dds): the perception process's frames
// (/fsd/perception/detections, fsd_msgs/ConeDetections) from the network. Each sample is decoded by Fast DDS on its
// own thread, checked whole (ros_messages.hpp: finite, bounded, known values, the right frame) and handed to the
// control thread through a bounded queue; a refused sample is counted and logged (at most once a second), never
// used. Stamps arrive as Unix time and are put on this run's clock.
#include <atomic>
#include <memory>
#include <optional>

#include "common/bounded_queue.hpp"
#include "daemon/dds/ros_messages.hpp"

namespace fsd::dds {

class Participant;

struct RemotePerceptionCounters {
  std::uint64_t received = 0, refused = 0, dropped = 0;
};

class RemotePerception {
 public:
  explicit RemotePerception(Participant& participant);
  ~RemotePerception();
  RemotePerception(const RemotePerception&) = delete;
  RemotePerception& operator=(const RemotePerception&) = delete;
  // The Unix time of this run clock's zero (ros_time.hpp), before frames are used.
  void set_epoch(double epoch);
  // The oldest frame not taken yet (the control thread).
  std::optional<RemoteDetections> poll();
  RemotePerceptionCounters counters() const;

 private:
  struct Listener;
  std::unique_ptr<Listener> listener_;
};

}  // namespace fsd::dds

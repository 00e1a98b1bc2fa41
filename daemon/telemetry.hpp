#pragma once
// Telemetry for the dashboard: the control loop hands a snapshot of what it knows to a latest-value slot and
// returns at once; a telemetry thread of its own turns the newest snapshot into the web channels' messages at
// each channel's rate. So the control loop never waits on JSON, the network or a slow client (DESIGN.md §4).
#include <atomic>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "common/bounded_queue.hpp"
#include "common/types.hpp"
#include "web/channels.hpp"

namespace fsd {

namespace web {
class WebServer;
}

struct TelemetrySnapshot {
  Stamp t = 0;
  VehicleState state;
  double target_speed = 0;
  std::shared_ptr<const std::vector<Cone>> cone_map;      // map frame
  std::shared_ptr<const ConeDetections> detections;       // vehicle frame
  std::shared_ptr<const web::PathSet> paths;
  std::shared_ptr<const Scan> scan;                       // sensor frame
  std::shared_ptr<const std::vector<std::uint8_t>> camera_jpeg;  // the newest camera frame as sent
  Pose3 lidar_pose = Pose3::Identity();                   // map ← sensor at the scan
  web::AsStatusView as;
  std::vector<web::FaultEvent> faults;
};

struct TelemetryRates {
  double state_hz = 25, car_hz = 25, scene_hz = 4, cloud_hz = 2, status_hz = 5, camera_hz = 5;
};

class Telemetry {
 public:
  Telemetry(web::WebServer& server, TelemetryRates rates = {});
  ~Telemetry();  // stops the thread
  void publish(TelemetrySnapshot snapshot);  // never blocks
  void stop();

 private:
  void loop();
  web::WebServer& server_;
  web::StandardChannels ch_;
  TelemetryRates rates_;
  LatestValue<std::shared_ptr<const TelemetrySnapshot>> latest_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace fsd

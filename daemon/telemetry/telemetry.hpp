#pragma once
// Telemetry for the dashboard: the control loop hands a snapshot of what it knows to a latest-value slot and
// returns at once; a telemetry thread of its own turns the newest snapshot into the web channels' messages at
// each channel's rate. So the control loop never waits on JSON, the network or a slow client (DESIGN.md §4).
// It also answers /api/state from the newest snapshot, counts the snapshots it skipped (/metrics), and
// forwards the daemon's log lines to the /log channel (LogForwarding).
#include <atomic>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include <spdlog/sinks/sink.h>

#include "common/bounded_queue.hpp"
#include "common/types.hpp"
#include "web/channels.hpp"
#include "web/metrics.hpp"

namespace fsd {

class Clock;

namespace web {
class WebServer;
}

// Perception's split of a scan (vehicle frame, deskewed, at `stamp`): the ground and what was clustered.
struct LabelledCloud {
  Stamp stamp = 0;
  std::vector<Point> ground, obstacles;
};

struct TelemetrySnapshot {
  Stamp t = 0;
  VehicleState state;  // the stack's own estimate (what it drives on)
  double target_speed = 0;
  std::shared_ptr<const std::vector<Cone>> cone_map;  // map frame
  std::shared_ptr<const ConeDetections> detections;   // vehicle frame
  std::optional<Pose2> detections_pose;               // the car's estimated pose at detections->stamp
  std::shared_ptr<const web::PathSet> paths;
  std::shared_ptr<const Scan> scan;                              // sensor frame
  std::shared_ptr<const LabelledCloud> cloud;                    // perception's split of the newest scan, if any
  Pose3 cloud_pose = Pose3::Identity();                          // map ← vehicle at cloud->stamp
  std::shared_ptr<const std::vector<std::uint8_t>> camera_jpeg;  // the newest camera frame as sent
  Pose3 lidar_pose = Pose3::Identity();                          // map ← sensor at the scan
  web::AsStatusView as;
  std::vector<web::FaultEvent> faults;
  // The localization's own view (source, quality, covariance) once the stack has a state; its loop closures.
  std::optional<web::LocalizationView> localization;
  std::vector<web::LoopClosureEvent> loop_closures;
  // Sim runs only: the simulator's ground truth, published on /truth/* (never mixed into the channels above).
  std::optional<web::TruthState> truth;
  std::shared_ptr<const std::vector<web::TruthCone>> truth_cones;  // a new pointer when a cone fell
  std::shared_ptr<const std::vector<Vec2>> truth_path;  // the true driven path, a new pointer when it grew
};

class Telemetry {
 public:
  // Adds the channels of the channel table (daemon/telemetry/telemetry_channels.hpp) and publishes them at their live
  // rates. `truth`: also the /truth/* channels (sim runs); `car`: the body drawn on /car and /truth/car. The
  // server must outlive the Telemetry.
  Telemetry(web::WebServer& server, bool truth = false, web::CarShape car = {});
  ~Telemetry();                                                     // stops the thread
  void publish(std::shared_ptr<const TelemetrySnapshot> snapshot);  // never blocks
  void stop();
  web::ChannelId channel(const std::string& topic) const { return ids_.at(topic); }

 private:
  void loop();
  web::WebServer& server_;
  bool truth_;
  web::ChannelIds ids_;
  web::CarShape car_;
  using Slot = LatestValue<std::shared_ptr<const TelemetrySnapshot>>;
  std::shared_ptr<Slot> latest_ = std::make_shared<Slot>();  // shared with the /api/state provider
  web::Counter& published_;
  web::Counter& skipped_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Sends the lines of every spdlog logger (those that exist now and those fsd::logger() creates later) to the
// /log channel as well, at `level` and above. Attach while no other thread logs (spdlog's sink lists are not
// thread-safe to change): before the server starts and the run's threads run; likewise detach() after they
// stopped and before the server goes away. The destructor detaches.
class LogForwarding {
 public:
  LogForwarding(web::WebServer& server, web::ChannelId log_channel, const Clock& clock,
                spdlog::level::level_enum level = spdlog::level::info);
  // Any sink (web::make_log_sink with a handler: the recorder's).
  explicit LogForwarding(std::shared_ptr<spdlog::sinks::sink> sink);
  ~LogForwarding();
  LogForwarding(const LogForwarding&) = delete;
  LogForwarding& operator=(const LogForwarding&) = delete;
  void detach();

 private:
  std::shared_ptr<spdlog::sinks::sink> sink_;
};

}  // namespace fsd

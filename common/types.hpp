#pragma once
// The data types that flow between the parts of the stack (DESIGN.md §3). Plain structs, SI units, radians,
// vehicle frame x forward / y left / z up with origin at the rear-axle centre on the ground.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/geometry.hpp"
#include "common/time.hpp"

namespace fsd {

// One LiDAR return in the sensor frame.
struct Point {
  float x = 0, y = 0, z = 0;
  float intensity = 0;     // reflectivity 0..255
  std::uint16_t ring = 0;  // laser index 0..15, sorted by elevation bottom-up
  float azimuth = 0;       // radians, sensor convention (clockwise from +x seen from above)
  float distance = 0;      // metres
  Stamp t = 0;             // time of the firing
};

// One revolution (or a cut of it) of the LiDAR.
struct Scan {
  Stamp stamp = 0;  // time of the first firing
  std::uint32_t seq = 0;
  std::vector<Point> points;
};

// The earliest and latest firing times of a scan's points (both `stamp` when it has none).
struct FiringSpan {
  Stamp first = 0, last = 0;
};
FiringSpan firing_span(const Scan& scan);

// Physical colour of a cone as a camera sees it.
enum class ConeColour : std::uint8_t { Unknown = 0, Blue, Yellow, Orange, BigOrange, Red };
std::string_view to_string(ConeColour c);
std::optional<ConeColour> cone_colour_from_string(std::string_view s);

// Which boundary a cone marks; derived from its colour through the event's colour convention.
enum class ConeRole : std::uint8_t { Unknown = 0, Left, Right, Timing, Other };
std::string_view to_string(ConeRole r);

// The last perception stage a detection passed (DESIGN.md §5b): LiDAR alone (unverified: the camera was down or
// the cone outside the image), or verified by the camera's classifier. Truth: the simulator's ideal detector.
enum class DetectionStage : std::uint8_t { Truth = 0, Lidar, Camera };
std::string_view to_string(DetectionStage s);

// Where a detection's colour came from.
enum class ColourSource : std::uint8_t { None = 0, Truth, Camera, LidarIntensity };
std::string_view to_string(ColourSource s);

struct Cone {
  Vec3 position = Vec3::Zero();  // frame named by the container (map or vehicle)
  ConeColour colour = ConeColour::Unknown;
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity() * 0.01;  // x/y, m²
  double confidence = 1.0;                                          // 0..1 detection or mapping confidence
  std::uint32_t id = 0;                                             // stable id in a map, 0 for a raw detection
  // Detections only (0 / defaults in a map):
  double colour_confidence = 1.0;  // 0..1; Unknown colour when too low to name one
  ColourSource colour_source = ColourSource::Truth;
  DetectionStage stage = DetectionStage::Truth;
  std::uint32_t points = 0;  // LiDAR points of its cluster
};

struct ConeDetections {
  Stamp stamp = 0;
  std::vector<Cone> cones;  // vehicle frame
};

// Motion state of the car in the map frame.
struct VehicleState {
  Stamp stamp = 0;
  Pose2 pose;             // rear-axle centre in the map (local ENU at the start)
  double vx = 0, vy = 0;  // body-frame velocity at the rear axle, m/s
  double yaw_rate = 0;    // rad/s
  double ax = 0, ay = 0;  // body-frame acceleration, m/s²
  double steering = 0;    // front wheel angle, rad (left positive)
  double speed() const;
  double sideslip() const;  // β = atan2(vy, vx), 0 at standstill
  // The lateral acceleration the estimated motion implies where no sensor measures it: vx·r (the rate of vy is small
  // beside it while the tyres grip).
  double kinematic_ay() const { return vx * yaw_rate; }
};

// What the stack asks of the VCU.
struct ControlCommand {
  Stamp stamp = 0;
  double steering = 0;      // front wheel angle, rad (left positive)
  double target_speed = 0;  // m/s, ≥ 0
  bool brake_hard = false;  // request maximum service braking (controlled stop)
};

// GNSS-INS fix after NMEA parsing; position in local ENU of the configured origin.
struct GnssSample {
  Stamp stamp = 0;
  double lat_deg = 0, lon_deg = 0, alt_m = 0;  // antenna as reported; alt_m above the WGS-84 ellipsoid
  Vec3 enu = Vec3::Zero();                     // rear-axle centre (lever arm removed)
  double speed = 0;                            // ground speed m/s
  double course = 0;                           // course over ground, rad, ENU (0 = east, CCW)
  double heading = 0;                          // vehicle yaw, rad, ENU
  double yaw_rate = 0;                         // rad/s
  double roll = 0, pitch = 0;                  // ISO 8855: roll positive right side down, pitch positive nose down
  bool velocity_valid = false;                 // speed (and course when moving) present in this epoch
  bool attitude_valid = false;                 // roll and pitch present in this epoch
  bool yaw_rate_valid = false;                 // yaw_rate present and valid in this epoch
  int fix_quality = 0;                         // GGA: 0 invalid, 1 single, 2 DGPS, 4 RTK fixed, 5 RTK float
  int satellites = 0;
  double hdop = 99.0;
  double age_s = 0;  // differential age
  bool heading_valid = false;
  double heading_sigma = 0;  // rad, 1σ of the heading as the receiver states it (PASHR); 0 when it does not
  bool good = false;         // usable for lap-2 tracking (fix quality, satellites, HDOP, age)
};

// Autonomous-system state owned by the VCU (FS rules).
enum class AsState : std::uint8_t { Off = 0, Ready = 1, Driving = 2, Emergency = 3, Finished = 4 };
std::string_view to_string(AsState s);
std::optional<AsState> as_state_from_string(std::string_view s);

enum class Mission : std::uint8_t { None = 0, Acceleration, Skidpad, Trackdrive, Autocross, Inspection, EbsTest };
std::string_view to_string(Mission m);
std::optional<Mission> mission_from_string(std::string_view s);

struct VcuStatus {
  Stamp stamp = 0;
  AsState as_state = AsState::Off;
  Mission mission = Mission::None;
  bool res_go = false;         // RES "go" seen
  bool res_emergency = false;  // RES emergency pressed
  bool ebs_active = false;
  double steering_measured = 0;          // rad
  std::array<double, 4> wheel_speeds{};  // m/s: FL, FR, RL, RR
  // The rear axle centre's forward speed (the vehicle frame's origin): the mean of the rear wheels.
  double rear_axle_speed() const { return 0.5 * (wheel_speeds[2] + wheel_speeds[3]); }
  std::uint32_t faults = 0;  // bit set, see docs/vcu-protocol.md
};

}  // namespace fsd

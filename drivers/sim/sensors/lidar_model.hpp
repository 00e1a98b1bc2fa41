#pragma once
// The virtual car's Velodyne VLP-16: ray casting into the World with the real laser table and firing timing,
// emitting the sensor's 1206-byte UDP payloads (common/wire/vlp16_format.hpp, DESIGN.md §6).
//
// Timing (VLP-16 manual ch. 9): a laser fires every 2.304 µs, a sequence of 16 every 55.296 µs, two sequences per
// data block and 12 blocks per packet, so 1327.104 µs per packet (753.5 packets/s at any rotation rate) and an
// azimuth step of 360°·f·55.296 µs per sequence (0.199° at 10 Hz). Each laser's ray is cast at the exact azimuth
// and from the exact vehicle pose of its own firing time (the pose sampled once per firing sequence), so a moving
// car's scan shows the motion distortion of a real spinning sensor.
//
// Sensor frame: x forward, y left, z up at the mount. A return of laser k (elevation ω, vertical offset v) at
// azimuth α (clockwise seen from above, 0 along +x) and distance d is the point
//   x = d·cosω·cosα,  y = −d·cosω·sinα,  z = d·sinω + v
// as the ROS velodyne driver computes it, i.e. the beam leaves the point (0, 0, v).
//
// Each return: distance in 2 mm units (0 = none), calibrated reflectivity 0..255 (the material's, scaled by
// 0.3 + 0.7·cos(incidence); on a cone the mean of its paints over the beam's vertical footprint, 9.5 mm at the
// sensor growing by 1.5 mrad: the manual's figures). Range noise is normal with σ = range_noise / 2, truncated at
// ±range_noise (the datasheet's "±3 cm typical" read as a 2σ bound). Returns are dropped with probability `dropout`
// and outside [min_range, max_range]. Noise and dropout of each firing are hashed from (seed, packet, channel):
// deterministic for a seed and independent of how the simulation is stepped.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "common/config.hpp"
#include "common/geometry.hpp"
#include "common/time.hpp"
#include "common/wire/vlp16_format.hpp"
#include "drivers/sim/sensors/sink.hpp"
#include "drivers/sim/world/world.hpp"

namespace fsd::sim {

struct LidarConfig {
  // Mount on the vehicle body frame (rear-axle centre on the ground): on the nose, ahead of the front wheels.
  // From the car's description (car.lidar) plus sim.mismatch.lidar_* (drivers/sim/vehicle/model_mismatch.hpp).
  double x = 2.0, y = 0.0, z = 0.35;
  double roll = 0.0, pitch = 0.0, yaw = 0.0;  // rad, Z-Y-X
  double rotation_hz = 10.0;
  double range_noise = 0.03;  // m, 2σ bound (see above)
  double dropout = 0.0;       // probability that a return is lost
  double max_range = 100.0;
  double min_range = 0.5;
  double latency = 0.0;                   // s from the last firing of a packet to its departure
  double beam_aperture = 0.0095;          // m: the beam's vertical size at the sensor
  double beam_divergence = 0.0015;        // rad: its vertical divergence (full angle)
  std::string return_mode = "strongest";  // "strongest" (0x37) or "last" (0x38); one surface per ray: same points
  int product_id = wire::vlp16::kProductVlp16;
};

const ConfigSection<LidarConfig>& lidar_section();  // prefix "sim.lidar"

// Body ← sensor transform of a mounting.
Pose3 lidar_mount(const LidarConfig& cfg);

// Returns the sensor sent from one world cone (the scorecard's recall_visible_15m: what the LiDAR could see).
struct ConeReturns {
  int cone = -1;    // index into World::cones()
  int returns = 0;  // returns sent (not dropped, in range) since the last take
  Stamp t = 0;      // the last of their firing times
};

class LidarModel {
 public:
  // `start` is the time of the first firing; the head points along the sensor's +x then.
  LidarModel(const LidarConfig& cfg, const World& world, std::uint64_t seed, Stamp start = 0.0);

  // Emits every packet whose firings all lie before t, stamped with its departure time (end of the packet plus
  // latency). body_pose_at(t) gives the vehicle body 3D pose (map ← body) at any firing time since the previous
  // call, e.g. VehicleTruth::body_pose3() interpolated by the caller.
  void advance_to(Stamp t, const std::function<Pose3(Stamp)>& body_pose_at, const ByteSink& sink);

  std::uint64_t packets_sent() const { return packets_; }
  // The cone returns of the packets emitted since the last call, one entry per cone (bounded: one per cone).
  std::vector<ConeReturns> take_cone_returns() { return std::exchange(cone_returns_, {}); }
  Stamp next_packet_start() const;
  const LidarConfig& config() const { return cfg_; }

 private:
  void build_packet(const std::function<Pose3(Stamp)>& body_pose_at);
  double azimuth_rad(Stamp t) const;
  void count_cone_return(int cone, Stamp t);

  LidarConfig cfg_;
  const World& world_;
  std::uint64_t seed_;
  Stamp start_;
  Pose3 mount_;
  std::uint8_t return_mode_;
  std::uint64_t packets_ = 0;
  std::array<double, wire::vlp16::kLasers> cos_elev_{}, sin_elev_{}, offset_{};
  double cos_step_ = 1.0, sin_step_ = 0.0;  // head rotation between two lasers' firings
  std::array<std::uint8_t, wire::vlp16::kPacketSize> packet_{};
  std::vector<ConeReturns> cone_returns_;
};

}  // namespace fsd::sim

#pragma once
// What the fusion filters take in (DESIGN.md §3 localization) and what they give out. Body frame x forward, y left,
// z up at the filter's reference point (the rear-axle centre on the car, the IMU in the AMZ 2017 logs); map frame a
// local ENU. All stamps on the run's clock, in seconds.
#include <cstdint>
#include <limits>
#include <string_view>
#include <variant>

#include <Eigen/Core>

#include "common/geometry.hpp"
#include "common/time.hpp"

namespace fsd::fusion {

// An IMU sample: angular rate (rad/s) and specific force (m/s²) in the body frame. The filters use gyro z.
struct ImuSample {
  Stamp t = 0;
  Vec3 gyro = Vec3::Zero();
  Vec3 acc = Vec3::Zero();
};

// Ground velocity measured by a sensor mounted at `lever` (body frame, from the reference point): an optical
// sensor (vx and vy, scaled by the filter's speed-scale estimate) or the wheels (vx only, taken at face value,
// used only while no optical sample arrives: they slip and their rpm factor is nominal).
// The filter moves it to the reference point with its yaw rate: v_ref = v_sensor − ω × lever.
struct BodySpeed {
  enum class Source : std::uint8_t { Optical, Wheels };
  Stamp t = 0;
  Source source = Source::Optical;
  double vx = 0, vy = 0;  // m/s at the sensor
  bool has_vy = true;     // wheels measure no lateral speed
  Vec2 lever = Vec2::Zero();
  // Wheels only: the kinematic yaw rate of their speed and the measured steering, vx·tan(δ)/L (NaN: unknown). The
  // filter takes it only while no gyro sample comes: a rough gyro (the tyres' slip makes the car turn less at the
  // limit) for when the GNSS-INS, the car's only gyro, falls silent.
  double kinematic_yaw_rate = std::numeric_limits<double>::quiet_NaN();
};

// A GNSS position of the reference point in the map frame (lever arm already removed), with what the receiver
// says of it. `sigma` ≤ 0: the configured σ of its fix quality.
struct GnssFix {
  Stamp t = 0;
  Vec2 position = Vec2::Zero();
  int fix_quality = 1;           // GGA: 0 invalid, 1 single, 2 DGPS, 4 RTK fixed, 5 RTK float
  double age_s = 0;              // differential age (0 for a single-point fix)
  double sigma = 0;              // m per horizontal axis
  bool heading_valid = false;    // a dual-antenna heading
  double heading = 0;            // rad, ENU
  double heading_sigma = 0;      // rad, as the receiver states it; ≤ 0: localization.fusion.gnss.heading_sigma
  bool velocity_valid = false;   // the receiver's velocity over ground (Doppler: RMC/VTG speed and course)
  Vec2 velocity = Vec2::Zero();  // m/s, ENU, of the point localization.fusion.ekf.gnss_velocity_lever_x names
};

// A relative pose from LiDAR odometry: the body at t1 seen from the body at t0, with its covariance over
// (x, y, yaw). The filters read it as the mean velocity and yaw rate over [t0, t1].
struct OdometryIncrement {
  Stamp t0 = 0, t1 = 0;
  Pose2 delta;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity() * 1e-4;
};

// The mean body velocity and yaw rate over an increment's interval (t1 > t0): the chord's direction is half the turn.
struct MeanTwist {
  double vx = 0, vy = 0, yaw_rate = 0;
};
MeanTwist mean_twist(const OdometryIncrement& o);

// The pose the cone map gives: one perception frame's cones laid onto the mapped ones (localization/map_match),
// moved to the filter's time. An absolute pose like a GNSS fix, but only as sure as the map it matched.
struct MapPose {
  Stamp t = 0;
  Pose2 pose;               // map frame
  double sigma = 0.1;       // m per horizontal axis
  double yaw_sigma = 0.02;  // rad
};

using Measurement = std::variant<ImuSample, BodySpeed, GnssFix, OdometryIncrement, MapPose>;
Stamp stamp_of(const Measurement& m);

// How far control can trust the pose: good (GNSS recently accepted, small covariance), degraded (dead reckoning
// through an outage or on down-weighted fixes: usable, growing covariance), lost (no heading yet, no motion input,
// or a covariance too large to drive on). Control falls back to real-time planning when it is not good.
enum class Quality : std::uint8_t { Good, Degraded, Lost };
std::string_view to_string(Quality q);

// The verdict on the latest GNSS fix.
enum class GnssVerdict : std::uint8_t {
  None,  // no fix seen yet
  Accepted,
  DownWeighted,        // used with an inflated σ: innovation beyond the soft gate, or stale differential corrections
  RejectedQuality,     // fix quality below the configured minimum
  RejectedStale,       // older than the filter's time by more than allowed
  RejectedInnovation,  // Mahalanobis distance beyond the gate
  RejectedJump,        // moved more than the dead-reckoned motion since the previous fix allows
  Waiting,             // held for the heading initialisation (the car moves, the heading is not known yet)
};
std::string_view to_string(GnssVerdict v);

struct GnssCounters {
  std::uint64_t fixes = 0, accepted = 0, down_weighted = 0, rejected = 0, jumps = 0;
};

struct LocalizationState {
  Stamp stamp = 0;
  bool initialised = false;  // position and heading known
  Pose2 pose;                // map frame
  double vx = 0, vy = 0;     // body-frame velocity at the reference point
  double yaw_rate = 0;
  double gyro_bias = 0;                                            // rad/s, z
  double speed_scale = 1;                                          // optical sensor reading / true speed
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity() * 1e6;  // over (x, y, yaw)
  Quality quality = Quality::Lost;
  GnssVerdict gnss = GnssVerdict::None;  // the latest fix's verdict
  double gnss_nis = 0;                   // its normalised innovation squared (0 when not computed)
  Stamp last_gnss_accepted = -1;         // < 0: never
  GnssCounters gnss_counters;
  std::uint64_t odometry_rejected = 0;   // LiDAR odometry increments the innovation gate turned away
  std::uint64_t map_poses_rejected = 0;  // map poses the gate turned away
  std::uint64_t headings_rejected = 0;   // receiver headings the gate turned away
  Stamp last_map_pose = -1;              // the newest map pose applied; < 0: never

  double position_sigma() const;  // m: √ of the larger eigenvalue of the position covariance
};

}  // namespace fsd::fusion

#pragma once
// The fusion filters' configuration: localization.fusion.* (which filter, heading initialisation, the state's
// quality thresholds), .gnss (the quality gate), .ekf and .complementary (their noise and time constants).
#include <string>

#include "common/config.hpp"

namespace fsd::fusion {

struct FusionCommonConfig {
  std::string filter = "ekf";           // ekf | complementary
  double heading_baseline_m = 10.0;     // GNSS track length that fixes the initial heading
  double moving_speed = 1.0;            // m/s: above it the car moves (heading from the track)
  double standstill_speed = 0.05;       // m/s: below it the car stands (the gyro reads its bias)
  double initial_heading_sigma = 0.05;  // rad: σ of the heading from the track
  double good_gnss_timeout_s = 1.0;     // the state is good only with a fix accepted this recently
  double good_sigma_m = 0.5;            // ... and a position σ below this
  double lost_sigma_m = 5.0;            // position σ beyond this: lost
  double motion_timeout_s = 0.5;        // no IMU or speed sample for this long: lost
  bool lidar_odometry = true;           // the daemon's fused source also takes the LiDAR odometry's increments
};
const ConfigSection<FusionCommonConfig>& fusion_common_section();

struct GnssGateConfig {
  int min_fix_quality = 1;         // GGA quality below this is rejected
  double sigma_single = 1.0;       // m per axis by fix quality: 1
  double sigma_dgps = 0.5;         // 2
  double sigma_rtk_float = 0.2;    // 5
  double sigma_rtk_fixed = 0.03;   // 4
  double max_age_s = 5.0;          // corrections older than this: the fix counts as single (down-weighted)
  double max_delay_s = 0.5;        // a fix older than the filter's time by more is stale
  double soft_gate_chi2 = 5.99;    // NIS beyond this (95 %, 2 dof): σ inflated by √(NIS / soft)
  double reject_gate_chi2 = 13.8;  // NIS beyond this (99.9 %): rejected
  double jump_min_m = 1.5;         // a fix may differ from the dead-reckoned motion since the previous fix by this
  double jump_fraction = 0.2;      // ... plus this share of that motion
  double recover_after_s = 3.0;    // fixes rejected (not jumps) for this long, mutually consistent: accepted again
  double heading_sigma = 0.005;    // rad: a dual-antenna heading's σ when the receiver does not state one (HDT)
};
const ConfigSection<GnssGateConfig>& gnss_gate_section();

struct EkfConfig {
  double gyro_sigma = 0.005;           // rad/s per sample
  double optical_sigma = 0.05;         // m/s per axis per sample
  double wheel_sigma = 0.3;            // m/s per sample ...
  double wheel_sigma_fraction = 0.05;  // ... plus this share of the speed (slip)
  double wheel_lateral_sigma = 0.5;    // m/s: the sideslip at the wheels' axle, held to 0 without optical vy
  double accel_noise = 8.0;            // m/s² /√Hz: random walk of vx and vy
  double yaw_accel_noise = 1.0;        // rad/s² /√Hz: random walk of the yaw rate (0.07 rad/s per 5 ms sample)
  double bias_walk = 2e-4;             // rad/s /√s
  double scale_walk = 2e-4;            // 1/√s
  double position_noise = 0.1;        // m/√s: what the kinematic model misses (slip of the contact patch, lever arms)
  double initial_bias_sigma = 0.01;   // rad/s
  double initial_scale_sigma = 0.03;  // optical speed scale
  double initial_slip_sigma = 0.005;  // rad/(m/s²): the rear slip compliance, from 0 (a kinematic rear axle)
  double slip_walk = 1e-5;            // rad/(m/s²)/√s
  double kinematic_rate_sigma = 0.05;     // rad/s: the wheels' kinematic yaw rate, while no gyro sample comes ...
  double kinematic_rate_fraction = 0.25;  // ... plus this share of it (understeer at the limit)
  double standstill_rate_sigma = 0.001;   // rad/s: a standing car does not turn (the gyro's bias shows)
  // The GNSS receiver's velocity over ground measures the sideslip the wheels cannot: a sliding car.
  bool gnss_velocity = true;
  double gnss_velocity_sigma = 0.1;     // m/s per axis
  double gnss_velocity_lever_x = 0.72;  // m ahead of the reference point: where the velocity is given (the virtual
                                        // car's unit reports its centre of gravity)
  double gnss_velocity_gate = 100.0;    // NIS (2 dof) beyond which a velocity is not taken (a broken one)
};
const ConfigSection<EkfConfig>& ekf_section();

struct ComplementaryConfig {
  double position_time_constant_s = 3.0;         // crossover: GNSS below 1/τ, dead reckoning above
  double heading_time_constant_s = 4.0;          // heading pulled to the GNSS course
  double course_baseline_m = 8.0;                // GNSS track length of one course measurement
  double bias_time_constant_s = 15.0;            // integral of the heading correction into the gyro bias
  double standstill_bias_time_constant_s = 2.0;  // gyro bias low-passed at standstill
  double scale_baseline_m = 40.0;                // travel of one speed-scale measurement
  double scale_time_constant_s = 10.0;           // low-pass of the speed scale
  double drift_fraction = 0.01;                  // σ of dead reckoning per metre travelled
};
const ConfigSection<ComplementaryConfig>& complementary_section();

struct FusionConfig {
  FusionCommonConfig common;
  GnssGateConfig gnss;
  EkfConfig ekf;
  ComplementaryConfig complementary;
};
void describe_fusion_config(ConfigSchema& schema);
FusionConfig read_fusion_config(const Config& cfg);

}  // namespace fsd::fusion

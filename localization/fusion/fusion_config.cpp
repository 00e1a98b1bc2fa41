#include "localization/fusion/fusion_config.hpp"

namespace fsd::fusion {

const ConfigSection<FusionCommonConfig>& fusion_common_section() {
  using C = FusionCommonConfig;
  static const auto s =
      ConfigSection<C>("localization.fusion")
          .string("filter", &C::filter, {"ekf", "complementary"},
                  "Fusion filter: ekf (position, yaw, velocity, yaw rate, gyro bias, speed scale) or complementary "
                  "(the paper's: dead reckoning high-passed, GNSS low-passed).")
          .number("heading_baseline_m", &C::heading_baseline_m, 2.0, 100.0, "m",
                  "GNSS track length that fixes the initial heading once the car moves.")
          .number("moving_speed", &C::moving_speed, 0.1, 10.0, "m/s", "Above this speed the car moves.")
          .number("standstill_speed", &C::standstill_speed, 0.0, 1.0, "m/s",
                  "Below this speed the car stands and the gyro reads its bias.")
          .number("initial_heading_sigma", &C::initial_heading_sigma, 0.001, 1.0, "rad",
                  "Standard deviation of the heading taken from the GNSS track.")
          .number("good_gnss_timeout_s", &C::good_gnss_timeout_s, 0.05, 60.0, "s",
                  "The state is good only with a GNSS fix accepted this recently.")
          .number("good_sigma_m", &C::good_sigma_m, 0.01, 10.0, "m", "The state is good only below this position σ.")
          .number("lost_sigma_m", &C::lost_sigma_m, 0.1, 1000.0, "m", "Beyond this position σ the state is lost.")
          .number("motion_timeout_s", &C::motion_timeout_s, 0.01, 10.0, "s",
                  "No IMU or speed sample for this long: the state is lost.")
          .boolean("lidar_odometry", &C::lidar_odometry,
                   "run.localization_source = fused also takes the LiDAR odometry's increments (the paper's LiDAR "
                   "odometry fused with GNSS-INS); needs the VLP-16.");
  return s;
}

const ConfigSection<GnssGateConfig>& gnss_gate_section() {
  using C = GnssGateConfig;
  static const auto s =
      ConfigSection<C>("localization.fusion.gnss")
          .integer("min_fix_quality", &C::min_fix_quality, 1, 5, "", "GGA fix quality below this is rejected.")
          .number("sigma_single", &C::sigma_single, 0.001, 100.0, "m", "Position σ of a single-point fix (quality 1).")
          .number("sigma_dgps", &C::sigma_dgps, 0.001, 100.0, "m", "Position σ of a DGPS fix (quality 2).")
          .number("sigma_rtk_float", &C::sigma_rtk_float, 0.001, 100.0, "m",
                  "Position σ of an RTK float fix (quality 5).")
          .number("sigma_rtk_fixed", &C::sigma_rtk_fixed, 0.001, 100.0, "m",
                  "Position σ of an RTK fixed fix (quality 4).")
          .number("max_age_s", &C::max_age_s, 0.0, 600.0, "s",
                  "Differential corrections older than this: the fix counts as single-point (down-weighted).")
          .number("max_delay_s", &C::max_delay_s, 0.0, 10.0, "s",
                  "A fix older than the filter's time by more is stale.")
          .number("soft_gate_chi2", &C::soft_gate_chi2, 0.1, 1000.0, "",
                  "Normalised innovation beyond this: the fix's σ is inflated by sqrt(NIS / soft).")
          .number("reject_gate_chi2", &C::reject_gate_chi2, 0.1, 1e6, "",
                  "Normalised innovation beyond this: rejected.")
          .number("jump_min_m", &C::jump_min_m, 0.01, 100.0, "m",
                  "A fix may move this much more than the dead-reckoned motion since the previous fix ...")
          .number("jump_fraction", &C::jump_fraction, 0.0, 10.0, "", "... plus this share of that motion; else a jump.")
          .number("recover_after_s", &C::recover_after_s, 0.1, 600.0, "s",
                  "Fixes rejected by the gate (not jumps) for this long are accepted again.")
          .number("heading_sigma", &C::heading_sigma, 1e-4, 1.0, "rad",
                  "σ of the receiver's dual-antenna heading when it does not state one (HDT; PASHR states it).");
  return s;
}

const ConfigSection<EkfConfig>& ekf_section() {
  using C = EkfConfig;
  static const auto s =
      ConfigSection<C>("localization.fusion.ekf")
          .number("gyro_sigma", &C::gyro_sigma, 1e-5, 1.0, "rad/s", "Gyro noise per sample.")
          .number("optical_sigma", &C::optical_sigma, 1e-4, 10.0, "m/s", "Optical speed noise per axis per sample.")
          .number("wheel_sigma", &C::wheel_sigma, 1e-3, 10.0, "m/s", "Wheel speed noise per sample ...")
          .number("wheel_sigma_fraction", &C::wheel_sigma_fraction, 0.0, 1.0, "",
                  "... plus this share of the speed (slip).")
          .number("wheel_lateral_sigma", &C::wheel_lateral_sigma, 0.01, 10.0, "m/s",
                  "Without optical vy, the lateral speed at the wheels' axle is held to 0 with this σ (sideslip).")
          .number("accel_noise", &C::accel_noise, 0.01, 100.0, "m/s²/√Hz", "Random walk of vx and vy.")
          .number("yaw_accel_noise", &C::yaw_accel_noise, 0.01, 100.0, "rad/s²/√Hz", "Random walk of the yaw rate.")
          .number("bias_walk", &C::bias_walk, 0.0, 0.1, "rad/s/√s", "Random walk of the gyro bias.")
          .number("scale_walk", &C::scale_walk, 0.0, 0.1, "1/√s", "Random walk of the optical speed scale.")
          .number("position_noise", &C::position_noise, 0.0, 10.0, "m/√s", "Position noise the kinematic model misses.")
          .number("initial_bias_sigma", &C::initial_bias_sigma, 1e-6, 1.0, "rad/s", "Initial σ of the gyro bias.")
          .number("initial_slip_sigma", &C::initial_slip_sigma, 1e-6, 0.1, "rad/(m/s²)",
                  "Initial σ of the rear axle's slip compliance (its slip angle per lateral acceleration; from 0).")
          .number("slip_walk", &C::slip_walk, 0.0, 0.01, "rad/(m/s²)/√s", "Random walk of the rear slip compliance.")
          .number("kinematic_rate_sigma", &C::kinematic_rate_sigma, 1e-3, 10.0, "rad/s",
                  "While no gyro sample comes: σ of the wheels' kinematic yaw rate (speed and steering) ...")
          .number("kinematic_rate_fraction", &C::kinematic_rate_fraction, 0.0, 1.0, "",
                  "... plus this share of it (the tyres' slip makes the car turn less than its steering says).")
          .number("initial_scale_sigma", &C::initial_scale_sigma, 1e-6, 1.0, "",
                  "Initial σ of the optical speed scale.")
          .number("standstill_rate_sigma", &C::standstill_rate_sigma, 1e-6, 1.0, "rad/s",
                  "σ of the zero yaw rate a standing car is held to.")
          .boolean("gnss_velocity", &C::gnss_velocity,
                   "Take the GNSS receiver's velocity over ground (speed and course): it measures the sideslip.")
          .number("gnss_velocity_sigma", &C::gnss_velocity_sigma, 1e-3, 10.0, "m/s", "GNSS velocity noise per axis.")
          .number("gnss_velocity_lever_x", &C::gnss_velocity_lever_x, -5.0, 5.0, "m",
                  "Where the receiver gives its velocity: this far ahead of the reference point (rear axle).")
          .number("gnss_velocity_gate", &C::gnss_velocity_gate, 1.0, 1e6, "",
                  "Normalised innovation squared beyond which a GNSS velocity is not taken.");
  return s;
}

const ConfigSection<ComplementaryConfig>& complementary_section() {
  using C = ComplementaryConfig;
  static const auto s =
      ConfigSection<C>("localization.fusion.complementary")
          .number("position_time_constant_s", &C::position_time_constant_s, 0.05, 600.0, "s",
                  "Crossover: GNSS position below 1/τ, dead reckoning above.")
          .number("heading_time_constant_s", &C::heading_time_constant_s, 0.05, 600.0, "s",
                  "Time constant of the heading's pull to the GNSS course.")
          .number("course_baseline_m", &C::course_baseline_m, 1.0, 100.0, "m",
                  "GNSS track length of one course measurement.")
          .number("bias_time_constant_s", &C::bias_time_constant_s, 1.0, 1e4, "s",
                  "Integral of the heading correction into the gyro bias.")
          .number("standstill_bias_time_constant_s", &C::standstill_bias_time_constant_s, 0.01, 600.0, "s",
                  "Gyro bias low-passed at standstill.")
          .number("scale_baseline_m", &C::scale_baseline_m, 1.0, 1000.0, "m", "Travel of one speed-scale measurement.")
          .number("scale_time_constant_s", &C::scale_time_constant_s, 0.1, 1e4, "s",
                  "Time constant of the speed scale's low-pass (one measurement per GNSS fix).")
          .number("drift_fraction", &C::drift_fraction, 0.0, 1.0, "", "σ of dead reckoning per metre travelled.");
  return s;
}

void describe_fusion_config(ConfigSchema& schema) {
  fusion_common_section().describe(schema);
  gnss_gate_section().describe(schema);
  ekf_section().describe(schema);
  complementary_section().describe(schema);
}

FusionConfig read_fusion_config(const Config& cfg) {
  return {fusion_common_section().read(cfg), gnss_gate_section().read(cfg), ekf_section().read(cfg),
          complementary_section().read(cfg)};
}

}  // namespace fsd::fusion

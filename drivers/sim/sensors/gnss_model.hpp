#pragma once
// The virtual car's GNSS-INS: samples the true vehicle state at a fixed rate and sends what a dual-antenna RTK
// GNSS-INS would, as NMEA 0183 bytes: per epoch GGA, RMC, VTG, HDT, PASHR and ROT (in that order, all stamped with
// the epoch's UTC time where the sentence has one). The driver in drivers/gnss parses it back; the geodesy is the
// same code (common/geodesy), so a noise-free model round-trips the truth to well below a millimetre.
//
// Error model (all from one seeded generator, deterministic for a seed):
//   - position: "rtk" white noise σ per horizontal axis (1.5 σ vertical); "single" white noise plus a slowly
//     wandering bias (first-order Gauss-Markov, σ and correlation time), quality 1, no corrections;
//   - multipath: events at a Poisson rate that shift the horizontal position by a fixed distance in a random
//     direction for a while, without the receiver noticing (quality unchanged);
//   - heading, roll/pitch, yaw rate: white noise; speed and course from the true velocity plus white noise per axis;
//   - latency: an epoch's sentences leave the receiver `latency_s` after the epoch, then take their serial time
//     at `baud` (10 bits per byte);
//   - dropouts: each epoch lost with a probability; and one scheduled outage window in which the receiver is
//     silent, reports no fix, or falls back to a single-point solution;
//   - corruption: a sentence with one character altered (the driver sees a checksum mismatch).
// The map frame is the local ENU frame at the configured origin; the antenna sits at the lever arm on the body
// (VehicleTruth::body_pose3, which includes roll and pitch).
#include <cstdint>
#include <deque>
#include <functional>
#include <random>
#include <string>

#include "common/config.hpp"
#include "common/geodesy.hpp"
#include "drivers/sim/sensors/sink.hpp"
#include "drivers/sim/vehicle/vehicle_truth.hpp"

namespace fsd::sim {

struct GnssModelConfig {
  double rate_hz = 50.0;
  // Map origin on the globe: the Hockenheimring paddock (Formula Student Germany).
  double origin_lat_deg = 49.3278;
  double origin_lon_deg = 8.5658;
  double origin_height_m = 150.0;    // above the WGS-84 ellipsoid (≈ 102 m above sea level)
  double geoid_separation_m = 47.6;  // geoid above the ellipsoid there; GGA altitude = height - separation
  double antenna_x = 0.5;            // antenna phase centre in the vehicle frame: car.gnss_antenna + sim.mismatch
  double antenna_y = 0.0;
  double antenna_z = 1.2;

  std::string mode = "rtk";          // rtk | single
  double rtk_sigma_m = 0.02;         // per horizontal axis; vertical 1.5×
  double single_sigma_m = 0.5;       // white part per horizontal axis
  double single_bias_sigma_m = 1.4;  // wandering part per horizontal axis
  double single_bias_tau_s = 30.0;
  int rtk_satellites = 18;
  int single_satellites = 9;
  double rtk_hdop = 0.7;
  double single_hdop = 1.3;
  double correction_interval_s = 1.0;  // RTK corrections arrive this often: differential age saw-tooth

  double heading_sigma_rad = 0.0017;     // ≈ 0.1°
  double attitude_sigma_rad = 0.0009;    // roll and pitch, ≈ 0.05°
  double yaw_rate_sigma_rad_s = 0.0017;  // ≈ 0.1°/s
  double velocity_sigma_m_s = 0.02;      // per horizontal axis

  double latency_s = 0.01;
  int baud = 460800;
  double dropout_probability = 0.0;  // per epoch
  double outage_start_s = -1.0;      // negative: no outage
  double outage_duration_s = 0.0;
  std::string outage_mode = "silent";  // silent | no_fix | single
  double multipath_rate_hz = 0.0;
  double multipath_step_m = 1.5;
  double multipath_duration_s = 3.0;
  double corrupt_probability = 0.0;  // per sentence

  int utc_year = 2024, utc_month = 8, utc_day = 8;
  double utc_start_s = 36000.0;  // UTC seconds of day at simulated time 0
  std::string talker = "GN";
};

const ConfigSection<GnssModelConfig>& gnss_model_section();

struct GnssModelStats {
  std::uint64_t epochs = 0;         // epochs computed
  std::uint64_t silent_epochs = 0;  // dropped or in a silent outage
  std::uint64_t sentences = 0;      // sent (or queued)
  std::uint64_t corrupted = 0;
  std::uint64_t multipath_events = 0;
};

class GnssModel {
 public:
  // Throws std::invalid_argument for values the config bounds cannot catch (unknown mode, impossible date).
  GnssModel(const GnssModelConfig& config, std::uint64_t seed);

  // Computes every epoch up to `t` from the truth at the epoch time and hands the bytes whose delivery time is
  // ≤ t to `sink`, in order, one call per sentence stamped with its delivery time. Later bytes stay queued.
  void advance_to(Stamp t, const std::function<VehicleTruth(Stamp)>& truth_at, const ByteSink& sink);

  // Replaces the configured outage window (the fault schedule opens its windows while the car drives).
  // `mode`: silent | no_fix | single; throws std::invalid_argument otherwise.
  void set_outage(Stamp start, Duration duration, const std::string& mode);

  const LocalEnu& frame() const { return frame_; }
  const GnssModelStats& stats() const { return stats_; }

 private:
  struct Pending {
    Stamp t;
    std::string bytes;
  };
  enum class Fix { Rtk, Single, None };

  void emit_epoch(std::uint64_t k, const VehicleTruth& truth);
  Fix fix_at(Stamp t) const;
  bool silent_at(Stamp t);
  Vec3 position_error(Stamp t, Fix fix);
  void queue(Stamp t_epoch, std::vector<std::string> sentences);

  GnssModelConfig c_;
  LocalEnu frame_;
  Vec3 lever_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
  Vec3 bias_ = Vec3::Zero();       // single-point wander, ENU
  Vec2 multipath_ = Vec2::Zero();  // current multipath offset, ENU
  Stamp multipath_end_ = -1.0;
  std::uint64_t next_epoch_ = 0;
  std::deque<Pending> pending_;  // bounded by latency and the 1 s serial backlog
  Stamp line_free_ = 0.0;        // when the last queued byte has left
  GnssModelStats stats_;
};

}  // namespace fsd::sim

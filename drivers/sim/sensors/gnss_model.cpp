#include "drivers/sim/sensors/gnss_model.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "common/wire/nmea.hpp"

namespace fsd::sim {
namespace {

constexpr double kKnot = 1852.0 / 3600.0;  // m/s
constexpr int kMinuteDecimals = 8;         // 1e-8 arc minutes ≈ 0.02 mm
constexpr double kVerticalFactor = 1.5;    // GNSS height error relative to one horizontal axis
constexpr double kMaxSerialBacklog = 1.0;  // s of unsent output before the receiver drops an epoch

// ENU yaw (counter-clockwise from east) → NMEA degrees clockwise from north in [0, 360).
double north_degrees(double yaw) {
  double d = std::fmod(90.0 - rad2deg(yaw), 360.0);
  if (d < 0.0) d += 360.0;
  return d;
}

std::string two_digits(int v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d", v);
  return buf;
}

using nmea::format_fixed;

}  // namespace

const ConfigSection<GnssModelConfig>& gnss_model_section() {
  using C = GnssModelConfig;
  static const auto s =
      ConfigSection<C>("sim.gnss")
          .number("rate_hz", &C::rate_hz, 1.0, 100.0, "Hz", "Epochs per second of the simulated GNSS-INS.")
          .number("origin_lat_deg", &C::origin_lat_deg, -89.0, 89.0, "deg", "Latitude of the map origin (WGS-84).")
          .number("origin_lon_deg", &C::origin_lon_deg, -180.0, 180.0, "deg", "Longitude of the map origin (WGS-84).")
          .number("origin_height_m", &C::origin_height_m, -1000.0, 10000.0, "m",
                  "Height of the map origin above the WGS-84 ellipsoid.")
          .number("geoid_separation_m", &C::geoid_separation_m, -150.0, 150.0, "m",
                  "Geoid above the ellipsoid at the track: GGA altitude = ellipsoidal height - separation.")
          .string("mode", &C::mode, {"rtk", "single"}, "Solution: rtk (GGA quality 4) or single point (quality 1).")
          .number("rtk_sigma_m", &C::rtk_sigma_m, 0.0, 1.0, "m",
                  "RTK position noise per horizontal axis (1.5x vertical).")
          .number("single_sigma_m", &C::single_sigma_m, 0.0, 20.0, "m",
                  "Single-point white position noise per horizontal axis.")
          .number("single_bias_sigma_m", &C::single_bias_sigma_m, 0.0, 20.0, "m",
                  "Single-point wandering bias per horizontal axis (first-order Gauss-Markov).")
          .number("single_bias_tau_s", &C::single_bias_tau_s, 1.0, 3600.0, "s", "Correlation time of that bias.")
          .integer("rtk_satellites", &C::rtk_satellites, 0, 99, "", "Satellites in use reported in RTK mode.")
          .integer("single_satellites", &C::single_satellites, 0, 99, "", "Satellites in use reported in single mode.")
          .number("rtk_hdop", &C::rtk_hdop, 0.1, 99.0, "", "HDOP reported in RTK mode.")
          .number("single_hdop", &C::single_hdop, 0.1, 99.0, "", "HDOP reported in single mode.")
          .number("correction_interval_s", &C::correction_interval_s, 0.1, 60.0, "s",
                  "Interval of RTK corrections; the differential age grows over it and restarts.")
          .number("heading_sigma_rad", &C::heading_sigma_rad, 0.0, 0.5, "rad", "Heading noise (HDT, PASHR).")
          .number("attitude_sigma_rad", &C::attitude_sigma_rad, 0.0, 0.5, "rad", "Roll and pitch noise (PASHR).")
          .number("yaw_rate_sigma_rad_s", &C::yaw_rate_sigma_rad_s, 0.0, 0.5, "rad/s", "Yaw rate noise (ROT).")
          .number("velocity_sigma_m_s", &C::velocity_sigma_m_s, 0.0, 5.0, "m/s",
                  "Velocity noise per horizontal axis (speed and course in RMC, VTG).")
          .number("latency_s", &C::latency_s, 0.0, 0.5, "s", "Delay from an epoch to its first byte on the line.")
          .integer("baud", &C::baud, 4800, 4000000, "bit/s", "Serial rate: each byte takes 10 bits of line time.")
          .number("dropout_probability", &C::dropout_probability, 0.0, 1.0, "", "Probability that an epoch is lost.")
          .number("outage_start_s", &C::outage_start_s, -1.0, 1e6, "s",
                  "Start of a scheduled outage in simulated time; negative: none.")
          .number("outage_duration_s", &C::outage_duration_s, 0.0, 1e6, "s", "Length of the scheduled outage.")
          .string("outage_mode", &C::outage_mode, {"silent", "no_fix", "single"},
                  "During the outage: no output, no fix (quality 0, INS attitude continues), or single point.")
          .number("multipath_rate_hz", &C::multipath_rate_hz, 0.0, 10.0, "1/s",
                  "Rate of multipath events that shift the position unnoticed.")
          .number("multipath_step_m", &C::multipath_step_m, 0.0, 50.0, "m", "Horizontal shift of a multipath event.")
          .number("multipath_duration_s", &C::multipath_duration_s, 0.0, 600.0, "s", "Length of a multipath event.")
          .number("corrupt_probability", &C::corrupt_probability, 0.0, 1.0, "",
                  "Probability that a sentence has one character altered on the line.")
          .integer("utc_year", &C::utc_year, 1980, 2100, "", "UTC date at simulated time 0: year.")
          .integer("utc_month", &C::utc_month, 1, 12, "", "UTC date at simulated time 0: month.")
          .integer("utc_day", &C::utc_day, 1, 31, "", "UTC date at simulated time 0: day.")
          .number("utc_start_s", &C::utc_start_s, 0.0, 86399.0, "s", "UTC time of day at simulated time 0.")
          .string("talker", &C::talker, {"GP", "GN", "GL", "GA", "IN"}, "NMEA talker id of the standard sentences.");
  return s;
}

GnssModel::GnssModel(const GnssModelConfig& config, std::uint64_t seed)
    : c_(config),
      frame_(Geodetic::from_degrees(config.origin_lat_deg, config.origin_lon_deg, config.origin_height_m)),
      lever_(config.antenna_x, config.antenna_y, config.antenna_z),
      rng_(seed) {
  if (c_.mode != "rtk" && c_.mode != "single") throw std::invalid_argument("sim.gnss.mode: '" + c_.mode + "'");
  if (c_.outage_mode != "silent" && c_.outage_mode != "no_fix" && c_.outage_mode != "single")
    throw std::invalid_argument("sim.gnss.outage_mode: '" + c_.outage_mode + "'");
  if (!(c_.rate_hz > 0.0) || c_.baud <= 0) throw std::invalid_argument("sim.gnss: rate_hz and baud must be > 0");
  if (c_.talker.size() != 2) throw std::invalid_argument("sim.gnss.talker: two letters");
  const std::chrono::year_month_day d{std::chrono::year{c_.utc_year}, std::chrono::month{unsigned(c_.utc_month)},
                                      std::chrono::day{unsigned(c_.utc_day)}};
  if (!d.ok())
    throw std::invalid_argument("sim.gnss: no such date " + std::to_string(c_.utc_year) + "-" +
                                std::to_string(c_.utc_month) + "-" + std::to_string(c_.utc_day));
  // Start the wander in its stationary distribution.
  for (int i = 0; i < 3; ++i) bias_[i] = c_.single_bias_sigma_m * (i == 2 ? kVerticalFactor : 1.0) * normal_(rng_);
}

void GnssModel::advance_to(Stamp t, const std::function<VehicleTruth(Stamp)>& truth_at, const ByteSink& sink) {
  for (;;) {
    const Stamp te = static_cast<double>(next_epoch_) / c_.rate_hz;
    if (te > t) break;
    emit_epoch(next_epoch_, truth_at(te));
    ++next_epoch_;
  }
  while (!pending_.empty() && pending_.front().t <= t) {
    const Pending& p = pending_.front();
    sink(p.t, {reinterpret_cast<const std::uint8_t*>(p.bytes.data()), p.bytes.size()});
    pending_.pop_front();
  }
}

void GnssModel::set_outage(Stamp start, Duration duration, const std::string& mode) {
  if (mode != "silent" && mode != "no_fix" && mode != "single")
    throw std::invalid_argument("GNSS outage mode: '" + mode + "'");
  c_.outage_start_s = start;
  c_.outage_duration_s = duration;
  c_.outage_mode = mode;
}

GnssModel::Fix GnssModel::fix_at(Stamp t) const {
  const bool outage =
      c_.outage_start_s >= 0.0 && t >= c_.outage_start_s && t < c_.outage_start_s + c_.outage_duration_s;
  if (outage && c_.outage_mode == "no_fix") return Fix::None;
  if (outage && c_.outage_mode == "single") return Fix::Single;
  return c_.mode == "rtk" ? Fix::Rtk : Fix::Single;
}

Vec3 GnssModel::position_error(Stamp t, Fix fix) {
  // Every process draws its numbers each epoch, whatever the fix, so that one setting does not reshuffle the rest.
  const double dt = 1.0 / c_.rate_hz;
  const double phi = std::exp(-dt / c_.single_bias_tau_s);
  const double q = std::sqrt(1.0 - phi * phi);
  for (int i = 0; i < 3; ++i)
    bias_[i] = phi * bias_[i] + q * c_.single_bias_sigma_m * (i == 2 ? kVerticalFactor : 1.0) * normal_(rng_);
  const Vec3 white(normal_(rng_), normal_(rng_), kVerticalFactor * normal_(rng_));
  const bool start = uniform_(rng_) < c_.multipath_rate_hz * dt;
  const double direction = 2.0 * std::numbers::pi * uniform_(rng_);
  if (t >= multipath_end_) {
    multipath_.setZero();
    if (start) {
      multipath_ = c_.multipath_step_m * Vec2(std::cos(direction), std::sin(direction));
      multipath_end_ = t + c_.multipath_duration_s;
      ++stats_.multipath_events;
    }
  }
  Vec3 e = Vec3::Zero();
  if (fix == Fix::Rtk) e = c_.rtk_sigma_m * white;
  if (fix == Fix::Single) e = c_.single_sigma_m * white + bias_;
  if (fix != Fix::None) e.head<2>() += multipath_;
  return e;
}

void GnssModel::emit_epoch(std::uint64_t k, const VehicleTruth& truth) {
  const Stamp te = static_cast<double>(k) / c_.rate_hz;
  ++stats_.epochs;
  const bool dropped = uniform_(rng_) < c_.dropout_probability;
  const bool outage =
      c_.outage_start_s >= 0.0 && te >= c_.outage_start_s && te < c_.outage_start_s + c_.outage_duration_s;
  const Fix fix = fix_at(te);
  const Vec3 err = position_error(te, fix);
  const double n_heading = c_.heading_sigma_rad * normal_(rng_);
  const double n_roll = c_.attitude_sigma_rad * normal_(rng_);
  const double n_pitch = c_.attitude_sigma_rad * normal_(rng_);
  const double n_rate = c_.yaw_rate_sigma_rad_s * normal_(rng_);
  const Vec2 n_vel = c_.velocity_sigma_m_s * Vec2(normal_(rng_), normal_(rng_));
  if (dropped || (outage && c_.outage_mode == "silent")) {
    ++stats_.silent_epochs;
    return;
  }

  // Time and date of the epoch.
  const double utc = c_.utc_start_s + te;
  const double day = std::floor(utc / 86400.0);
  const std::chrono::year_month_day date{std::chrono::sys_days{std::chrono::year_month_day{
                                             std::chrono::year{c_.utc_year}, std::chrono::month{unsigned(c_.utc_month)},
                                             std::chrono::day{unsigned(c_.utc_day)}}} +
                                         std::chrono::days{static_cast<int>(day)}};
  const std::string hhmmss = nmea::format_time_of_day(utc, 2);
  const std::string ddmmyy =
      nmea::format_date({int(date.year()), int(unsigned(date.month())), int(unsigned(date.day()))});

  // Antenna position on the globe.
  const Vec3 antenna = truth.body_pose3() * lever_ + err;
  const Geodetic g = frame_.to_geodetic(antenna);
  const auto lat = nmea::format_latitude(rad2deg(g.lat), kMinuteDecimals);
  const auto lon = nmea::format_longitude(rad2deg(g.lon), kMinuteDecimals);

  // Velocity over ground of the centre of gravity, course and heading.
  const double course_true = truth.pose.yaw + truth.sideslip();
  const Vec2 v = truth.speed() * Vec2(std::cos(course_true), std::sin(course_true)) + n_vel;
  const double speed = v.norm();
  const std::string course = speed >= 0.1 ? format_fixed(north_degrees(std::atan2(v.y(), v.x())), 2) : "";
  const std::string heading = format_fixed(north_degrees(truth.pose.yaw + n_heading), 3);

  const bool has_fix = fix != Fix::None;
  const int quality = fix == Fix::Rtk ? 4 : fix == Fix::Single ? 1 : 0;
  const std::string mode = fix == Fix::Rtk ? "R" : fix == Fix::Single ? "A" : "N";
  const std::string t = c_.talker;
  std::vector<std::string> out;
  if (has_fix) {
    const bool rtk = fix == Fix::Rtk;
    const double age = 0.2 + std::fmod(te, c_.correction_interval_s);
    out.push_back(nmea::build(
        t + "GGA",
        std::vector<std::string>{
            hhmmss, lat.value, lat.hemisphere, lon.value, lon.hemisphere, std::to_string(quality),
            two_digits(rtk ? c_.rtk_satellites : c_.single_satellites),
            format_fixed(rtk ? c_.rtk_hdop : c_.single_hdop, 2), format_fixed(g.h - c_.geoid_separation_m, 3), "M",
            format_fixed(c_.geoid_separation_m, 3), "M", rtk ? format_fixed(age, 1) : "", rtk ? "0000" : ""}));
    out.push_back(nmea::build(
        t + "RMC", std::vector<std::string>{hhmmss, "A", lat.value, lat.hemisphere, lon.value, lon.hemisphere,
                                            format_fixed(speed / kKnot, 3), course, ddmmyy, "", "", mode}));
    out.push_back(nmea::build(t + "VTG", std::vector<std::string>{course, "T", "", "M", format_fixed(speed / kKnot, 3),
                                                                  "N", format_fixed(speed * 3.6, 3), "K", mode}));
  } else {
    out.push_back(nmea::build(
        t + "GGA", std::vector<std::string>{hhmmss, "", "", "", "", "0", "00", "", "", "M", "", "M", "", ""}));
    out.push_back(
        nmea::build(t + "RMC", std::vector<std::string>{hhmmss, "V", "", "", "", "", "", "", ddmmyy, "", "", "N"}));
    out.push_back(nmea::build(t + "VTG", std::vector<std::string>{"", "T", "", "M", "", "N", "", "K", "N"}));
  }
  // The inertial part keeps heading, attitude and rate through a GNSS outage.
  out.push_back(nmea::build(t + "HDT", std::vector<std::string>{heading, "T"}));
  out.push_back(nmea::build(
      "PASHR", std::vector<std::string>{
                   nmea::format_time_of_day(utc, 3), heading, "T", format_fixed(rad2deg(truth.roll + n_roll), 3, true),
                   format_fixed(-rad2deg(truth.pitch + n_pitch), 3, true), "+0.000",
                   format_fixed(rad2deg(c_.attitude_sigma_rad), 3), format_fixed(rad2deg(c_.attitude_sigma_rad), 3),
                   format_fixed(rad2deg(c_.heading_sigma_rad), 3), std::to_string(quality), "1"}));
  out.push_back(
      nmea::build(t + "ROT", std::vector<std::string>{format_fixed(-rad2deg(truth.yaw_rate + n_rate) * 60.0, 3), "A"}));
  queue(te, std::move(out));
}

void GnssModel::queue(Stamp t_epoch, std::vector<std::string> sentences) {
  const double byte_time = 10.0 / c_.baud;
  Stamp t = std::max(t_epoch + c_.latency_s, line_free_);  // the line may still be busy with earlier output
  if (t - (t_epoch + c_.latency_s) > kMaxSerialBacklog) {  // output buffer full: the receiver drops the epoch
    ++stats_.silent_epochs;
    return;
  }
  for (auto& s : sentences) {
    const bool corrupt = uniform_(rng_) < c_.corrupt_probability;
    const double where = uniform_(rng_);
    if (corrupt && s.size() > 8) {
      // One bit flipped between '$' and '*': printable stays printable and the checksum no longer matches.
      const std::size_t i = 1 + static_cast<std::size_t>(where * static_cast<double>(s.size() - 7));
      s[i] = static_cast<char>(s[i] ^ 0x01);
      ++stats_.corrupted;
    }
    t += static_cast<double>(s.size()) * byte_time;
    pending_.push_back({t, std::move(s)});
    ++stats_.sentences;
  }
  line_free_ = t;
}

}  // namespace fsd::sim

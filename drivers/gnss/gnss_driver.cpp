#include "drivers/gnss/gnss_driver.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "common/rotation.hpp"
#include "common/wire/nmea.hpp"

namespace fsd {
namespace {

constexpr double kKnot = 1852.0 / 3600.0;  // m/s

std::optional<SentenceType> ender_from_config(const std::string& name) {
  if (name == "auto") return std::nullopt;
  for (int i = 0; i < kSentenceTypes; ++i) {
    const auto t = static_cast<SentenceType>(i);
    if (name == to_string(t)) return t;
  }
  throw std::invalid_argument("drivers.gnss.emit_on: unknown sentence '" + name + "'");
}

// NMEA angle (degrees clockwise from true north) → ENU yaw (radians counter-clockwise from east).
double enu_yaw_from_north_deg(double deg) { return wrap_angle(std::numbers::pi / 2 - deg2rad(deg)); }

// Velocity, heading, attitude and yaw rate of an epoch into the sample (no position).
void fill_motion(const Epoch& e, GnssSample& s) {
  if (e.vtg && e.vtg->mode != 'N' && (e.vtg->speed_kmh || e.vtg->speed_knots)) {
    s.speed = e.vtg->speed_kmh ? *e.vtg->speed_kmh / 3.6 : *e.vtg->speed_knots * kKnot;
    s.velocity_valid = true;
    if (e.vtg->course_deg) s.course = enu_yaw_from_north_deg(*e.vtg->course_deg);
  } else if (e.rmc && e.rmc->valid && e.rmc->speed_knots) {
    s.speed = *e.rmc->speed_knots * kKnot;
    s.velocity_valid = true;
    if (e.rmc->course_deg) s.course = enu_yaw_from_north_deg(*e.rmc->course_deg);
  }
  std::optional<double> heading;
  if (e.hdt && e.hdt->heading_deg)
    heading = e.hdt->heading_deg;
  else if (e.pashr && e.pashr->heading_deg)
    heading = e.pashr->heading_deg;
  if (heading) {
    s.heading = enu_yaw_from_north_deg(*heading);
    s.heading_valid = true;
    if (e.pashr && e.pashr->heading_sigma_deg && *e.pashr->heading_sigma_deg > 0)
      s.heading_sigma = deg2rad(*e.pashr->heading_sigma_deg);
  }
  if (e.pashr && e.pashr->roll_deg && e.pashr->pitch_deg) {
    s.roll = deg2rad(*e.pashr->roll_deg);     // both conventions: right side down positive
    s.pitch = -deg2rad(*e.pashr->pitch_deg);  // PASHR bow up positive, ISO 8855 nose down positive
    s.attitude_valid = true;
  }
  if (e.rot && e.rot->valid && e.rot->rate_deg_per_min) {
    s.yaw_rate = -deg2rad(*e.rot->rate_deg_per_min) / 60.0;
    s.yaw_rate_valid = true;
  }
}

}  // namespace

GnssDriver::GnssDriver(const GnssConfig& config, SampleCallback on_sample)
    : config_(config),
      min_fix_rank_(fix_rank(config.min_fix)),
      lever_(config.antenna_x, config.antenna_y, config.antenna_z),
      on_sample_(std::move(on_sample)),
      splitter_(static_cast<std::size_t>(std::clamp(config.max_line_length, 16, 65536))),
      assembler_(ender_from_config(config.emit_on), [this](const Epoch& e) { on_epoch(e); }) {
  if (config_.max_line_length < 16 || config_.max_line_length > 65536)
    throw std::invalid_argument("drivers.gnss.max_line_length: " + std::to_string(config_.max_line_length));
  if (!config_.use_first_fix)
    origin_.emplace(Geodetic::from_degrees(config_.origin_lat_deg, config_.origin_lon_deg, config_.origin_height_m));
}

void GnssDriver::feed(std::span<const std::uint8_t> bytes, Stamp receive_time) {
  splitter_.feed(bytes, receive_time, [this](std::string_view line, Stamp t) { on_line(line, t); });
}

GnssCounters GnssDriver::counters() const {
  GnssCounters c = counters_;
  c.framing = splitter_.counters();
  c.late_sentences = assembler_.late_sentences();
  return c;
}

void GnssDriver::on_line(std::string_view line, Stamp t) {
  ++counters_.lines;
  const nmea::Unframed u = nmea::unframe(line, config_.require_checksum);
  switch (u.error) {
    case nmea::FrameError::None:
      break;
    case nmea::FrameError::MissingChecksum:
      ++counters_.missing_checksum;
      return;
    default:
      ++counters_.bad_checksum;
      return;
  }
  const ParsedSentence p = parse_sentence(u.payload);
  switch (p.error) {
    case SentenceError::None:
      break;
    case SentenceError::Unsupported:
      ++counters_.unsupported;
      return;
    case SentenceError::BadAddress:
      ++counters_.bad_address;
      return;
    case SentenceError::Malformed:
      ++counters_.malformed;
      return;
  }
  ++counters_.sentences;
  assembler_.add(p.sentence, t);
}

void GnssDriver::on_epoch(const Epoch& e) {
  if (!e.gga) {
    ++counters_.epochs_without_gga;
    return;
  }
  const GgaSentence& gga = *e.gga;
  GnssSample s;
  s.stamp = e.receive_time - config_.latency_s;
  s.fix_quality = gga.quality;
  s.satellites = gga.satellites.value_or(0);
  s.hdop = gga.hdop.value_or(99.0);
  s.age_s = gga.diff_age_s.value_or(0.0);
  fill_motion(e, s);

  const bool has_fix = gga.quality != 0 && gga.lat_deg && gga.lon_deg;
  const int rank = fix_rank(gga.quality);
  const bool dead_reckoning = gga.quality == 6 && config_.dead_reckoning_good;
  const bool quality_ok =
      has_fix && (dead_reckoning ||
                  (rank >= min_fix_rank_ && s.satellites >= config_.min_satellites && s.hdop <= config_.max_hdop &&
                   !(min_fix_rank_ >= 2 && gga.diff_age_s && *gga.diff_age_s > config_.max_diff_age_s)));
  const bool heading_ok = s.heading_valid || !config_.require_heading;
  const bool rmc_ok = !e.rmc || e.rmc->valid;

  if (has_fix) {
    s.lat_deg = *gga.lat_deg;
    s.lon_deg = *gga.lon_deg;
    // A 2D fix has no altitude: put it on the origin's height rather than on the ellipsoid.
    s.alt_m = gga.altitude_msl_m ? *gga.altitude_msl_m + gga.geoid_separation_m.value_or(0.0)
                                 : (origin_ ? origin_->origin().h : 0.0);
    const Geodetic antenna = Geodetic::from_degrees(s.lat_deg, s.lon_deg, s.alt_m);
    // Antenna → rear axle in ENU; without a heading only the height of the lever arm is known.
    const Vec3 lever_enu =
        s.heading_valid ? Vec3(rotation_zyx(s.heading, s.pitch, s.roll) * lever_) : Vec3(0.0, 0.0, lever_.z());
    if (!origin_ && config_.use_first_fix && quality_ok && heading_ok && rmc_ok)
      origin_.emplace(LocalEnu(antenna).to_geodetic(-lever_enu));
    if (origin_) s.enu = origin_->to_enu(antenna) - lever_enu;
  }
  s.good = quality_ok && heading_ok && rmc_ok && origin_.has_value();
  ++counters_.samples;
  if (s.good) ++counters_.good_samples;
  on_sample_(s);
}

}  // namespace fsd

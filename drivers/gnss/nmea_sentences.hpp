#pragma once
// The NMEA 0183 sentences a GNSS-INS sends, parsed field by field into plain structs (degrees and knots as on
// the wire; the driver converts to SI and ENU). An empty field is "no data" (std::nullopt); a field with
// characters that do not belong there makes the whole sentence malformed.
//
// Attitude and rate come from two real-world sentences:
//   $PASHR,hhmmss.sss,HHH.HH,T,±RR.RR,±PP.PP,±hh.hh,r.rrr,p.ppp,h.hhh,Q,I*CS  (Applanix/Trimble/OxTS "PASHR")
//     true heading; roll positive right (starboard) side down; pitch positive bow up; heave m; 1σ accuracies
//     in degrees; GNSS quality / aiding flag; IMU status.
//   $--ROT,±x.x,A*CS   (standard NMEA rate of turn)
//     degrees per minute, negative = bow turns to port (left); A = valid, V = invalid.
// Ashtech's other $PASHR,<word>,... sentences share the address; they are recognised and reported unsupported.
#include <cstdint>
#include <optional>
#include <string_view>
#include <variant>

#include "common/wire/nmea.hpp"

namespace fsd {

enum class SentenceType : std::uint8_t { GGA = 0, RMC, VTG, HDT, PASHR, ROT };
inline constexpr int kSentenceTypes = 6;
const char* to_string(SentenceType t);

struct GgaSentence {
  std::optional<double> utc_s;             // seconds since UTC midnight
  std::optional<double> lat_deg, lon_deg;  // empty without a fix
  int quality = 0;                         // 0 invalid, 1 single, 2 DGPS, 3 PPS, 4 RTK fixed, 5 RTK float,
                                           // 6 dead reckoning, 7 manual, 8 simulator
  std::optional<int> satellites;
  std::optional<double> hdop;
  std::optional<double> altitude_msl_m;      // antenna height above mean sea level (geoid)
  std::optional<double> geoid_separation_m;  // geoid above the ellipsoid
  std::optional<double> diff_age_s;          // age of differential corrections
  std::optional<int> station_id;
};

struct RmcSentence {
  std::optional<double> utc_s;
  bool valid = false;  // status A (valid) / V (void)
  std::optional<double> lat_deg, lon_deg;
  std::optional<double> speed_knots;
  std::optional<double> course_deg;  // true course over ground, clockwise from north
  std::optional<nmea::Date> date;
  char mode = 0;  // NMEA 2.3 mode indicator (A, D, E, F, R, N, ...), 0 if absent
};

struct VtgSentence {
  std::optional<double> course_deg;  // true course over ground
  std::optional<double> speed_knots;
  std::optional<double> speed_kmh;
  char mode = 0;  // N = not valid
};

struct HdtSentence {
  std::optional<double> heading_deg;  // true heading, clockwise from north; empty when unknown
};

struct PashrSentence {
  std::optional<double> utc_s;
  std::optional<double> heading_deg;
  std::optional<double> roll_deg;   // positive right side down
  std::optional<double> pitch_deg;  // positive bow up
  std::optional<double> heave_m;
  std::optional<double> roll_sigma_deg, pitch_sigma_deg, heading_sigma_deg;
  std::optional<int> gnss_quality;
  std::optional<int> imu_status;
};

struct RotSentence {
  std::optional<double> rate_deg_per_min;  // negative = turning left
  bool valid = false;
};

using Sentence = std::variant<GgaSentence, RmcSentence, VtgSentence, HdtSentence, PashrSentence, RotSentence>;

SentenceType type_of(const Sentence& s);
// UTC time of day the sentence carries (GGA, RMC, PASHR), nullopt for the others or an empty field.
std::optional<double> utc_of(const Sentence& s);

enum class SentenceError : std::uint8_t {
  None = 0,
  Unsupported,  // well-formed address of a sentence this driver does not use (GSV, ZDA, $PASHR,ATT, ...)
  BadAddress,   // not a talker id + type or a proprietary 'P' address
  Malformed,    // a field that cannot be what the sentence defines there
};
const char* to_string(SentenceError e);

struct ParsedSentence {
  SentenceError error = SentenceError::None;
  Sentence sentence;
  char talker[3] = {0, 0, 0};  // "GP", "GN", "HE"...; empty for proprietary sentences
};

// `payload` as returned by nmea::unframe (checksum already verified). Any two upper-case letters are accepted as
// a talker id (GP, GN, GL, GA, GB, BD, GQ, HE, HC, IN, TI, ...).
ParsedSentence parse_sentence(std::string_view payload);

}  // namespace fsd

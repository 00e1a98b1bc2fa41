#include "drivers/gnss/nmea_sentences.hpp"

#include <array>

namespace fsd {
namespace {

using nmea::Fields;

// Reads optional fields and remembers whether any of them was malformed.
class FieldReader {
 public:
  explicit FieldReader(const Fields& f) : f_(f) {}

  bool ok() const { return ok_ && !f_.overflow(); }
  bool empty(std::size_t i) const { return f_[i].empty(); }
  std::string_view raw(std::size_t i) const { return f_[i]; }

  std::optional<double> number(std::size_t i, double min, double max) {
    return check(i, nmea::parse_decimal(f_[i]), min, max);
  }
  std::optional<int> integer(std::size_t i, int max) {
    const auto v = nmea::parse_integer(f_[i]);
    if (v && *v > max) return fail<int>();
    return v || empty(i) ? v : fail<int>();
  }
  std::optional<double> time(std::size_t i) { return check(i, nmea::parse_time_of_day(f_[i]), 0.0, 86401.0); }
  // A value and its hemisphere letter are both present or both empty.
  std::optional<double> latitude(std::size_t v, std::size_t h) {
    return coordinate(v, h, nmea::parse_latitude(f_[v], f_[h]));
  }
  std::optional<double> longitude(std::size_t v, std::size_t h) {
    return coordinate(v, h, nmea::parse_longitude(f_[v], f_[h]));
  }
  std::optional<nmea::Date> date(std::size_t i) {
    const auto d = nmea::parse_date(f_[i]);
    return d || empty(i) ? d : fail<nmea::Date>();
  }
  // One character out of `allowed`, or 0 for an empty field.
  char letter(std::size_t i, std::string_view allowed) {
    const auto s = f_[i];
    if (s.empty()) return 0;
    if (s.size() != 1 || allowed.find(s[0]) == std::string_view::npos) {
      ok_ = false;
      return 0;
    }
    return s[0];
  }

 private:
  template <class T>
  std::optional<T> fail() {
    ok_ = false;
    return std::nullopt;
  }
  std::optional<double> check(std::size_t i, std::optional<double> v, double min, double max) {
    if (empty(i)) return std::nullopt;
    if (!v || *v < min || *v > max) return fail<double>();
    return v;
  }
  std::optional<double> coordinate(std::size_t v, std::size_t h, std::optional<double> value) {
    if (empty(v) && empty(h)) return std::nullopt;
    return value ? value : fail<double>();
  }

  const Fields& f_;
  bool ok_ = true;
};

ParsedSentence malformed() { return {SentenceError::Malformed, {}, {}}; }

ParsedSentence parse_gga(FieldReader& r) {
  GgaSentence s;
  s.utc_s = r.time(1);
  s.lat_deg = r.latitude(2, 3);
  s.lon_deg = r.longitude(4, 5);
  const auto q = r.integer(6, 9);
  if (!q) return malformed();  // the fix quality is mandatory
  s.quality = *q;
  s.satellites = r.integer(7, 99);
  s.hdop = r.number(8, 0.0, 100.0);
  s.altitude_msl_m = r.number(9, -1e4, 1e6);
  s.geoid_separation_m = r.number(11, -1000.0, 1000.0);
  s.diff_age_s = r.number(13, 0.0, 1e6);
  s.station_id = nmea::parse_integer(r.raw(14));  // informational only; some receivers send letters here
  if (!r.ok()) return malformed();
  return {SentenceError::None, s, {}};
}

ParsedSentence parse_rmc(FieldReader& r) {
  RmcSentence s;
  s.utc_s = r.time(1);
  const char status = r.letter(2, "AV");
  if (status == 0) return malformed();
  s.valid = status == 'A';
  s.lat_deg = r.latitude(3, 4);
  s.lon_deg = r.longitude(5, 6);
  s.speed_knots = r.number(7, 0.0, 1e5);
  s.course_deg = r.number(8, 0.0, 360.0);
  s.date = r.date(9);
  s.mode = r.letter(12, "ADEFMNPRS");
  if (!r.ok()) return malformed();
  return {SentenceError::None, s, {}};
}

ParsedSentence parse_vtg(FieldReader& r) {
  VtgSentence s;
  // NMEA 2.3+ layout with unit letters; the pre-2.0 layout without them is not supported.
  r.letter(2, "T");
  s.course_deg = r.number(1, 0.0, 360.0);
  s.speed_knots = r.number(5, 0.0, 1e5);
  s.speed_kmh = r.number(7, 0.0, 2e5);
  s.mode = r.letter(9, "ADEFMNPRS");
  if (!r.ok()) return malformed();
  return {SentenceError::None, s, {}};
}

ParsedSentence parse_hdt(FieldReader& r) {
  HdtSentence s;
  s.heading_deg = r.number(1, 0.0, 360.0);
  r.letter(2, "T");
  if (!r.ok()) return malformed();
  return {SentenceError::None, s, {}};
}

ParsedSentence parse_rot(FieldReader& r) {
  RotSentence s;
  s.rate_deg_per_min = r.number(1, -1e5, 1e5);
  s.valid = r.letter(2, "AV") == 'A';
  if (!r.ok()) return malformed();
  return {SentenceError::None, s, {}};
}

ParsedSentence parse_pashr(FieldReader& r) {
  const auto first = r.raw(1);
  if (!first.empty() && !(first[0] >= '0' && first[0] <= '9'))
    return {SentenceError::Unsupported, {}, {}};  // Ashtech $PASHR,<word>,... family
  PashrSentence s;
  s.utc_s = r.time(1);
  s.heading_deg = r.number(2, 0.0, 360.0);
  r.letter(3, "T");
  s.roll_deg = r.number(4, -180.0, 180.0);
  s.pitch_deg = r.number(5, -90.0, 90.0);
  s.heave_m = r.number(6, -1e3, 1e3);
  s.roll_sigma_deg = r.number(7, 0.0, 360.0);
  s.pitch_sigma_deg = r.number(8, 0.0, 360.0);
  s.heading_sigma_deg = r.number(9, 0.0, 360.0);
  s.gnss_quality = r.integer(10, 9);
  s.imu_status = r.integer(11, 9);
  if (!r.ok()) return malformed();
  return {SentenceError::None, s, {}};
}

bool upper(char c) { return c >= 'A' && c <= 'Z'; }

}  // namespace

const char* to_string(SentenceType t) {
  static constexpr std::array<const char*, kSentenceTypes> kNames = {"GGA", "RMC", "VTG", "HDT", "PASHR", "ROT"};
  return kNames[static_cast<std::size_t>(t)];
}

const char* to_string(SentenceError e) {
  switch (e) {
    case SentenceError::None:
      return "ok";
    case SentenceError::Unsupported:
      return "unsupported sentence";
    case SentenceError::BadAddress:
      return "bad address";
    case SentenceError::Malformed:
      return "malformed field";
  }
  return "?";
}

SentenceType type_of(const Sentence& s) { return static_cast<SentenceType>(s.index()); }

std::optional<double> utc_of(const Sentence& s) {
  if (const auto* g = std::get_if<GgaSentence>(&s)) return g->utc_s;
  if (const auto* r = std::get_if<RmcSentence>(&s)) return r->utc_s;
  if (const auto* p = std::get_if<PashrSentence>(&s)) return p->utc_s;
  return std::nullopt;
}

ParsedSentence parse_sentence(std::string_view payload) {
  const Fields f(payload);
  FieldReader r(f);
  const std::string_view address = f[0];
  if (address.size() >= 2 && address[0] == 'P') {
    for (char c : address)
      if (!upper(c)) return {SentenceError::BadAddress, {}, {}};
    if (address == "PASHR") return parse_pashr(r);
    return {SentenceError::Unsupported, {}, {}};
  }
  if (address.size() != 5) return {SentenceError::BadAddress, {}, {}};
  for (char c : address)
    if (!upper(c)) return {SentenceError::BadAddress, {}, {}};
  const std::string_view type = address.substr(2);
  ParsedSentence p;
  if (type == "GGA")
    p = parse_gga(r);
  else if (type == "RMC")
    p = parse_rmc(r);
  else if (type == "VTG")
    p = parse_vtg(r);
  else if (type == "HDT")
    p = parse_hdt(r);
  else if (type == "ROT")
    p = parse_rot(r);
  else
    return {SentenceError::Unsupported, {}, {}};
  p.talker[0] = address[0];
  p.talker[1] = address[1];
  return p;
}

}  // namespace fsd

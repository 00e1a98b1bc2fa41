#include "common/wire/nmea.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace fsd::nmea {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

bool all_digits(std::string_view s) {
  for (char c : s)
    if (!is_digit(c)) return false;
  return true;
}

// Degrees and minutes: the two digits before the decimal point and what follows are minutes, the digits before
// them are degrees (ddmm.mmmm, dddmm.mmmm).
std::optional<double> parse_degrees_minutes(std::string_view v, double max_deg) {
  const std::size_t dot = v.find('.');
  const std::string_view whole = v.substr(0, dot);
  if (whole.size() < 3 || whole.size() > 5 || !all_digits(whole)) return std::nullopt;
  const auto deg = parse_integer(whole.substr(0, whole.size() - 2));
  const auto min = parse_decimal(v.substr(whole.size() - 2));
  if (!deg || !min || *min >= 60.0) return std::nullopt;
  const double d = *deg + *min / 60.0;
  if (d > max_deg) return std::nullopt;
  return d;
}

std::optional<double> signed_coordinate(std::optional<double> d, std::string_view hemi, char pos, char neg) {
  if (!d || hemi.size() != 1) return std::nullopt;
  if (hemi[0] == pos) return *d;
  if (hemi[0] == neg) return -*d;
  return std::nullopt;
}

Coordinate format_degrees_minutes(double deg, int decimals, int deg_digits, char pos, char neg) {
  const double a = std::abs(deg);
  double d = std::floor(a);
  const double scale = std::pow(10.0, decimals);
  double m = std::round((a - d) * 60.0 * scale) / scale;
  if (m >= 60.0) {  // 59.99999999 rounded up
    d += 1.0;
    m -= 60.0;
  }
  char buf[48];
  const int width = decimals > 0 ? 3 + decimals : 2;
  std::snprintf(buf, sizeof buf, "%0*d%0*.*f", deg_digits, static_cast<int>(d), width, decimals, m);
  return {buf, std::string(1, deg < 0 ? neg : pos)};
}

}  // namespace

std::uint8_t checksum(std::string_view payload) {
  std::uint8_t x = 0;
  for (char c : payload) x ^= static_cast<std::uint8_t>(c);
  return x;
}

const char* to_string(FrameError e) {
  switch (e) {
    case FrameError::None:
      return "ok";
    case FrameError::NoStart:
      return "no '$' at start";
    case FrameError::MissingChecksum:
      return "missing checksum";
    case FrameError::MalformedChecksum:
      return "malformed checksum";
    case FrameError::ChecksumMismatch:
      return "checksum mismatch";
  }
  return "?";
}

Unframed unframe(std::string_view line, bool require_checksum) {
  if (line.empty() || line.front() != '$') return {FrameError::NoStart, {}};
  const std::string_view body = line.substr(1);
  const std::size_t star = body.find('*');
  if (star == std::string_view::npos) {
    if (require_checksum) return {FrameError::MissingChecksum, {}};
    return {FrameError::None, body};
  }
  const std::string_view hex = body.substr(star + 1);
  const int hi = hex.size() == 2 ? hex_value(hex[0]) : -1;
  const int lo = hex.size() == 2 ? hex_value(hex[1]) : -1;
  if (hi < 0 || lo < 0) return {FrameError::MalformedChecksum, {}};
  const std::string_view payload = body.substr(0, star);
  if (checksum(payload) != hi * 16 + lo) return {FrameError::ChecksumMismatch, {}};
  return {FrameError::None, payload};
}

std::string frame(std::string_view payload) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  const std::uint8_t c = checksum(payload);
  std::string s;
  s.reserve(payload.size() + 6);
  s += '$';
  s += payload;
  s += '*';
  s += kHex[c >> 4];
  s += kHex[c & 0xF];
  s += "\r\n";
  return s;
}

std::string build(std::string_view address, std::span<const std::string> fields) {
  std::string payload(address);
  for (const auto& f : fields) {
    payload += ',';
    payload += f;
  }
  return frame(payload);
}

Fields::Fields(std::string_view payload) {
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = payload.find(',', start);
    if (n_ == kMax) {
      overflow_ = true;
      return;
    }
    f_[n_++] = payload.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    if (comma == std::string_view::npos) return;
    start = comma + 1;
  }
}

std::string_view Fields::operator[](std::size_t i) const { return i < n_ ? f_[i] : std::string_view{}; }

std::optional<double> parse_decimal(std::string_view s) {
  bool negative = false;
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) {
    negative = s[0] == '-';
    s.remove_prefix(1);
  }
  // Validate the shape here so that from_chars sees nothing it would read differently (inf, nan, exponents).
  std::size_t digits = 0, dots = 0;
  for (char c : s) {
    if (is_digit(c))
      ++digits;
    else if (c == '.')
      ++dots;
    else
      return std::nullopt;
  }
  if (digits == 0 || dots > 1 || s.size() > 32) return std::nullopt;
  double v = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, std::chars_format::fixed);
  if (r.ec != std::errc{} || r.ptr != s.data() + s.size()) return std::nullopt;
  return negative ? -v : v;
}

std::optional<int> parse_integer(std::string_view s) {
  if (s.empty() || s.size() > 9 || !all_digits(s)) return std::nullopt;
  int v = 0;
  std::from_chars(s.data(), s.data() + s.size(), v);
  return v;
}

std::optional<double> parse_latitude(std::string_view value, std::string_view hemisphere) {
  return signed_coordinate(parse_degrees_minutes(value, 90.0), hemisphere, 'N', 'S');
}

std::optional<double> parse_longitude(std::string_view value, std::string_view hemisphere) {
  return signed_coordinate(parse_degrees_minutes(value, 180.0), hemisphere, 'E', 'W');
}

std::optional<double> parse_time_of_day(std::string_view s) {
  if (s.size() < 6 || !all_digits(s.substr(0, 6))) return std::nullopt;
  const int hh = (s[0] - '0') * 10 + (s[1] - '0');
  const int mm = (s[2] - '0') * 10 + (s[3] - '0');
  double ss = (s[4] - '0') * 10 + (s[5] - '0');
  if (s.size() > 6) {
    if (s[6] != '.') return std::nullopt;
    if (s.size() > 7) {
      const auto frac = parse_decimal(s.substr(6));
      if (!frac || !all_digits(s.substr(7))) return std::nullopt;
      ss += *frac;
    }
  }
  if (hh > 23 || mm > 59 || ss >= 61.0) return std::nullopt;
  return hh * 3600.0 + mm * 60.0 + ss;
}

std::optional<Date> parse_date(std::string_view s) {
  if (s.size() != 6 || !all_digits(s)) return std::nullopt;
  const int dd = (s[0] - '0') * 10 + (s[1] - '0');
  const int mo = (s[2] - '0') * 10 + (s[3] - '0');
  const int yy = (s[4] - '0') * 10 + (s[5] - '0');
  const Date d{yy >= 80 ? 1900 + yy : 2000 + yy, mo, dd};
  const std::chrono::year_month_day ymd{std::chrono::year{d.year}, std::chrono::month{static_cast<unsigned>(mo)},
                                        std::chrono::day{static_cast<unsigned>(dd)}};
  if (!ymd.ok()) return std::nullopt;
  return d;
}

std::string format_fixed(double v, int decimals, bool plus) {
  char buf[64];
  std::snprintf(buf, sizeof buf, plus ? "%+.*f" : "%.*f", decimals, v);
  return buf;
}

Coordinate format_latitude(double deg, int minute_decimals) {
  return format_degrees_minutes(deg, minute_decimals, 2, 'N', 'S');
}

Coordinate format_longitude(double deg, int minute_decimals) {
  return format_degrees_minutes(deg, minute_decimals, 3, 'E', 'W');
}

std::string format_time_of_day(double s, int decimals) {
  decimals = std::clamp(decimals, 0, 9);
  long long unit = 1;
  for (int i = 0; i < decimals; ++i) unit *= 10;
  const long long day = 86400LL * unit;
  long long u = std::llround(s * static_cast<double>(unit)) % day;
  if (u < 0) u += day;
  const int secs = static_cast<int>(u / unit);
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d%02d%02d", secs / 3600 % 100, secs / 60 % 60, secs % 60);
  std::string out = buf;
  if (decimals > 0) {
    std::string frac = std::to_string(u % unit);
    out += '.';
    out.append(static_cast<std::size_t>(decimals) - frac.size(), '0');
    out += frac;
  }
  return out;
}

std::string format_date(const Date& d) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d%02d%02d", d.day % 100, d.month % 100, d.year % 100);
  return buf;
}

}  // namespace fsd::nmea

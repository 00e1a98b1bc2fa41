#pragma once
// NMEA 0183 sentence framing and field codecs, shared by the GNSS driver (parsing) and the virtual car's GNSS
// model (building). A sentence on the wire is
//     $<address>,<field>,<field>,...*<HH><CR><LF>
// where <address> is a talker id and sentence type ("GNGGA") or a proprietary 'P' address ("PASHR") and HH is
// the XOR of every character between '$' and '*' in two hex digits.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace fsd::nmea {

// Longest sentence the standard allows, '$' to <LF> inclusive. Proprietary sentences often exceed it.
inline constexpr std::size_t kStandardMaxLength = 82;

// XOR of the characters of `payload` (the text between '$' and '*').
std::uint8_t checksum(std::string_view payload);

enum class FrameError : std::uint8_t {
  None = 0,
  NoStart,            // the line does not begin with '$'
  MissingChecksum,    // no '*HH' and the checksum is required
  MalformedChecksum,  // '*' not followed by exactly two hex digits
  ChecksumMismatch,   // the two hex digits differ from the computed checksum
};
const char* to_string(FrameError e);

struct Unframed {
  FrameError error = FrameError::None;
  std::string_view payload;  // between '$' and '*' (or the end); empty on error
};

// `line` is one sentence without its CR/LF.
Unframed unframe(std::string_view line, bool require_checksum = true);

// "$" + payload + "*HH\r\n".
std::string frame(std::string_view payload);
// Joins the address and fields with ',' and frames the result.
std::string build(std::string_view address, std::span<const std::string> fields);

// The comma-separated fields of a payload, split without allocation. Index 0 is the address; reading past the
// end gives an empty field, so optional trailing fields that a receiver leaves out read as empty.
class Fields {
 public:
  static constexpr std::size_t kMax = 40;
  explicit Fields(std::string_view payload);
  std::size_t size() const { return n_; }
  bool overflow() const { return overflow_; }  // more than kMax fields; the rest were dropped
  std::string_view operator[](std::size_t i) const;

 private:
  std::array<std::string_view, kMax> f_{};
  std::size_t n_ = 0;
  bool overflow_ = false;
};

// ---- field codecs; every parser returns nullopt for an empty or malformed field ----

// [+|-]digits[.digits] or [+|-].digits; no exponent, no inf/nan, no spaces.
std::optional<double> parse_decimal(std::string_view s);
// Unsigned decimal integer of at most 9 digits.
std::optional<int> parse_integer(std::string_view s);
// ddmm.mmmm + N/S, dddmm.mmmm + E/W → degrees, south/west negative.
std::optional<double> parse_latitude(std::string_view value, std::string_view hemisphere);
std::optional<double> parse_longitude(std::string_view value, std::string_view hemisphere);
// hhmmss[.s...] → seconds since UTC midnight (leap second 60 accepted).
std::optional<double> parse_time_of_day(std::string_view s);

struct Date {
  int year = 0, month = 0, day = 0;
  friend bool operator==(const Date&, const Date&) = default;
};
// ddmmyy; years 80..99 are 1980..1999, 00..79 are 2000..2079.
std::optional<Date> parse_date(std::string_view s);

// Fixed-point with `decimals` digits, e.g. format_fixed(-1.5, 2) = "-1.50"; with `plus` a '+' on non-negatives.
std::string format_fixed(double v, int decimals, bool plus = false);
struct Coordinate {
  std::string value;       // ddmm.mmmm or dddmm.mmmm
  std::string hemisphere;  // "N"/"S" or "E"/"W"
};
Coordinate format_latitude(double deg, int minute_decimals);
Coordinate format_longitude(double deg, int minute_decimals);
// seconds since midnight (wrapped into [0, 86400)) → hhmmss.ss with `decimals` fraction digits.
std::string format_time_of_day(double s, int decimals);
std::string format_date(const Date& d);  // ddmmyy

}  // namespace fsd::nmea

// libFuzzer target for the NMEA 0183 path of the GNSS-INS driver: framing, checksum, sentence parsers, epoch
// assembly, geodesy and the sample. Links fsd_drivers (which brings fsd_common).
//
// Input: byte 0 chooses the driver settings (epoch ender, checksum required, origin mode) and how the rest is cut
// into chunks; bytes 1.. are the serial stream. The seed corpus in corpus/nmea/ holds real receiver output and the
// virtual car's output, each behind one such byte.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <numbers>
#include <span>
#include <string_view>

#include "common/wire/nmea.hpp"
#include "drivers/gnss/gnss_driver.hpp"
#include "drivers/gnss/nmea_sentences.hpp"

namespace {

void check(bool ok) {
  if (!ok) std::abort();
}

void check_sample(const fsd::GnssSample& s) {
  check(std::isfinite(s.stamp) && std::isfinite(s.lat_deg) && std::isfinite(s.lon_deg) && std::isfinite(s.alt_m));
  check(std::isfinite(s.enu.x()) && std::isfinite(s.enu.y()) && std::isfinite(s.enu.z()));
  check(std::isfinite(s.speed) && s.speed >= 0.0);
  check(std::abs(s.heading) <= std::numbers::pi + 1e-9 && std::abs(s.course) <= std::numbers::pi + 1e-9);
  check(std::isfinite(s.yaw_rate) && std::isfinite(s.roll) && std::isfinite(s.pitch));
  check(!s.good || (s.fix_quality != 0 && s.heading_valid));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::uint8_t sel = data[0];
  static constexpr const char* kEnders[] = {"auto", "GGA", "RMC", "VTG", "HDT", "PASHR", "ROT", "auto"};
  fsd::GnssConfig c;
  c.emit_on = kEnders[sel & 7];
  c.require_checksum = (sel & 0x08) == 0;
  c.use_first_fix = (sel & 0x10) == 0;
  c.origin_lat_deg = 49.3278;
  c.origin_lon_deg = 8.5658;
  c.origin_height_m = 150.0;
  const std::size_t chunk = (sel >> 5) == 0 ? size : (sel >> 5) * 3;  // whole input or 3..21-byte chunks

  fsd::GnssDriver driver(c, check_sample);
  const std::span<const std::uint8_t> stream(data + 1, size - 1);
  double t = 0.0;
  for (std::size_t i = 0; i < stream.size(); i += chunk, t += 0.001)
    driver.feed(stream.subspan(i, std::min(chunk, stream.size() - i)), t);
  const fsd::GnssCounters k = driver.counters();
  check(k.framing.bytes == stream.size());
  check(k.samples >= k.good_samples);

  // The pieces on their own, on the raw input as one line.
  const std::string_view text(reinterpret_cast<const char*>(stream.data()), stream.size());
  const fsd::nmea::Unframed u = fsd::nmea::unframe(text, false);
  (void)fsd::parse_sentence(u.error == fsd::nmea::FrameError::None ? u.payload : text);
  (void)fsd::nmea::parse_time_of_day(text);
  (void)fsd::nmea::parse_date(text);
  (void)fsd::nmea::parse_latitude(text, "N");
  return 0;
}

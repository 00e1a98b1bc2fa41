#include "drivers/gnss/gnss_config.hpp"

#include <stdexcept>

namespace fsd {

const ConfigSection<GnssConfig>& gnss_section() {
  static const auto s =
      ConfigSection<GnssConfig>("drivers.gnss")
          .string("device", &GnssConfig::device, {}, "Serial device of the GNSS-INS receiver (a pty slave in sim).")
          .integer("baud", &GnssConfig::baud, 1200, 4000000, "baud", "Line rate, 8N1; any rate the UART supports.")
          .boolean("use_first_fix", &GnssConfig::use_first_fix,
                   "Put the local ENU origin at the rear axle of the first good fix; false: use origin_*.")
          .number("origin_lat_deg", &GnssConfig::origin_lat_deg, -90.0, 90.0, "deg",
                  "Latitude of the local ENU origin (WGS-84) when use_first_fix is false.")
          .number("origin_lon_deg", &GnssConfig::origin_lon_deg, -180.0, 180.0, "deg",
                  "Longitude of the local ENU origin (WGS-84) when use_first_fix is false.")
          .number("origin_height_m", &GnssConfig::origin_height_m, -1000.0, 10000.0, "m",
                  "Height of the local ENU origin above the WGS-84 ellipsoid (not above sea level).")
          .string("min_fix", &GnssConfig::min_fix, {"single", "dgps", "rtk_float", "rtk_fixed"},
                  "Weakest GGA fix quality that counts as GNSS good.")
          .boolean("dead_reckoning_good", &GnssConfig::dead_reckoning_good,
                   "Count GGA quality 6 (INS dead reckoning) as GNSS good.", true)
          .integer("min_satellites", &GnssConfig::min_satellites, 0, 99, "", "Fewest satellites in use for GNSS good.",
                   true)
          .number("max_hdop", &GnssConfig::max_hdop, 0.1, 99.0, "", "Largest HDOP for GNSS good.", true)
          .number("max_diff_age_s", &GnssConfig::max_diff_age_s, 0.0, 600.0, "s",
                  "Oldest differential corrections for GNSS good (when min_fix needs corrections).", true)
          .boolean("require_heading", &GnssConfig::require_heading,
                   "GNSS good needs a heading (HDT or PASHR) in the same epoch.", true)
          .integer("max_line_length", &GnssConfig::max_line_length, 82, 4096, "characters",
                   "Longest accepted sentence from '$' to the checksum; longer lines are dropped and counted.")
          .boolean("require_checksum", &GnssConfig::require_checksum, "Reject sentences without a '*HH' checksum.")
          .string("emit_on", &GnssConfig::emit_on, {"auto", "GGA", "RMC", "VTG", "HDT", "PASHR", "ROT"},
                  "Sentence that ends a receiver epoch and triggers the sample; auto learns it as the last "
                  "sentence before the UTC time changes.")
          .number("latency_s", &GnssConfig::latency_s, 0.0, 1.0, "s",
                  "Receiver output latency subtracted from the receive time to stamp a sample.");
  return s;
}

GnssConfig read_gnss_config(const Config& config) {
  GnssConfig c = gnss_section().read(config);
  const Lever antenna = read_car(config).gnss_antenna;
  c.antenna_x = antenna.x;
  c.antenna_y = antenna.y;
  c.antenna_z = antenna.z;
  return c;
}

int fix_rank(int gga_quality) {
  switch (gga_quality) {
    case 1:
      return 1;
    case 6:
      return 1;  // dead reckoning: no better than a single-point fix unless accepted explicitly
    case 2:
      return 2;
    case 3:
      return 2;
    case 9:
      return 2;  // WAAS/SBAS on some receivers
    case 5:
      return 3;
    case 4:
      return 4;
    default:
      return 0;
  }
}

int fix_rank(const std::string& min_fix) {
  if (min_fix == "single") return 1;
  if (min_fix == "dgps") return 2;
  if (min_fix == "rtk_float") return 3;
  if (min_fix == "rtk_fixed") return 4;
  throw std::invalid_argument("drivers.gnss.min_fix: unknown fix '" + min_fix + "'");
}

}  // namespace fsd

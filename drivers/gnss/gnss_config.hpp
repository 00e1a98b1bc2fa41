#pragma once
// Configuration of the GNSS-INS driver (section "drivers.gnss").
#include <string>

#include "common/car.hpp"
#include "common/config.hpp"

namespace fsd {

struct GnssConfig {
  // The receiver's serial port (fsd run on the car; the NMEA parsing below does not use these).
  std::string device = "/dev/ttyGNSS";  // deploy/99-fsd.rules makes this symlink; a pty slave in sim
  int baud = 115200;

  // Local ENU origin: the first good fix (its rear-axle point) or the geodetic point below.
  bool use_first_fix = true;
  double origin_lat_deg = 0.0;
  double origin_lon_deg = 0.0;
  double origin_height_m = 0.0;  // above the WGS-84 ellipsoid (GGA altitude + geoid separation)

  // "GNSS good": every condition must hold.
  std::string min_fix = "rtk_float";  // single < dgps < rtk_float < rtk_fixed
  bool dead_reckoning_good = false;   // accept GGA quality 6 (INS coasting) regardless of min_fix
  int min_satellites = 5;
  double max_hdop = 2.0;
  double max_diff_age_s = 3.0;  // checked when min_fix needs corrections and the receiver reports an age
  bool require_heading = true;  // HDT or PASHR heading present in the epoch

  // Antenna phase centre in the vehicle frame (x forward, y left, z up from the rear-axle centre on the ground):
  // the car's description, car.gnss_antenna.
  double antenna_x = CarDescription{}.gnss_antenna.x;
  double antenna_y = CarDescription{}.gnss_antenna.y;
  double antenna_z = CarDescription{}.gnss_antenna.z;

  int max_line_length = 120;  // characters from '$' to the checksum; longer lines are dropped
  bool require_checksum = true;
  // Sentence type that ends a receiver epoch and triggers the sample; "auto" learns it from the stream.
  std::string emit_on = "auto";
  double latency_s = 0.0;  // subtracted from the receive time of an epoch's first sentence
};

const ConfigSection<GnssConfig>& gnss_section();
// The section plus the antenna of the car's description (car.gnss_antenna).
GnssConfig read_gnss_config(const Config& config);

// Ordering of GGA fix qualities for "min_fix": 0 none/manual/simulator, 1 single (and dead reckoning),
// 2 DGPS/PPS, 3 RTK float, 4 RTK fixed.
int fix_rank(int gga_quality);
// Rank of a min_fix name; throws std::invalid_argument for an unknown one.
int fix_rank(const std::string& min_fix);

}  // namespace fsd

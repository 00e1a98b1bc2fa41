// libFuzzer target for the sensor log parser of `fsd localize` (drivers/logs/sensor_csv).
// The first byte picks the log's columns (IMU, optical speed, GNSS) so one corpus covers all three; invariants
// beyond "no crash": a parsed log has at least one row, a whole number of rows, every value finite, time strictly
// increasing and no gap beyond the limit; a rejection is a SensorCsvError with a message naming the origin.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "drivers/logs/sensor_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  fsd::SensorCsvSpec spec;
  switch (data[0] % 3) {
    case 0:
      spec.columns = {"t_unix_s",   "gyro_x_rad_s", "gyro_y_rad_s", "gyro_z_rad_s",
                      "acc_x_m_s2", "acc_y_m_s2",   "acc_z_m_s2"};
      spec.max_gap_s = 0.5;
      break;
    case 1:
      spec.columns = {"t_unix_s", "vx_m_s", "vy_m_s"};
      spec.max_gap_s = 0.5;
      break;
    default:
      spec.columns = {"t_unix_s", "lat_deg", "lon_deg", "east_m", "north_m"};
      break;
  }
  spec.max_rows = 2000;  // small, so that the limit path is reached
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const fsd::SensorCsv c = fsd::parse_sensor_csv(text, "fuzz.csv", spec);
    if (c.rows() == 0 || c.rows() > spec.max_rows || c.values.size() % c.columns != 0) std::abort();
    for (const double v : c.values)
      if (!std::isfinite(v)) std::abort();
    for (std::size_t i = 1; i < c.rows(); ++i) {
      const double dt = c.at(i, 0) - c.at(i - 1, 0);
      if (!(dt > 0)) std::abort();
      if (spec.max_gap_s > 0 && dt > spec.max_gap_s) std::abort();
    }
  } catch (const fsd::SensorCsvError& e) {
    if (std::string_view(e.what()).substr(0, 8) != "fuzz.csv") std::abort();
  }
  return 0;
}

// libFuzzer target for the CSV point cloud parser of `fsd detect` (drivers/cloud/csv_cloud).
// Invariants checked beyond "no crash": a parsed cloud has at least one point and at most the point limit, every
// point finite and within the coordinate bound, distance and azimuth consistent with x, y, z, and rows =
// points + dropped rows; a rejection is a CloudError with a message.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "drivers/cloud/csv_cloud.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fsd::CsvCloudLimits limits;
  limits.max_points = 5000;  // small, so that the limit path is reached
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const fsd::CsvCloud c = fsd::parse_csv_cloud(text, "fuzz.csv", limits);
    if (c.scan.points.empty() || c.scan.points.size() > limits.max_points) std::abort();
    if (c.rows != c.scan.points.size() + c.invalid) std::abort();
    for (const auto& p : c.scan.points) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.intensity) ||
          !std::isfinite(p.t))
        std::abort();
      if (std::abs(p.x) > limits.max_coordinate || std::abs(p.y) > limits.max_coordinate ||
          std::abs(p.z) > limits.max_coordinate)
        std::abort();
      const double d = std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z);
      if (std::abs(d - p.distance) > 1e-3 * (1.0 + d)) std::abort();
      if (!(p.azimuth >= 0.0f && p.azimuth <= 6.2832f)) std::abort();
    }
  } catch (const fsd::CloudError& e) {
    if (std::string_view(e.what()).empty()) std::abort();
  }
  return 0;
}

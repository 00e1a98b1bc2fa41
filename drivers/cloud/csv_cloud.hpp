#pragma once
// Point clouds from CSV text, for `fsd detect --cloud FILE` (DESIGN.md §9): one point a row, `x,y,z[,intensity]`
// in metres in the cloud's own frame (x forward, y left, z up), an optional header. With a header, columns are
// found by name and others are ignored, so `fsd lidar-dump --csv` output (t_us,laser,...,x,y,z) reads too, with
// each point's laser and firing time. Untrusted input: malformed rows, a wrong number of fields, a cloud beyond
// the limits or without a single valid point are rejected (CloudError naming the line); rows whose coordinates
// are not finite (NaN, inf) or absurdly far are dropped and counted.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "common/types.hpp"

namespace fsd {

class CloudError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CsvCloudLimits {
  std::size_t max_points = 2'000'000;       // rows with a point (a VLP-16 revolution has ~29 k)
  std::uintmax_t max_bytes = 256ull << 20;  // file size
  double max_coordinate = 1000.0;           // m: farther rows are dropped as invalid
};

struct CsvCloud {
  Scan scan;                // points with distance and azimuth from the frame origin; ring and t when given
  std::size_t rows = 0;     // data rows
  std::size_t invalid = 0;  // rows dropped: a coordinate beyond max_coordinate (NaN, inf), an intensity beyond
                            // ±1e6 or a time beyond ±1e15 µs
  bool header = false;
  bool has_intensity = false, has_lasers = false, has_times = false;
};

// `origin` names the text in error messages ("FILE:LINE: problem").
CsvCloud parse_csv_cloud(std::string_view text, const std::string& origin, const CsvCloudLimits& limits = {});
// Reads and parses a file; throws CloudError when it is missing, unreadable or too large.
CsvCloud load_csv_cloud(const std::filesystem::path& file, const CsvCloudLimits& limits = {});

}  // namespace fsd

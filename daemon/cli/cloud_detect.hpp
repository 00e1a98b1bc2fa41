#pragma once
// `fsd detect --cloud FILE`: the LiDAR stages on one cloud in the input's own frame (DESIGN.md §9). The cloud is a
// CSV (drivers/cloud/csv_cloud.hpp) or a VLP-16 pcap (its first full revolution, the real decoder). One frame: no
// motion, no accumulation. The frame is the sensor's own (x forward, y left, z up at the sensor), so the ground
// plane is searched 0.1-3 m below the origin, at any tilt up to perception.lidar.ground.max_tilt_deg, and the
// metre around the sensor is cut out (its own mount); every other perception.lidar.* key applies as configured.
#include <filesystem>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "common/types.hpp"
#include "perception/lidar_cone_detector.hpp"

namespace fsd {

struct LoadedCloud {
  Scan scan;
  std::string kind;             // "csv" or "pcap"
  std::size_t dropped = 0;      // CSV rows dropped (coordinates not finite or absurd)
  bool partial = false;         // pcap: less than one revolution in the file
  double azimuth_span_deg = 0;  // pcap: azimuth covered
};

// Throws CloudError, PcapError or LaserTableError (all bad input) when the file cannot give a cloud.
LoadedCloud load_cloud(const std::filesystem::path& file);

// The configured LiDAR stages adapted to a cloud in its sensor's own frame (see above).
// A CSV's intensity column has no known scale (another sensor's, normalised, or absent): the rejection of black
// rubber by its VLP-16 reflectivity is off for it, on for a pcap's.
LidarDetectorConfig detect_frame_config(LidarDetectorConfig cfg, const LoadedCloud& cloud);

// {"cones": [{"x","y","z","colour","confidence","points"}...], "ground": {"a","b","h"}}, keys in that order.
nlohmann::ordered_json detection_json(const LidarDetection& d);
// A readable report: the cloud, the ground plane, what each stage dropped, a table of the cones.
std::string detection_table(const std::string& file, const LoadedCloud& cloud, const LidarDetection& d);

}  // namespace fsd

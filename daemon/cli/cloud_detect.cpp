#include "daemon/cli/cloud_detect.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "drivers/cloud/csv_cloud.hpp"
#include "drivers/vlp16/pcap_revolution.hpp"

namespace fsd {

LoadedCloud load_cloud(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw CloudError(file.string() + ": no such file");
  LoadedCloud out;
  if (looks_like_pcap(file)) {
    Vlp16Revolution rev = read_first_revolution(file, Vlp16Config{});
    if (rev.scan.points.empty())
      throw CloudError(file.string() + ": no VLP-16 return in the capture (" + std::to_string(rev.packets) +
                       " data packets accepted, " + std::to_string(rev.rejected_packets) + " rejected)");
    out.scan = std::move(rev.scan);
    out.kind = "pcap";
    out.partial = !rev.complete;
    out.azimuth_span_deg = rev.azimuth_span_deg;
    return out;
  }
  CsvCloud csv = load_csv_cloud(file);
  out.scan = std::move(csv.scan);
  out.kind = "csv";
  out.dropped = csv.invalid;
  return out;
}

LidarDetectorConfig detect_frame_config(LidarDetectorConfig cfg, const LoadedCloud& cloud) {
  if (cloud.kind != "pcap") cfg.colour.reject_black = false;
  cfg.ground.height_min = -3.0;
  cfg.ground.height_max = -0.1;
  cfg.roi.body_x_min = cfg.roi.body_y_min = -1.0;
  cfg.roi.body_x_max = cfg.roi.body_y_max = 1.0;
  return cfg;
}

nlohmann::ordered_json detection_json(const LidarDetection& d) {
  nlohmann::ordered_json cones = nlohmann::ordered_json::array();
  for (const auto& c : d.detections.cones)
    cones.push_back(nlohmann::ordered_json{{"x", c.position.x()},
                                           {"y", c.position.y()},
                                           {"z", c.position.z()},
                                           {"colour", std::string(to_string(c.colour))},
                                           {"confidence", c.confidence},
                                           {"points", c.points}});
  return nlohmann::ordered_json{
      {"cones", cones}, {"ground", nlohmann::ordered_json{{"a", d.ground.a}, {"b", d.ground.b}, {"h", d.ground.h}}}};
}

std::string detection_table(const std::string& file, const LoadedCloud& cloud, const LidarDetection& d) {
  std::string o;
  char line[256];
  const auto add = [&](const char* fmt, auto... args) {
    std::snprintf(line, sizeof line, fmt, args...);
    o += line;
  };
  const auto& n = d.counters;
  add("%s (%s): %zu points", file.c_str(), cloud.kind.c_str(), cloud.scan.points.size());
  if (cloud.dropped > 0) add(", %zu rows dropped (coordinates not finite)", cloud.dropped);
  if (cloud.kind == "pcap")
    add(cloud.partial ? ", partial revolution (%.0f deg)" : ", one revolution", cloud.azimuth_span_deg);
  o += "\n";
  add("ground: z = %+.4f x %+.4f y %+.3f (tilt %.2f deg, %zu inliers, RMS %.3f m)%s\n", d.ground.a, d.ground.b,
      d.ground.h, rad2deg(d.ground.tilt()), d.ground.inliers, d.ground.rms,
      d.ground.valid ? "" : "  NOT FOUND: nominal plane used");
  add("stages: %llu outside the ROI, %llu on the car, %llu ground, %llu below it, %llu above the ROI, %llu obstacle "
      "points (%llu on grazing beams), %llu clusters\n",
      static_cast<unsigned long long>(n.outside_roi), static_cast<unsigned long long>(n.in_body),
      static_cast<unsigned long long>(n.ground), static_cast<unsigned long long>(n.below_ground),
      static_cast<unsigned long long>(n.above_roi), static_cast<unsigned long long>(n.obstacles),
      static_cast<unsigned long long>(n.grazing), static_cast<unsigned long long>(n.clusters));
  add("rejected: %llu too sparse, %llu too wide, %llu too tall, %llu not cone-shaped, %llu too flat, %llu floating, "
      "%llu beside something taller, %llu black (rubber), %llu too large to cluster\n",
      static_cast<unsigned long long>(n.too_sparse), static_cast<unsigned long long>(n.too_wide),
      static_cast<unsigned long long>(n.too_tall), static_cast<unsigned long long>(n.not_cone_shaped),
      static_cast<unsigned long long>(n.too_flat), static_cast<unsigned long long>(n.floating),
      static_cast<unsigned long long>(n.beside_taller), static_cast<unsigned long long>(n.black),
      static_cast<unsigned long long>(n.clusters_too_large));
  add("%zu cone(s), %llu of the clusters split into touching cones\n", d.detections.cones.size(),
      static_cast<unsigned long long>(n.split_clusters));
  if (d.detections.cones.empty()) return o;
  add("  %3s %8s %8s %8s %7s %7s %-10s %5s %6s\n", "#", "x [m]", "y [m]", "z [m]", "range", "height", "colour", "conf",
      "points");
  for (std::size_t i = 0; i < d.detections.cones.size(); ++i) {
    const auto& c = d.detections.cones[i];
    const auto& k = d.candidates[i];
    add("  %3zu %8.3f %8.3f %8.3f %7.2f %7.3f %-10s %5.2f %6u\n", i + 1, c.position.x(), c.position.y(), c.position.z(),
        k.range, k.height, std::string(to_string(c.colour)).c_str(), c.confidence, c.points);
  }
  return o;
}

}  // namespace fsd

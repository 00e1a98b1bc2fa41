#include "daemon/scoring/map_export.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace fsd {

MapExport map_as_track(const std::vector<Cone>& map, const Pose2& start, const ColourConvention& convention,
                       std::string name) {
  MapExport out;
  out.track.name = std::move(name);
  out.track.start = start;
  out.track.convention = convention;
  for (const auto& c : map) {
    const ConeRole role = convention.role_of(c.colour);
    if (role == ConeRole::Unknown) {
      ++out.without_role;
      continue;
    }
    TrackCone t;
    t.position = c.position.head<2>();
    t.role = role;
    t.colour = c.colour;
    out.track.cones.push_back(t);
  }
  return out;
}

void write_map_csv(const std::string& path, const MapExport& map) {
  std::ofstream f(path);
  if (f) f << format_track(map.track);
  if (!f) throw std::invalid_argument("--map-out " + path + ": cannot be written (" + std::strerror(errno) + ")");
}

}  // namespace fsd

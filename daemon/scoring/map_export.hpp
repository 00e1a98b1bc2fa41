#pragma once
// `fsd run --map-out FILE`: the cone map at the end of a run as a track file in the shared EUFS/FSDS CSV format
// (common/track.hpp), so that a lap-1 map can be reused (`fsd run --sim --track FILE` drives it), compared with
// another layout and shown by any tool that reads track files. The map frame is the run's: the car_start row is the
// first pose the Stack drove on.
#include <cstddef>
#include <string>
#include <vector>

#include "common/track.hpp"
#include "common/types.hpp"

namespace fsd {

struct MapExport {
  Track track;
  std::size_t without_role = 0;  // mapped cones whose colour names no boundary in the convention: not written
};

MapExport map_as_track(const std::vector<Cone>& map, const Pose2& start, const ColourConvention& convention,
                       std::string name);

// Writes the file; throws std::invalid_argument naming the path when it cannot be written.
void write_map_csv(const std::string& path, const MapExport& map);

}  // namespace fsd

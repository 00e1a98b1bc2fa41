#pragma once
// Track files in the EUFS/FSDS CSV format of ../shared/tracks:
//   tag,x,y,direction,x_variance,y_variance,xy_covariance
// Tags give each cone's role (blue = left boundary, yellow = right boundary, orange = small orange,
// big_orange = timing/start-finish) and one car_start row whose direction is the start yaw. The physical colour
// of each cone comes from the event's colour convention (FSG: blue/yellow; FSAC 2017: red/blue, yellow timing).
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/types.hpp"

namespace fsd {

struct ColourConvention {
  std::string name = "fsg";
  ConeColour left = ConeColour::Blue;
  ConeColour right = ConeColour::Yellow;
  ConeColour timing = ConeColour::BigOrange;
  ConeColour other = ConeColour::Orange;

  // "fsg" or "fsac"; throws std::invalid_argument otherwise.
  static ColourConvention named(const std::string& name);
  ConeColour colour_of(ConeRole role) const;
  ConeRole role_of(ConeColour colour) const;  // Unknown for a colour the convention does not use
};

struct TrackCone {
  Vec2 position = Vec2::Zero();
  ConeRole role = ConeRole::Unknown;
  ConeColour colour = ConeColour::Unknown;
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
};

struct Track {
  std::string name;  // file stem, e.g. "epfl_track_1"
  Pose2 start;       // car_start row
  ColourConvention convention;
  std::vector<TrackCone> cones;
  int duplicates_dropped = 0;  // rows that repeat a cone already listed (within 1 cm): one physical cone

  std::size_t count(ConeRole role) const;
};

// The track's cones as a perfect cone map would hold them (map frame, on the ground, with their colours).
std::vector<Cone> cones_of(const Track& track);

// Thrown for unreadable or malformed files; what() is "FILE:LINE: problem".
class TrackError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

Track load_track(const std::filesystem::path& path, const ColourConvention& convention = {});
// The file's text for a track: the header, the car_start row, then one row per cone in order with its role's tag;
// positions to 4 decimals (0.1 mm), the start
// yaw to 6, no covariance. parse_track reads it back to the same track. Throws std::invalid_argument
// for a cone without a role.
std::string format_track(const Track& track);
// Parses text already in memory; `origin` names it in error messages.
Track parse_track(const std::string& text, const std::string& origin, const ColourConvention& convention = {});

}  // namespace fsd

#include "daemon/layout_check.hpp"

#include "control/missions.hpp"
#include "control/skidpad.hpp"

namespace fsd {

std::optional<std::string> layout_refusal(const Track& track, Mission mission, const AutopilotConfig& control) {
  std::vector<Cone> cones;
  for (const auto& c : track.cones) {
    Cone k;
    k.position = Vec3(c.position.x(), c.position.y(), 0);
    k.colour = c.colour;
    cones.push_back(k);
  }
  const std::string what = "mission '" + std::string(to_string(mission)) + "' on " + track.name + ": ";
  switch (mission) {
    case Mission::Trackdrive:
    case Mission::Autocross: {
      const auto left = track.count(ConeRole::Left), right = track.count(ConeRole::Right);
      if (left < 2 || right < 2)
        return what + "the layout has one boundary only (" + std::to_string(left) + " left, " + std::to_string(right) +
               " right cones under the '" + track.convention.name + "' colours); the planner needs both";
      return std::nullopt;
    }
    case Mission::Skidpad: {
      std::string reason;
      if (!fit_skidpad(cones, track.start, track.convention, &reason))
        return what + "no skid pad (two circles of cones) around the start: " + reason;
      return std::nullopt;
    }
    case Mission::Acceleration:
    case Mission::EbsTest: {
      const double length = 2.0 * control.mission.acceleration_length + control.mission.acceleration_stop_distance;
      if (!straight_from_cones(cones, track.start, length, control.planner.ds))
        return what + "no straight lane of cones ahead of the start";
      return std::nullopt;
    }
    case Mission::Inspection:
    case Mission::None: return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace fsd

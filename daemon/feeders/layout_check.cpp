#include "daemon/feeders/layout_check.hpp"

#include <algorithm>

#include "control/missions/missions.hpp"
#include "control/missions/skidpad.hpp"
#include "control/missions/straight_lane.hpp"
#include "control/planning/path.hpp"

namespace fsd {

namespace {
constexpr double kLaneReach = 3.0;  // m from the lane's centre line: its boundary cones (lanes are 3-5 m wide)
constexpr double kLaneShare = 0.8;  // of control.mission.acceleration_length the lane's cones must span
}  // namespace

std::optional<std::string> layout_refusal(const Track& track, Mission mission, const AutopilotConfig& control) {
  const std::vector<Cone> cones = cones_of(track);
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
      const auto line = straight_from_cones(cones, track.start, length, control.planner.ds);
      if (!line) return what + "no straight lane of cones ahead of the start";
      // A lane of cones, but is it the acceleration lane? A skid pad's entry lane is straight too, for 15 m.
      double first = 1e9, last = -1e9;
      for (const auto& c : cones) {
        const auto p = project(*line, c.position.head<2>());
        if (!p || p->distance() > kLaneReach) continue;
        first = std::min(first, p->s);
        last = std::max(last, p->s);
      }
      const double span = last > first ? last - first : 0.0;
      if (span < kLaneShare * control.mission.acceleration_length)
        return what + "no straight lane of cones ahead of the start: the cones along it span " +
               std::to_string(static_cast<int>(span)) + " m of the " +
               std::to_string(static_cast<int>(control.mission.acceleration_length)) + " m the mission drives";
      return std::nullopt;
    }
    case Mission::Inspection:
    case Mission::None:
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace fsd

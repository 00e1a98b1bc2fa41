#include "common/types.hpp"

#include <algorithm>
#include <cmath>

namespace fsd {

namespace {
template <class E, std::size_t N>
std::optional<E> lookup(const std::array<std::pair<E, std::string_view>, N>& table, std::string_view s) {
  for (const auto& [e, name] : table)
    if (name == s) return e;
  return std::nullopt;
}
template <class E, std::size_t N>
std::string_view name_of(const std::array<std::pair<E, std::string_view>, N>& table, E e) {
  for (const auto& [v, name] : table)
    if (v == e) return name;
  return "unknown";
}

constexpr std::array<std::pair<ConeColour, std::string_view>, 6> kColours{{{ConeColour::Unknown, "unknown"},
                                                                           {ConeColour::Blue, "blue"},
                                                                           {ConeColour::Yellow, "yellow"},
                                                                           {ConeColour::Orange, "orange"},
                                                                           {ConeColour::BigOrange, "big_orange"},
                                                                           {ConeColour::Red, "red"}}};
constexpr std::array<std::pair<DetectionStage, std::string_view>, 3> kStages{
    {{DetectionStage::Truth, "truth"}, {DetectionStage::Lidar, "lidar"}, {DetectionStage::Camera, "camera"}}};
constexpr std::array<std::pair<ColourSource, std::string_view>, 4> kColourSources{
    {{ColourSource::None, "none"},
     {ColourSource::Truth, "truth"},
     {ColourSource::Camera, "camera"},
     {ColourSource::LidarIntensity, "lidar_intensity"}}};
constexpr std::array<std::pair<ConeRole, std::string_view>, 5> kRoles{{{ConeRole::Unknown, "unknown"},
                                                                       {ConeRole::Left, "left"},
                                                                       {ConeRole::Right, "right"},
                                                                       {ConeRole::Timing, "timing"},
                                                                       {ConeRole::Other, "other"}}};
constexpr std::array<std::pair<AsState, std::string_view>, 5> kStates{{{AsState::Off, "Off"},
                                                                       {AsState::Ready, "Ready"},
                                                                       {AsState::Driving, "Driving"},
                                                                       {AsState::Emergency, "Emergency"},
                                                                       {AsState::Finished, "Finished"}}};
constexpr std::array<std::pair<Mission, std::string_view>, 7> kMissions{{{Mission::None, "none"},
                                                                         {Mission::Acceleration, "acceleration"},
                                                                         {Mission::Skidpad, "skidpad"},
                                                                         {Mission::Trackdrive, "trackdrive"},
                                                                         {Mission::Autocross, "autocross"},
                                                                         {Mission::Inspection, "inspection"},
                                                                         {Mission::EbsTest, "ebs_test"}}};
}  // namespace

std::string_view to_string(ConeColour c) { return name_of(kColours, c); }
std::optional<ConeColour> cone_colour_from_string(std::string_view s) { return lookup(kColours, s); }
std::string_view to_string(ConeRole r) { return name_of(kRoles, r); }
std::string_view to_string(DetectionStage s) { return name_of(kStages, s); }
std::string_view to_string(ColourSource s) { return name_of(kColourSources, s); }
std::string_view to_string(AsState s) { return name_of(kStates, s); }
std::optional<AsState> as_state_from_string(std::string_view s) { return lookup(kStates, s); }
std::string_view to_string(Mission m) { return name_of(kMissions, m); }
std::optional<Mission> mission_from_string(std::string_view s) { return lookup(kMissions, s); }

double VehicleState::speed() const { return std::hypot(vx, vy); }
double VehicleState::sideslip() const { return speed() < 0.1 ? 0.0 : std::atan2(vy, vx); }

FiringSpan firing_span(const Scan& scan) {
  if (scan.points.empty()) return {scan.stamp, scan.stamp};
  FiringSpan f{scan.points.front().t, scan.points.front().t};
  for (const auto& q : scan.points) f.first = std::min(f.first, q.t), f.last = std::max(f.last, q.t);
  return f;
}

}  // namespace fsd

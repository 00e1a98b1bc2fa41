#include "drivers/sim/world/timing_gates.hpp"

#include <cmath>

namespace fsd::sim {

TimingGates::TimingGates(const Track& track) {
  const Vec2 fwd(std::cos(track.start.yaw), std::sin(track.start.yaw));
  std::vector<std::vector<Vec2>> groups;
  for (const auto& c : track.cones) {
    if (c.role != ConeRole::Timing) continue;
    std::vector<Vec2>* group = nullptr;
    for (auto& g : groups)
      for (const auto& q : g)
        if (!group && (q - c.position).norm() < 6.0) group = &g;
    if (group)
      group->push_back(c.position);
    else
      groups.push_back({c.position});
  }
  for (const auto& g : groups) {
    Gate gate;
    for (const auto& q : g) gate.centre += q;
    gate.centre /= static_cast<double>(g.size());
    gate.forward = fwd;
    const Vec2 lat(-fwd.y(), fwd.x());
    double w = 0;
    for (const auto& q : g) w = std::max(w, std::fabs((q - gate.centre).dot(lat)));
    gate.half_width = std::max(1.5, w);
    gates_.push_back(gate);
  }
  if (gates_.empty()) gates_.push_back({track.start.position(), fwd, 3.0});
}

double TimingGates::past(std::size_t i, const Vec2& p) const { return (p - gates_[i].centre).dot(gates_[i].forward); }

std::optional<std::size_t> TimingGates::crossed(const Vec2& a, const Vec2& b) const {
  for (std::size_t i = 0; i < gates_.size(); ++i) {
    const double da = past(i, a), db = past(i, b);
    if (!(da < 0.0 && db >= 0.0)) continue;
    const Vec2 x = a + (b - a) * (da / (da - db));
    const Vec2 lat(-gates_[i].forward.y(), gates_[i].forward.x());
    if (std::fabs((x - gates_[i].centre).dot(lat)) <= gates_[i].half_width) return i;
  }
  return std::nullopt;
}

}  // namespace fsd::sim

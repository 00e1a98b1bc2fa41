#include "localization/fusion/heading_init.hpp"

#include <cmath>

namespace fsd::fusion {

std::optional<HeadingInitialiser::Offset> HeadingInitialiser::add(const Vec2& fix, const Vec2& dr_position) {
  if (!anchor_) {
    anchor_ = std::make_pair(fix, dr_position);
    return std::nullopt;
  }
  const Vec2 g = fix - anchor_->first;
  const Vec2 d = dr_position - anchor_->second;
  // The dead-reckoned chord must be long too: a GNSS step alone (a jump at the start) gives no bearing.
  if (g.norm() < baseline_ || d.norm() < 0.5 * baseline_) return std::nullopt;
  const double yaw = wrap_angle(std::atan2(g.y(), g.x()) - std::atan2(d.y(), d.x()));
  return Offset{yaw, anchor_->first, anchor_->second};
}

}  // namespace fsd::fusion

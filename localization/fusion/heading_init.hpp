#pragma once
// The initial heading from the GNSS track (a single antenna has none of its own): from the first fix taken while
// the car moves, the bearing of the GNSS displacement against the bearing of the filter's dead-reckoned
// displacement over the same interval (integrated with a provisional heading) gives the heading's offset once the
// track is long enough. A curved start is fine: both chords turn by the same angle.
#include <optional>

#include "common/geometry.hpp"

namespace fsd::fusion {

class HeadingInitialiser {
 public:
  explicit HeadingInitialiser(double baseline_m) : baseline_(baseline_m) {}

  struct Offset {
    double yaw;       // to add to the provisional heading
    Vec2 anchor_fix;  // the first fix ...
    Vec2 anchor_dr;   // ... and the provisional position then: p_map = anchor_fix + R(yaw)(p − anchor_dr)
  };
  // A fix while the car moves, with the provisional position at the same instant.
  std::optional<Offset> add(const Vec2& fix, const Vec2& dr_position);
  void reset() { anchor_.reset(); }

 private:
  double baseline_;
  std::optional<std::pair<Vec2, Vec2>> anchor_;
};

}  // namespace fsd::fusion

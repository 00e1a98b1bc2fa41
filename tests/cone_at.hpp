#pragma once
// A cone at (x, y) on the ground with a colour: hand-placed cones for the tests.
#include "common/types.hpp"

namespace fsd::test {

inline Cone cone_at(double x, double y, ConeColour colour) {
  Cone c;
  c.position = Vec3(x, y, 0);
  c.colour = colour;
  return c;
}

}  // namespace fsd::test

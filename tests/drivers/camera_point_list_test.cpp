// The four-point lists of `fsd calibrate-homography`: parsed strictly, every error naming the option.
#include <gtest/gtest.h>

#include <string>

#include "drivers/camera/ground_homography.hpp"

namespace fsd {
namespace {

TEST(CameraPointList, PointListsAreParsedStrictly) {
  const PointQuad q = parse_point_quad("1,2; 3.5,-4 ;5e1,6;  7 , 8", "pts");
  EXPECT_EQ(q[0], Vec2(1, 2));
  EXPECT_EQ(q[1], Vec2(3.5, -4));
  EXPECT_EQ(q[2], Vec2(50, 6));
  EXPECT_EQ(q[3], Vec2(7, 8));
  for (const char* bad :
       {"", "1,2;3,4;5,6", "1,2;3,4;5,6;7,8;9,10", "1,2;3,4;5,6;7", "1,2;3,4;5,6;7,8,9", "1,2;3,4;5,x;7,8",
        "1,2;3,4;5,6;7,8;", "1,2;3,4;;7,8", "1,2;3,4;5,6;nan,8", "1,2;3,4;5,6;inf,8"}) {
    try {
      parse_point_quad(bad, "--image-points");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const HomographyError& e) {
      EXPECT_NE(std::string(e.what()).find("--image-points"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace fsd

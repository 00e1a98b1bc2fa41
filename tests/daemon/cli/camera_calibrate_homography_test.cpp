// `fsd calibrate-homography` as a user runs it: the real binary, its exit status, the file it writes.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "drivers/camera/camera_calibration.hpp"
#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

namespace fs = std::filesystem;

struct Result {
  int status;
  std::string out;
};

Result fsd(const std::string& args) {
  Result r;
  r.status = test::run_fsd(args, &r.out);
  return r;
}

class CalibrateHomographyCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_path(::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// A camera 1 m up looking level (fx = fy = 400, principal point (320, 240)) sees ground (x, y) at
// u = 320 − 400·y/x, v = 240 + 400/x. The four points: (5, ±1) and (10, ±1).
const char* kImage = "--image-points \"240,320;400,320;360,280;280,280\"";
const char* kGround = "--ground-points \"5,1;5,-1;10,-1;10,1\"";

TEST_F(CalibrateHomographyCommand, WritesAHomographyThatMapsOtherPoints) {
  const fs::path out = dir_ / "calib.json";
  const Result r = fsd(std::string("calibrate-homography ") + kImage + " " + kGround + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out;
  const CameraCalibration c = load_camera_calibration(out);
  ASSERT_TRUE(c.homography);
  // Ground (20, −2.5): u = 320 + 50 = 370, v = 240 + 20 = 260.
  const auto px = ground_to_image(c.homography->homography, {20.0, -2.5});
  ASSERT_TRUE(px);
  EXPECT_NEAR(px->x(), 370.0, 1e-3);
  EXPECT_NEAR(px->y(), 260.0, 1e-3);
  const auto g = image_to_ground(c.homography->homography, {320.0, 250.0});  // v = 250 → x = 40, y = 0
  ASSERT_TRUE(g);
  EXPECT_NEAR(g->x(), 40.0, 1e-3);
  EXPECT_NEAR(g->y(), 0.0, 1e-3);
}

TEST_F(CalibrateHomographyCommand, KeepsTheOtherSectionsOfAnExistingFile) {
  CameraCalibration existing;
  CameraIntrinsics intrinsics{640, 480, Eigen::Matrix3d::Identity(), {}};
  intrinsics.K << 400, 0, 320, 0, 400, 240, 0, 0, 1;
  existing.intrinsics = intrinsics;
  existing.extrinsics = CameraMount{0.5, 0, 1.0, 0, 0, 0};
  const fs::path in = dir_ / "in.json", out = dir_ / "out.json";
  save_camera_calibration(existing, in);
  const Result r = fsd(std::string("calibrate-homography ") + kImage + " " + kGround + " --in " + in.string() +
                       " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out;
  const CameraCalibration c = load_camera_calibration(out);
  ASSERT_TRUE(c.intrinsics && c.extrinsics && c.homography);
  EXPECT_EQ(c.intrinsics->width, 640);
  EXPECT_DOUBLE_EQ(c.extrinsics->z, 1.0);
}

TEST_F(CalibrateHomographyCommand, BadInputExitsTwoWithAMessage) {
  const std::string out = " --out " + (dir_ / "x.json").string();
  const struct {
    std::string args, message;
  } cases[] = {
      {std::string("--image-points \"240,320;400,320;360,280\" ") + kGround + out, "expected 4 points"},
      {std::string("--image-points \"240,320;400,320;360,28x;280,280\" ") + kGround + out, "'28x' is not a number"},
      {std::string("--image-points \"240,320;300,320;400,320;280,280\" ") + kGround + out, "collinear"},
      {std::string(kImage) + " --ground-points \"5,1;5,-1;10,1;10,-1\"" + out, "order"},
      {std::string(kImage) + " " + kGround + " --in " + (dir_ / "missing.json").string() + out, "cannot open"},
      {std::string(kImage) + " " + kGround, "--out"},
  };
  for (const auto& c : cases) {
    const Result r = fsd("calibrate-homography " + c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.message), std::string::npos) << c.args << "\n" << r.out;
  }
  EXPECT_FALSE(fs::exists(dir_ / "x.json")) << "nothing written on bad input";
}

}  // namespace
}  // namespace fsd

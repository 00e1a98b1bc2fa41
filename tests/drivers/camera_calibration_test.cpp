// Camera calibration file: round trip and every validation error, each naming the file and the field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "drivers/camera/camera_calibration.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class CameraCalibrationFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_path(::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// A complete calibration: a 640×480 camera 1.2 m up, and the homography of four points from a rectangle on the
// ground (pixels chosen by hand, the homography computed by the library).
CameraCalibration full_calibration() {
  CameraCalibration c;
  CameraIntrinsics in;
  in.width = 640;
  in.height = 480;
  in.K << 500, 0, 320, 0, 505, 240, 0, 0, 1;
  in.distortion = {-0.1, 0.02, 0.001, -0.002, 0.0};
  c.intrinsics = in;
  c.extrinsics = CameraMount{0.5, 0.0, 1.2, 0.01, 0.15, -0.02};
  HomographyCalibration h;
  h.image_points = PointQuad{Vec2(200, 400), Vec2(440, 400), Vec2(380, 300), Vec2(260, 300)};
  h.ground_points = PointQuad{Vec2(5, 2), Vec2(5, -2), Vec2(10, -2), Vec2(10, 2)};
  h.homography = compute_ground_homography(*h.image_points, *h.ground_points);
  c.homography = h;
  return c;
}

TEST_F(CameraCalibrationFile, RoundTripKeepsEveryValue) {
  const CameraCalibration c = full_calibration();
  const fs::path file = dir_ / "calib.json";
  save_camera_calibration(c, file);
  const CameraCalibration back = load_camera_calibration(file);
  ASSERT_TRUE(back.intrinsics && back.extrinsics && back.homography);
  EXPECT_EQ(back.intrinsics->width, 640);
  EXPECT_EQ(back.intrinsics->height, 480);
  for (int i = 0; i < 9; ++i) EXPECT_DOUBLE_EQ(back.intrinsics->K(i), c.intrinsics->K(i));
  EXPECT_EQ(back.intrinsics->distortion, c.intrinsics->distortion);
  EXPECT_DOUBLE_EQ(back.extrinsics->z, 1.2);
  EXPECT_DOUBLE_EQ(back.extrinsics->pitch, 0.15);
  EXPECT_DOUBLE_EQ(back.extrinsics->yaw, -0.02);
  for (int i = 0; i < 9; ++i)
    EXPECT_DOUBLE_EQ(back.homography->homography.image_to_ground(i), c.homography->homography.image_to_ground(i));
  EXPECT_EQ(*back.homography->image_points, *c.homography->image_points);
  EXPECT_EQ(*back.homography->ground_points, *c.homography->ground_points);
  // The loaded homography maps the calibration pixels onto their ground points.
  for (std::size_t i = 0; i < 4; ++i) {
    const auto g = image_to_ground(back.homography->homography, (*c.homography->image_points)[i]);
    ASSERT_TRUE(g);
    EXPECT_NEAR(g->x(), (*c.homography->ground_points)[i].x(), 1e-4);
    EXPECT_NEAR(g->y(), (*c.homography->ground_points)[i].y(), 1e-4);
  }
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
}

TEST_F(CameraCalibrationFile, SectionsAreOptional) {
  CameraCalibration only_h;
  only_h.homography = full_calibration().homography;
  only_h.homography->image_points.reset();
  only_h.homography->ground_points.reset();
  const fs::path file = dir_ / "h.json";
  save_camera_calibration(only_h, file);
  const CameraCalibration back = load_camera_calibration(file);
  EXPECT_FALSE(back.intrinsics);
  EXPECT_FALSE(back.extrinsics);
  ASSERT_TRUE(back.homography);
  EXPECT_FALSE(back.homography->image_points);
}

TEST(CameraMount, OpticalAxisLooksForwardAndDownByThePitch) {
  const Pose3 T = CameraMount{0.5, 0.1, 1.2, 0.0, 0.15, 0.0}.body_from_optical();
  const Vec3 axis = T.linear() * Vec3::UnitZ();  // optical z = viewing direction
  EXPECT_NEAR(axis.x(), std::cos(0.15), 1e-12);
  EXPECT_NEAR(axis.y(), 0.0, 1e-12);
  EXPECT_NEAR(axis.z(), -std::sin(0.15), 1e-12);
  const Vec3 right = T.linear() * Vec3::UnitX();  // image u grows to the car's right (−y)
  EXPECT_NEAR(right.y(), -1.0, 1e-12);
  EXPECT_TRUE(T.translation().isApprox(Vec3(0.5, 0.1, 1.2)));
}

struct BadCase {
  const char* what;
  std::function<void(json&)> mutate;
  const char* expected;  // substring of the error
};

TEST(CameraCalibrationValidation, EachErrorNamesTheField) {
  const json good = to_json(full_calibration());
  ASSERT_NO_THROW(parse_camera_calibration(good, "calib.json"));
  const std::vector<BadCase> cases{
      {"not an object", [](json& j) { j = json::array(); }, "expected an object"},
      {"unknown top-level field", [](json& j) { j["lens"] = 1; }, "field 'lens': unknown field"},
      {"wrong format tag", [](json& j) { j["format"] = "other"; }, "field 'format'"},
      {"future version", [](json& j) { j["version"] = 2; }, "field 'version': unsupported"},
      {"nothing in it",
       [](json& j) {
         j = {{"version", 1}};
       },
       "holds no calibration"},
      {"missing K", [](json& j) { j["intrinsics"].erase("K"); }, "field 'intrinsics.K': missing"},
      {"K not 3x3",
       [](json& j) {
         j["intrinsics"]["K"] = {{1, 0, 0}, {0, 1, 0}};
       },
       "field 'intrinsics.K': expected a 3×3"},
      {"K row short",
       [](json& j) {
         j["intrinsics"]["K"][1] = {0, 1};
       },
       "row 1 has 2 numbers"},
      {"K text", [](json& j) { j["intrinsics"]["K"][0][0] = "500"; }, "field 'intrinsics.K[0][0]': expected a number"},
      {"negative focal", [](json& j) { j["intrinsics"]["K"][0][0] = -500.0; }, "focal lengths"},
      {"not upper triangular", [](json& j) { j["intrinsics"]["K"][2][2] = 2.0; }, "upper triangular"},
      {"principal point outside", [](json& j) { j["intrinsics"]["K"][0][2] = 900.0; }, "principal point"},
      {"zero width", [](json& j) { j["intrinsics"]["width"] = 0; }, "field 'intrinsics.width': 0 is outside"},
      {"fractional height", [](json& j) { j["intrinsics"]["height"] = 480.5; },
       "field 'intrinsics.height': expected an integer"},
      {"distortion count",
       [](json& j) {
         j["intrinsics"]["distortion"] = {0.1, 0.2, 0.3};
       },
       "has 3 coefficients"},
      {"distortion text", [](json& j) { j["intrinsics"]["distortion"][1] = "x"; }, "field 'intrinsics.distortion[1]'"},
      {"missing z", [](json& j) { j["extrinsics"].erase("z"); }, "field 'extrinsics.z': missing"},
      {"pitch out of range", [](json& j) { j["extrinsics"]["pitch"] = 2.0; },
       "field 'extrinsics.pitch': 2.000000 is outside"},
      {"mount far off the car", [](json& j) { j["extrinsics"]["x"] = 50.0; }, "field 'extrinsics.x'"},
      {"unknown extrinsics field", [](json& j) { j["extrinsics"]["scale"] = 1.0; },
       "field 'extrinsics.scale': unknown"},
      {"singular homography",
       [](json& j) {
         j["homography"]["image_to_ground"] = {{1, 2, 3}, {2, 4, 6}, {0, 0, 1}};
       },
       "field 'homography.image_to_ground': homography is singular"},
      {"homography disagrees with its points",
       [](json& j) {
         j["homography"]["ground_points"][2] = {11.0, -2.0};
       },
       "does not map image point 3 onto ground point 3"},
      {"points without partner", [](json& j) { j["homography"].erase("ground_points"); },
       "field 'homography.ground_points': missing"},
      {"three points", [](json& j) { j["homography"]["image_points"].erase(3); },
       "field 'homography.image_points': expected 4 points"},
  };
  for (const auto& c : cases) {
    json j = good;
    c.mutate(j);
    try {
      parse_camera_calibration(j, "calib.json");
      ADD_FAILURE() << c.what << ": accepted";
    } catch (const CalibrationError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind("calib.json: ", 0), 0u) << c.what << ": " << msg;
      EXPECT_NE(msg.find(c.expected), std::string::npos) << c.what << ": " << msg;
    }
  }
}

TEST_F(CameraCalibrationFile, UnreadableFilesAreReported) {
  EXPECT_THROW(load_camera_calibration(dir_ / "missing.json"), CalibrationError);
  const fs::path broken = dir_ / "broken.json";
  std::ofstream(broken) << "{ \"intrinsics\": ";
  try {
    load_camera_calibration(broken);
    FAIL();
  } catch (const CalibrationError& e) {
    EXPECT_NE(std::string(e.what()).find("not valid JSON"), std::string::npos) << e.what();
  }
  // A number beyond a double is nlohmann's out_of_range, not a parse_error (found by cone_model_fuzz).
  const fs::path overflow = dir_ / "overflow.json";
  std::ofstream(overflow) << "{ \"extrinsics\": { \"x\": 1e999 } }";
  EXPECT_THROW(load_camera_calibration(overflow), CalibrationError);
  EXPECT_THROW(save_camera_calibration(full_calibration(), dir_ / "no_such_dir" / "c.json"), CalibrationError);
}

}  // namespace
}  // namespace fsd

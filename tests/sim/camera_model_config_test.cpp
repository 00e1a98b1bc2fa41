// Camera model configuration: the "sim.camera" keys and the pinhole geometry derived from them.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "drivers/sim/sensors/camera_model_config.hpp"

namespace fsd::sim {
namespace {

std::shared_ptr<const ConfigSchema> schema() {
  auto s = std::make_shared<ConfigSchema>();
  camera_section().describe(*s);  // throws if a default lies outside its bounds
  return s;
}

TEST(CameraConfig, SectionDefaultsAreTheStructsAndOverridesAreChecked) {
  Config cfg(schema());
  const CameraConfig d = camera_section().read(cfg);
  EXPECT_EQ(d.rate, 20.0);
  EXPECT_EQ(d.width, 640);
  EXPECT_EQ(d.height, 480);
  EXPECT_EQ(d.jpeg_quality, 85);
  cfg.merge(nlohmann::json::parse(R"({"sim": {"camera": {"rate": 30, "pitch": 0.2, "width": 800}}})"), "test");
  const CameraConfig c = camera_section().read(cfg);
  EXPECT_EQ(c.rate, 30.0);
  EXPECT_EQ(c.pitch, 0.2);
  EXPECT_EQ(c.width, 800);
  EXPECT_THROW(cfg.set("sim.camera.rate", 100, "test"), ConfigError);
  EXPECT_THROW(cfg.set("sim.camera.jpeg_quality", 0, "test"), ConfigError);
}

TEST(CameraConfig, IntrinsicsFromTheFieldOfViewOrGivenValues) {
  CameraConfig c;
  c.hfov = 1.2;
  const PinholeIntrinsics k = camera_intrinsics(c);
  EXPECT_NEAR(k.fx, 320.0 / std::tan(0.6), 1e-9);  // half the width over tan(half the field of view)
  EXPECT_EQ(k.fy, k.fx);
  EXPECT_EQ(k.cx, 319.5);
  EXPECT_EQ(k.cy, 239.5);
  c.fx = 500;
  c.fy = 510;
  c.cx = 300;
  c.cy = 250;
  const PinholeIntrinsics g = camera_intrinsics(c);
  EXPECT_EQ(g.fx, 500);
  EXPECT_EQ(g.fy, 510);
  EXPECT_EQ(g.cx, 300);
  EXPECT_EQ(g.cy, 250);
}

TEST(CameraConfig, MountLooksForwardAndDownByThePitch) {
  CameraConfig c;
  c.x = 0.5;
  c.z = 1.05;
  c.pitch = 0.1;
  c.yaw = 0.0;
  const Pose3 T = camera_mount(c);
  const Vec3 view = T.linear() * Vec3::UnitZ();
  EXPECT_NEAR(view.x(), std::cos(0.1), 1e-12);
  EXPECT_NEAR(view.z(), -std::sin(0.1), 1e-12);
  EXPECT_NEAR((T.linear() * Vec3::UnitX()).y(), -1.0, 1e-12) << "image right is the car's right";
  EXPECT_NEAR((T.linear() * Vec3::UnitY()).z(), -std::cos(0.1), 1e-12) << "image down is down";
  EXPECT_TRUE(T.translation().isApprox(Vec3(0.5, 0.0, 1.05)));
}

}  // namespace
}  // namespace fsd::sim

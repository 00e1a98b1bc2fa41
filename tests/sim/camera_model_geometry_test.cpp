// Camera model geometry: where cones, the horizon and fallen cones land in the image, checked against pinhole
// projections computed by hand from the intrinsics and the mounting.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "common/track.hpp"

#include "tests/sim/camera_test_util.hpp"
#include "tests/sim/world_test_util.hpp"

namespace fsd::sim {
namespace {

using test::hue_mask;
using test::make_cone;
using test::make_track;
using test::plain_camera;

constexpr double kF = 400.0, kCx = 319.5, kCy = 239.5, kCamHeight = 1.0;
// Small cone dimensions from the FSG rules: 228 mm base, 325 mm high; 50 mm tip.
constexpr double kR0 = 0.114, kR1 = 0.025, kH = 0.325;

double u_of(double x, double y) { return kCx - kF * y / x; }
double v_of(double x, double z) { return kCy + kF * (kCamHeight - z) / x; }

// Cone blue is far more saturated than the sky (S ≈ 0.84 against at most 0.55); dark blue (the hollow inside of a
// fallen cone) counts too.
cv::Rect blue_box(const cv::Mat& img) { return cv::boundingRect(hue_mask(img, 100, 130, 170, 20)); }

TEST(CameraModelGeometry, StandingConeBoxMatchesPinholeProjection) {
  const World world(make_track({make_cone(8.0, 0.0, ConeRole::Left)}), test::bare_config(), 1);
  const CameraModel cam(plain_camera(), world, 1);
  const cv::Mat img = cam.render(Pose3::Identity());
  ASSERT_EQ(img.size(), cv::Size(640, 480));
  ASSERT_EQ(img.type(), CV_8UC3);

  // By hand: the widest part is the base circle (tangent rays at asin(r/d)), the highest image point the far edge
  // of the top disc, the lowest the near edge of the base.
  const double half_width = kR0 / std::sqrt(8.0 * 8.0 - kR0 * kR0);
  const double left = kCx - kF * half_width, right = kCx + kF * half_width;
  const double top = v_of(8.0 + kR1, kH), bottom = v_of(8.0 - kR0, 0.0);

  const cv::Rect box = blue_box(img);
  ASSERT_GT(box.area(), 0) << "no blue pixels";
  // Filled pixels have their centres inside the silhouette: the first column is the one right of `left`, etc.
  EXPECT_NEAR(box.x, left, 1.0);
  EXPECT_NEAR(box.x + box.width - 1, right, 1.0);
  EXPECT_NEAR(box.y, top, 1.0);
  EXPECT_NEAR(box.y + box.height - 1, bottom, 1.0);
}

TEST(CameraModelGeometry, ConeOffAxisAndRotatedCarMatchProjection) {
  // Car at (10, 5) heading 90°: a cone 6 m ahead and 1.5 m to the right of the car is at map (11.5, 11).
  const World world(make_track({make_cone(11.5, 11.0, ConeRole::Left)}), test::bare_config(), 1);
  const CameraModel cam(plain_camera(), world, 1);
  const cv::Mat img = cam.render(Pose2{10.0, 5.0, std::numbers::pi / 2}.to_pose3());
  const cv::Rect box = blue_box(img);
  ASSERT_GT(box.area(), 0);
  // In the body frame the cone stands at x = 6, y = −1.5. Its base centre projects to (u_of(6, −1.5), v_of(6, 0)).
  EXPECT_NEAR(box.x + (box.width - 1) / 2.0, u_of(6.0, -1.5), 1.0);
  EXPECT_NEAR(box.y + box.height - 1, v_of(6.0 - kR0, 0.0), 1.0);
  EXPECT_NEAR(box.y, v_of(6.0 + kR1, kH), 1.0);
}

TEST(CameraModelGeometry, HorizonOfALevelGroundFollowsThePitch) {
  const World world(make_track({make_cone(30.0, 20.0)}), test::bare_config(), 1);
  CameraConfig cfg = plain_camera();
  cfg.pitch = 0.1;  // looking down: the horizon moves up by fy·tan(pitch)
  const CameraModel cam(cfg, world, 1);
  const cv::Mat img = cam.render(Pose3::Identity());
  const double horizon = kCy - kF * std::tan(0.1);
  for (int u : {20, 320, 620}) {
    const cv::Vec3b sky = img.at<cv::Vec3b>(static_cast<int>(horizon) - 4, u);
    const cv::Vec3b ground = img.at<cv::Vec3b>(static_cast<int>(horizon) + 5, u);
    EXPECT_GT(sky[0] - sky[2], 10) << "sky is bluish above the horizon at u=" << u;
    EXPECT_LT(std::abs(ground[0] - ground[2]), 8) << "asphalt is grey below the horizon at u=" << u;
    EXPECT_GT(sky[1], ground[1] + 40) << "sky is brighter than asphalt";
  }
}

TEST(CameraModelGeometry, KnockedConeLiesOnItsSide) {
  World world(make_track({make_cone(8.0, 0.0, ConeRole::Left)}), test::bare_config(), 1);
  const CameraModel cam(plain_camera(), world, 1);
  const cv::Rect standing = blue_box(cam.render(Pose3::Identity()));

  // A footprint touching the cone from its right: the cone falls with its tip pointing left (+y), across the view.
  const std::vector<Vec2> footprint{{7.8, -1.0}, {8.2, -1.0}, {8.2, -0.05}, {7.8, -0.05}};
  ASSERT_EQ(world.update_hits(footprint, 1.0), 1);
  ASSERT_NEAR(world.cones()[0].fall_yaw, std::numbers::pi / 2, 1e-9);
  const cv::Rect lying = blue_box(cam.render(Pose3::Identity()));
  ASSERT_GT(lying.area(), 0);

  // By hand: one generator on the ground, the axis dipping by the half-angle θ. The highest point is the top of the
  // base rim, 2·r0·cosθ above the ground; the base rim reaches r0·sinθ to the right of the base centre, the tip
  // disc h·cosθ + r1·sinθ to the left; the contact line is at x = 8 on the ground.
  const double theta = std::atan((kR0 - kR1) / kH);
  const double top = v_of(8.0, 2 * kR0 * std::cos(theta));
  const double bottom = v_of(8.0, 0.0);
  const double left = u_of(8.0, kH * std::cos(theta) + kR1 * std::sin(theta));
  const double right = u_of(8.0, -kR0 * std::sin(theta));
  EXPECT_NEAR(lying.y, top, 1.0);
  EXPECT_NEAR(lying.y + lying.height - 1, bottom, 1.0);
  EXPECT_NEAR(lying.x, left, 1.0);
  EXPECT_NEAR(lying.x + lying.width - 1, right, 1.0);
  EXPECT_GT(lying.width, lying.height);
  EXPECT_GT(standing.height, standing.width);
  EXPECT_GT(lying.y, standing.y + 4) << "a fallen cone is lower than a standing one";
}

TEST(CameraModelGeometry, VisibleConesGiveBoxesBasePixelsAndOcclusion) {
  // One cone ahead, one behind the car, one far off to the side outside the field of view.
  const World world(
      make_track({make_cone(8.0, 0.0, ConeRole::Left), make_cone(-5.0, 0.0, ConeRole::Left), make_cone(2.0, 10.0)}),
      test::bare_config(), 1);
  const CameraModel cam(plain_camera(), world, 1);
  const auto cones = cam.visible_cones(Pose3::Identity());
  ASSERT_EQ(cones.size(), 1u);
  const ProjectedCone& c = cones[0];
  EXPECT_EQ(c.index, 0);
  EXPECT_EQ(c.colour, ConeColour::Blue);
  EXPECT_FALSE(c.knocked);
  EXPECT_FALSE(c.truncated);
  EXPECT_DOUBLE_EQ(c.visible_fraction, 1.0);
  EXPECT_NEAR(c.distance, std::hypot(8.0, 1.0), 1e-9);
  EXPECT_NEAR(c.base_pixel.x, u_of(8.0, 0.0), 1e-6);
  EXPECT_NEAR(c.base_pixel.y, v_of(8.0, 0.0), 1e-6);
  const cv::Rect rendered = blue_box(cam.render(Pose3::Identity()));
  // The box covers the stripe too; the rendered blue pixels span the same columns and rows.
  EXPECT_NEAR(c.box.x, rendered.x, 1);
  EXPECT_NEAR(c.box.y, rendered.y, 1);
  EXPECT_NEAR(c.box.br().x, rendered.br().x, 1);
  EXPECT_NEAR(c.box.br().y, rendered.br().y, 1);
}

TEST(CameraModelGeometry, NearConeHidesTheConeBehindIt) {
  // A camera below the cone tops, two cones in line: the near one (2 m) covers almost all of the far one (4 m).
  const World world(make_track({make_cone(4.0, 0.0, ConeRole::Right), make_cone(2.0, 0.0, ConeRole::Left)}),
                    test::bare_config(), 1);
  CameraConfig cfg = plain_camera();
  cfg.z = 0.3;
  const CameraModel cam(cfg, world, 1);
  const auto cones = cam.visible_cones(Pose3::Identity());
  ASSERT_EQ(cones.size(), 2u);
  EXPECT_EQ(cones[0].index, 0) << "far to near";
  EXPECT_LT(cones[0].visible_fraction, 0.5);
  EXPECT_DOUBLE_EQ(cones[1].visible_fraction, 1.0);
}

// Distance from p to the segment a–b.
double to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double s = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + s * ab - p).norm();
}

// A viewpoint 6 m from distractor `index` with a clear line of sight (no cone or other object within 1.5 m of it).
std::optional<Pose2> clear_view_of(const World& world, int index) {
  const Vec2 target = world.distractors()[static_cast<std::size_t>(index)].position;
  for (int k = 0; k < 16; ++k) {
    const double a = k * std::numbers::pi / 8;
    const Vec2 eye = target + 6.0 * Vec2(std::cos(a), std::sin(a));
    bool clear = true;
    for (const auto& c : world.cones()) clear = clear && to_segment(c.base.head<2>(), eye, target) > 1.5;
    for (int j = 0; j < static_cast<int>(world.distractors().size()); ++j) {
      if (j == index) continue;
      const Distractor& d = world.distractors()[static_cast<std::size_t>(j)];
      const double dist =
          d.type == DistractorType::Fence
              ? std::min({to_segment(eye, d.position, d.fence_end()), to_segment(target, d.position, d.fence_end())})
              : to_segment(d.position, eye, target);
      clear = clear && dist > 1.5 + (d.type == DistractorType::Fence ? 0.0 : d.footprint_radius());
    }
    if (clear) return Pose2{eye.x(), eye.y(), a + std::numbers::pi};
  }
  return std::nullopt;
}

TEST(CameraModelGeometry, PostsAreGreyAndTyreStacksBlackWhereTheWorldPutsThem) {
  const World world(load_track("../shared/tracks/epfl_track_1.csv"), WorldConfig{}, 1);
  const CameraModel cam(plain_camera(), world, 1);
  int posts = 0, stacks = 0;
  for (int i = 0; i < static_cast<int>(world.distractors().size()); ++i) {
    const Distractor& d = world.distractors()[static_cast<std::size_t>(i)];
    if (d.type != DistractorType::Post && d.type != DistractorType::TyreStack) continue;
    const auto eye = clear_view_of(world, i);
    if (!eye) continue;
    const cv::Mat img = cam.render(eye->to_pose3());
    cv::Mat hsv;
    cv::cvtColor(img, hsv, cv::COLOR_BGR2HSV);
    // The object's axis projects onto the centre column; sample it between 10 cm above the ground and 10 cm below
    // the top (capped at 0.9 m, below the camera), on the front surface 6 m − radius away.
    const double near = 6.0 - d.radius;
    const int v0 = static_cast<int>(std::ceil(v_of(near, std::min(d.height - 0.1, 0.9))));
    const int v1 = static_cast<int>(std::floor(v_of(near, 0.1)));
    ASSERT_LT(v0, v1);
    for (int v = v0; v <= v1; ++v) {
      const cv::Vec3b p = hsv.at<cv::Vec3b>(v, 320);
      if (d.type == DistractorType::Post) {
        EXPECT_LT(p[1], 40) << "post pixels are grey, row " << v;
        EXPECT_GT(p[2], 90) << "post pixels are light, row " << v;
      } else {
        EXPECT_LT(p[2], 70) << "tyre pixels are dark, row " << v;
      }
    }
    (d.type == DistractorType::Post ? posts : stacks)++;
  }
  EXPECT_GT(posts, 0);
  EXPECT_GT(stacks, 0);
}

}  // namespace
}  // namespace fsd::sim

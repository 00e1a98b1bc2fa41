// Distractors stay off the track, at least the configured offset from both boundaries, and are placed by seed.
// The track surface here is built independently of the world's own boundary model: from the order of the cones
// in the track file (consecutive cones of one colour form the boundary polyline) and the quads between each
// boundary step and the nearest cones of the other boundary, filled with sample points. A boundary closes on
// itself when its last cone is not much farther from its first than the widest step between cones. Tracks whose
// files list cones out of order (epfl_autoX_Vaudoise_Sponso, epfl_ebs_test_fss) or as separate circles
// (skidpads) do not fit this model and are left out.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "drivers/sim/world/world.hpp"

namespace fsd::sim {
namespace {

constexpr double kMaxGap = 7.0;  // m between consecutive cones of a boundary

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double s = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

struct TrackModel {
  std::vector<std::pair<Vec2, Vec2>> boundary;  // polyline segments in file order
  std::vector<Vec2> surface;                    // sample points on the driving surface
};

TrackModel model_of(const Track& track) {
  TrackModel m;
  std::vector<Vec2> left, right;
  for (const auto& c : track.cones) {
    if (c.role == ConeRole::Left) left.push_back(c.position);
    if (c.role == ConeRole::Right) right.push_back(c.position);
  }
  auto nearest = [](const std::vector<Vec2>& v, const Vec2& p) {
    Vec2 best = v.front();
    for (const auto& q : v)
      if ((q - p).norm() < (best - p).norm()) best = q;
    return best;
  };
  for (const auto* side : {&left, &right}) {
    const auto& other = side == &left ? right : left;
    double widest = 0;
    for (std::size_t i = 0; i + 1 < side->size(); ++i) widest = std::max(widest, ((*side)[i + 1] - (*side)[i]).norm());
    for (std::size_t i = 0; i < side->size(); ++i) {
      const bool closing = i + 1 == side->size();
      const Vec2 a = (*side)[i], b = (*side)[(i + 1) % side->size()];
      if ((b - a).norm() > (closing ? std::min(kMaxGap, 1.6 * widest) : kMaxGap)) continue;
      m.boundary.emplace_back(a, b);
      // Quad a, b, across(b), across(a) sampled on an 11 × 11 bilinear grid.
      const Vec2 qa = nearest(other, a), qb = nearest(other, b);
      for (int u = 0; u <= 10; ++u)
        for (int v = 0; v <= 10; ++v) {
          const double s = u / 10.0, w = v / 10.0;
          m.surface.push_back((1 - w) * ((1 - s) * a + s * b) + w * ((1 - s) * qa + s * qb));
        }
    }
  }
  // Timing and orange cones stand on or beside the track: their places belong to it too.
  for (const auto& c : track.cones)
    if (c.role != ConeRole::Left && c.role != ConeRole::Right) m.surface.push_back(c.position);
  return m;
}

// Least distance between a distractor's footprint and the track (boundary lines and driving surface).
double clearance(const Distractor& d, const TrackModel& m) {
  std::vector<Vec2> points;
  double radius = d.footprint_radius();
  if (d.type == DistractorType::Fence) {
    for (int k = 0; k <= 100; ++k) points.push_back(d.position + (d.fence_end() - d.position) * (k / 100.0));
    radius = 0;
  } else {
    points.push_back(d.position);
  }
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : points) {
    for (const auto& [a, b] : m.boundary) best = std::min(best, segment_distance(p, a, b) - radius);
    for (const auto& s : m.surface) best = std::min(best, (s - p).norm() - radius);
  }
  return best;
}

Track shared_track(const std::string& name) { return load_track("../shared/tracks/" + name + ".csv"); }

TEST(WorldDistractors, NeverOnTheTrackAndAtLeastTheOffsetAway) {
  for (const char* name :
       {"epfl_track_1", "epfl_fsds_competition_2", "epfl_VSV_XS", "epfl_acceleration", "amz_fssim_thin"}) {
    const Track track = shared_track(name);
    const TrackModel model = model_of(track);
    WorldConfig cfg;
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      const World world(track, cfg, seed);
      int fences = 0, round = 0;
      for (const auto& d : world.distractors()) {
        const double min_offset = d.type == DistractorType::Fence ? cfg.fence_offset_min : cfg.distractor_min_offset;
        EXPECT_GT(clearance(d, model), min_offset - 1e-6)
            << name << " seed " << seed << " " << to_string(d.type) << " at " << d.position.transpose();
        (d.type == DistractorType::Fence ? fences : round)++;
      }
      EXPECT_EQ(round, cfg.tyres + cfg.posts + cfg.tyre_stacks) << name << " seed " << seed;
      EXPECT_GE(fences, 1) << name << " seed " << seed;
    }
  }
}

// Every shared track, including those the model above does not fit: nothing within the offset of any cone.
TEST(WorldDistractors, EverySharedTrackKeepsThemAwayFromTheCones) {
  const WorldConfig cfg;
  for (const auto& entry : std::filesystem::directory_iterator("../shared/tracks")) {
    const Track track = load_track(entry.path());
    const World world(track, cfg, 1);
    EXPECT_GE(world.distractors().size(), static_cast<std::size_t>(cfg.tyres + cfg.posts)) << track.name;
    for (const auto& d : world.distractors()) {
      const double min_offset = d.type == DistractorType::Fence ? cfg.fence_offset_min : cfg.distractor_min_offset;
      for (const auto& c : track.cones) {
        const double gap = d.type == DistractorType::Fence ? segment_distance(c.position, d.position, d.fence_end())
                                                           : (c.position - d.position).norm() - d.footprint_radius();
        ASSERT_GT(gap, min_offset) << track.name << " " << to_string(d.type) << " at " << d.position.transpose();
      }
    }
  }
}

TEST(WorldDistractors, SizesAreThoseOfRealObjects) {
  const World world(shared_track("epfl_track_1"), WorldConfig{}, 5);
  for (const auto& d : world.distractors()) {
    switch (d.type) {
      case DistractorType::Tyre:
        EXPECT_NEAR(d.radius, 0.3, 0.03);
        EXPECT_NEAR(d.width, 0.2, 0.04);
        EXPECT_NEAR(d.height, d.standing ? 2 * d.radius : d.width, 1e-12);
        break;
      case DistractorType::TyreStack:
        EXPECT_GE(d.tyre_count, 2);
        EXPECT_LE(d.tyre_count, 4);
        EXPECT_NEAR(d.height, d.tyre_count * d.width, 1e-12);
        break;
      case DistractorType::Post:
        EXPECT_NEAR(d.radius, 0.05, 0.011);
        EXPECT_NEAR(d.height, 1.2, 0.21);
        break;
      case DistractorType::Fence:
        EXPECT_DOUBLE_EQ(d.height, 1.5);
        EXPECT_LE(d.length, 15.0);
        break;
    }
  }
}

TEST(WorldDistractors, DeterministicPerSeedDifferentAcrossSeeds) {
  const Track track = shared_track("epfl_track_1");
  const World a(track, WorldConfig{}, 7), b(track, WorldConfig{}, 7), c(track, WorldConfig{}, 8);
  ASSERT_EQ(a.distractors().size(), b.distractors().size());
  for (std::size_t i = 0; i < a.distractors().size(); ++i) {
    EXPECT_EQ(a.distractors()[i].type, b.distractors()[i].type);
    EXPECT_EQ(a.distractors()[i].position, b.distractors()[i].position);
    EXPECT_EQ(a.distractors()[i].height, b.distractors()[i].height);
  }
  int moved = 0;
  for (std::size_t i = 0; i < std::min(a.distractors().size(), c.distractors().size()); ++i)
    moved += (a.distractors()[i].position - c.distractors()[i].position).norm() > 0.5;
  EXPECT_GT(moved, static_cast<int>(a.distractors().size()) / 2);
}

TEST(WorldDistractors, NoneWhenDisabled) {
  WorldConfig cfg;
  cfg.distractors = false;
  EXPECT_TRUE(World(shared_track("epfl_track_1"), cfg, 1).distractors().empty());
}

TEST(WorldDistractors, RaysHitPostsAndTyresWithTheirSurface) {
  const World world(shared_track("epfl_track_1"), WorldConfig{}, 3);
  int checked = 0;
  for (const auto& d : world.distractors()) {
    if (d.type != DistractorType::Post && !(d.type == DistractorType::TyreStack)) continue;
    // Horizontal ray at half height towards the axis from 0.4 m outside the surface: hits after 0.4 m.
    const Vec2 from = d.position + Vec2(d.radius + 0.4, 0.0);
    const Vec3 o(from.x(), from.y(), d.height / 2);
    const auto hit = world.raycast(o, -Vec3::UnitX(), 10.0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 0.4, 1e-9);
    EXPECT_EQ(hit->surface, d.type == DistractorType::Post ? Surface::Post : Surface::Tyre);
    ++checked;
  }
  EXPECT_EQ(checked, WorldConfig{}.posts + WorldConfig{}.tyre_stacks);
}

TEST(WorldGround, GrassBeyondTheEdgeAsphaltOnTheTrack) {
  const Track track = shared_track("epfl_track_1");
  const World world(track, WorldConfig{}, 1);
  const TrackModel model = model_of(track);
  // Every driving-surface sample is asphalt.
  for (const auto& s : model.surface) ASSERT_EQ(world.ground_surface(s.x(), s.y()), Surface::Ground) << s.transpose();
  // Points more than grass_offset + 1 m (the edge wanders by < 1 m) from every cone and surface sample: grass.
  int grass = 0;
  for (double x = -60; x <= 60; x += 2.5)
    for (double y = -60; y <= 80; y += 2.5) {
      const Vec2 p(x, y);
      bool far = true;
      for (const auto& s : model.surface) far = far && (s - p).norm() > WorldConfig{}.grass_offset + 1.0;
      if (!far) continue;
      EXPECT_EQ(world.ground_surface(x, y), Surface::Grass) << p.transpose();
      ++grass;
    }
  EXPECT_GT(grass, 100);
  WorldConfig no_grass;
  no_grass.grass_edges = false;
  EXPECT_EQ(World(track, no_grass, 1).ground_surface(500, 500), Surface::Ground);
}

TEST(WorldGround, TextureVariesAroundTheMaterialReflectivity) {
  WorldConfig cfg;
  cfg.grass_edges = false;
  const World world(shared_track("epfl_track_1"), cfg, 1);
  double lo = 1e9, hi = -1e9;
  for (double x = 0; x < 20; x += 0.13) {
    const double r = world.ground_reflectivity(x, 0.7 * x);
    lo = std::min(lo, r);
    hi = std::max(hi, r);
    EXPECT_LE(std::abs(r - cfg.ground_reflectivity), cfg.ground_texture + 1e-9);
  }
  EXPECT_GT(hi - lo, cfg.ground_texture / 2);
}

}  // namespace
}  // namespace fsd::sim

// The grazing-beam test of GroundSplitter (ground_split.hpp) against the rule written out here by brute force, on
// the virtual car's VLP-16 scans (cones, distractors, fences; raw, in the sensor frame) and on cuts of them: whole
// revolutions, a scan cut short (the cut's gap under and over half a turn), more than a revolution, and two
// returns per firing. The obstacle points the test adds must be exactly the rule's. (Written to hold a one-pass
// sliding-window version of the test to the walk; that version was no faster in the detector and is not kept.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <tuple>
#include <vector>

#include "perception/ground_split.hpp"
#include "tests/perception/sim_lidar_drive.hpp"

namespace fsd {
namespace {

using Key = std::tuple<double, int, float, float>;  // firing time, laser, azimuth, range: one return
Key key_of(const Point& p) { return {p.t, p.ring, p.azimuth, p.distance}; }

// The rule: a band point (ground without the test) at least min_range from the sensor whose laser, on each side
// within `window` of azimuth (walking from it in firing order, round the ring, to the first firing outside), has
// at least ceil(min_neighbours / 2) band returns of which one is farther than its range / (1 - drop).
std::multiset<Key> rule(const std::vector<Point>& band, double min_range, const GrazingBeams& g) {
  std::multiset<Key> marked;
  std::vector<std::vector<Point>> rings(256);
  for (const auto& p : band) rings[p.ring & 0xFF].push_back(p);
  const auto angle = [](float a, float b) {
    const double d = std::abs(a - b);
    return std::min(d, 2 * std::numbers::pi - d);
  };
  const std::size_t need = static_cast<std::size_t>(g.min_neighbours + 1) / 2;
  for (const auto& ring : rings) {
    const std::size_t n = ring.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Point& p = ring[k];
      if (std::hypot(p.x, p.y) < min_range) continue;
      const float beyond = p.distance / static_cast<float>(1.0 - g.drop);
      bool both = true;
      for (const int dir : {-1, 1}) {
        std::size_t count = 0;
        bool far = false;
        for (std::size_t step = 1; step < n; ++step) {
          const Point& q = ring[(k + n + dir * static_cast<std::ptrdiff_t>(step) % static_cast<std::ptrdiff_t>(n)) % n];
          if (angle(q.azimuth, p.azimuth) > g.window) break;
          ++count;
          far = far || q.distance > beyond;
        }
        both = both && far && count >= need;
      }
      if (both) marked.insert(key_of(p));
    }
  }
  return marked;
}

// What the grazing test adds to the obstacles of `points`, and what the rule says it should.
void expect_rule(const std::vector<Point>& points, double sensor_height, const char* what) {
  GroundPlane plane;
  plane.h = -sensor_height, plane.valid = true;
  const GroundSurface ground(plane);
  constexpr double kTau = 0.05, kMaxHeight = 1.0;
  GroundSplitter splitter;
  std::vector<Point> band, without, with;
  splitter.split(points, ground, kTau, kMaxHeight, &band, without);
  const GrazingBeams g;
  const auto counts = splitter.split(points, ground, kTau, kMaxHeight, nullptr, with, &g);
  std::multiset<Key> added;
  for (const auto& p : with) added.insert(key_of(p));
  for (const auto& p : without) added.erase(added.find(key_of(p)));
  const std::multiset<Key> expected = rule(band, sensor_height * g.band / kTau, g);
  EXPECT_EQ(added.size(), counts.grazing) << what;
  EXPECT_EQ(added, expected) << what << ": " << added.size() << " marked, the rule " << expected.size();
}

TEST(GroundSplit, GrazingBeamsMarkExactlyWhatTheRuleSaysOnEveryCutOfARealisticScan) {
  test::SimLidarSetup setup;
  setup.world.fence_segments = 20;  // walls behind the track: long far returns beside the cones' short ones
  test::SimLidarDrive drive(setup);
  const double h = setup.lidar.z;
  int marked_somewhere = 0;
  for (int f = 0; f < 6; ++f) {
    const Scan scan = drive.next();
    expect_rule(scan.points, h, "a revolution");
    std::vector<Point> cut_long, cut_short, more, dual;
    for (const auto& p : scan.points) {
      if (p.azimuth >= 0.5f && p.azimuth <= 5.0f) cut_long.push_back(p);   // the cut's gap is under half a turn
      if (p.azimuth >= 0.5f && p.azimuth <= 2.0f) cut_short.push_back(p);  // over half a turn
      dual.push_back(p);
      Point second = p;  // a second, farther return of the same firing
      second.distance *= 1.06f, second.x *= 1.06f, second.y *= 1.06f, second.z *= 1.06f;
      dual.push_back(second);
    }
    more = scan.points;  // a revolution and a tenth: the ring's azimuths go round more than once
    for (std::size_t i = 0; i < scan.points.size() / 10; ++i) {
      Point again = scan.points[i];
      again.t += 0.1;
      more.push_back(again);
    }
    expect_rule(cut_long, h, "cut, gap under half a turn");
    expect_rule(cut_short, h, "cut, gap over half a turn");
    expect_rule(more, h, "more than a revolution");
    expect_rule(dual, h, "two returns per firing");
    GroundPlane plane;
    plane.h = -h, plane.valid = true;
    GroundSplitter splitter;
    std::vector<Point> obstacles;
    const GrazingBeams g;
    marked_somewhere += splitter.split(scan.points, GroundSurface(plane), 0.05, 1.0, nullptr, obstacles, &g).grazing > 0;
  }
  EXPECT_GT(marked_somewhere, 0) << "the scans must hold something the test marks, or the comparison proves little";
}

}  // namespace
}  // namespace fsd

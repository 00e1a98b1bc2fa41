// A hairpin into a hairpin the other way (an S), planned as the car drives through the first: the generated
// autocross layout of seed 54 (drivers/sim's generator, pure and seeded), whose road between the two keeps turning
// the first one's way and whose second hairpin's entry lies within the first's outer ring. The car's poses are the
// simulator's truth of a run through it, one per plan (10 Hz). Truth: the layout's cones; every plan's line must
// carry the car's body clear of them. Held through the first hairpin, the plan once rejoined the midline beyond the
// second's entry, and its exit straight ran through the second's inner cones (16 cones hit).
#include <gtest/gtest.h>

#include <cmath>

#include "control/midline_planner.hpp"
#include "drivers/sim/track_generator.hpp"

namespace fsd {
namespace {

// Least gap between the body (0.5 m behind to 2.4 m ahead of the rear axle, 0.7 m to each side), carried along the
// first `length` m of `path`, and the base of any cone (0.12 m radius).
double body_clearance(const Path& path, const std::vector<Cone>& cones, double length) {
  double gap = 1e9;
  for (const auto& q : path.points) {
    if (q.s > length) break;
    const Vec2 f(std::cos(q.yaw), std::sin(q.yaw)), l(-f.y(), f.x());
    for (const auto& c : cones) {
      const Vec2 d = c.position.head<2>() - q.p;
      const double x = d.dot(f), y = d.dot(l);
      const double dx = std::max({-0.5 - x, 0.0, x - 2.4}), dy = std::max({-0.7 - y, 0.0, y - 0.7});
      gap = std::min(gap, std::hypot(dx, dy) - 0.12);
    }
  }
  return gap;
}

TEST(HeldTurn, AHairpinIntoAHairpinTheOtherWayKeepsEveryPlanClearOfTheCones) {
  sim::TrackGeneratorOptions options;
  options.kind = sim::LayoutKind::Autocross;
  options.seed = 54;
  const Track track = sim::generate_track(options);
  const std::vector<Cone> cones = cones_of(track);
  // The rear axle's pose every 0.1 s from 32.5 s, as the car came down to the first hairpin and round it.
  const std::vector<Pose2> poses = {
      {94.22, 45.43, -0.673}, {94.74, 45.01, -0.746}, {95.20, 44.57, -0.801}, {95.63, 44.12, -0.815},
      {96.04, 43.68, -0.853}, {96.41, 43.24, -0.923}, {96.74, 42.79, -0.976}, {97.05, 42.33, -0.987},
      {97.35, 41.88, -0.988}, {97.65, 41.43, -0.991}, {97.94, 40.98, -0.995}, {98.22, 40.54, -0.991},
      {98.50, 40.11, -1.008}, {98.77, 39.68, -1.050}, {99.01, 39.25, -1.119}, {99.21, 38.81, -1.213},
      {99.36, 38.37, -1.329}, {99.45, 37.92, -1.468}, {99.48, 37.47, -1.614}, {99.44, 37.02, -1.764},
      {99.33, 36.59, -1.917}, {99.16, 36.18, -2.071}, {98.93, 35.80, -2.226}, {98.65, 35.46, -2.380},
      {98.32, 35.17, -2.534}, {97.94, 34.94, -2.688}, {97.52, 34.75, -2.826}, {97.07, 34.62, -2.941}};
  const MidlinePlanner planner({}, track.convention, SpeedLimits{});
  std::optional<TightTurn> held;
  int turns_left = 0, turns_right = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    VehicleState state;
    state.stamp = 32.5 + 0.1 * static_cast<double>(i);
    state.pose = poses[i];
    state.vx = 4.5;
    const PlanResult r = planner.plan(cones, state, held ? &*held : nullptr);
    ASSERT_TRUE(r.ok) << "plan " << i << ": " << r.reason;
    held = r.tight_turn;
    if (held) ++(held->direction > 0 ? turns_left : turns_right);
    // The next 15 m: through the rest of the first hairpin and into the second.
    EXPECT_GT(body_clearance(r.path, cones, 15.0), 0.0) << "plan " << i << " from " << poses[i].x << ", " << poses[i].y;
  }
  EXPECT_GT(turns_right, 10);  // the first hairpin (to the right) was held through
}

}  // namespace
}  // namespace fsd

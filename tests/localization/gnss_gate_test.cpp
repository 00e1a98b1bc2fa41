// The GNSS gate against values worked out by hand: σ by fix quality, the NIS of a known innovation, the soft and
// the hard gate, the jump test against the dead-reckoned motion, recovery after a run of rejections.
#include <gtest/gtest.h>

#include "localization/fusion/gnss_gate.hpp"

namespace fsd::fusion {
namespace {

GnssFix fix(Stamp t, double x, double y, int quality = 4) {
  GnssFix f;
  f.t = t;
  f.position = Vec2(x, y);
  f.fix_quality = quality;
  return f;
}

TEST(GnssGate, SigmaFollowsTheFixQualityAndTheCorrectionsAge) {
  GnssGate g;
  EXPECT_DOUBLE_EQ(g.nominal_sigma(fix(0, 0, 0, 4)), 0.03);
  EXPECT_DOUBLE_EQ(g.nominal_sigma(fix(0, 0, 0, 5)), 0.2);
  EXPECT_DOUBLE_EQ(g.nominal_sigma(fix(0, 0, 0, 2)), 0.5);
  EXPECT_DOUBLE_EQ(g.nominal_sigma(fix(0, 0, 0, 1)), 1.0);
  GnssFix old = fix(0, 0, 0, 4);
  old.age_s = 30.0;
  EXPECT_DOUBLE_EQ(g.nominal_sigma(old), 1.0) << "RTK with 30 s old corrections is single-point";
  old.sigma = 0.07;
  EXPECT_DOUBLE_EQ(g.nominal_sigma(old), 0.07) << "the fix's own σ wins";
}

TEST(GnssGate, NisAndTheTwoGates) {
  GnssGateConfig cfg;
  cfg.sigma_rtk_fixed = 0.3;  // S = (0.4² + 0.3²) I = 0.25 I
  GnssGate g(cfg);
  const Eigen::Matrix2d P = Eigen::Matrix2d::Identity() * 0.16;
  // 0.5 m off: NIS = 0.25 / 0.25 = 1 → accepted.
  auto c = g.check(fix(0.0, 0.5, 0.0), 0.0, Vec2::Zero(), P, Vec2::Zero());
  EXPECT_EQ(c.verdict, GnssVerdict::Accepted);
  EXPECT_NEAR(c.nis, 1.0, 1e-12);
  // 1.5 m off (the motion says 1 m east, the fix moved 2 m: 1 m, under the jump limit): NIS = 2.25/0.25 = 9
  // → down-weighted, σ × √(9 / 5.99).
  c = g.check(fix(0.1, 2.5, 0.0), 0.1, Vec2(1.0, 0.0), P, Vec2(1.0, 0.0));
  EXPECT_EQ(c.verdict, GnssVerdict::DownWeighted);
  EXPECT_NEAR(c.nis, 9.0, 1e-12);
  EXPECT_NEAR(c.sigma, 0.3 * std::sqrt(9.0 / 5.99), 1e-12);
  // 2 m off with a consistent step: NIS 16 > 13.8 → rejected by the innovation gate.
  c = g.check(fix(0.2, 5.5, 0.0), 0.2, Vec2(3.5, 0.0), P, Vec2(3.0, 0.0));
  EXPECT_EQ(c.verdict, GnssVerdict::RejectedInnovation);
  EXPECT_NEAR(c.nis, 16.0, 1e-12);
}

TEST(GnssGate, AJumpIsAStepTheMotionDoesNotExplain) {
  GnssGate g;
  const Eigen::Matrix2d P = Eigen::Matrix2d::Identity() * 100.0;  // wide: only the jump test can reject
  EXPECT_EQ(g.check(fix(0.0, 0, 0), 0.0, Vec2::Zero(), P, Vec2::Zero()).verdict, GnssVerdict::Accepted);
  // Allowed: 1.5 m + 0.2 × motion + 3.5 √2 × 0.03 m (RTK fixed) = 1.648 m + 0.2 × motion.
  // Moved 10 m, the car drove 10 m: fine. Then 10 m + 3.6 m, allowed 3.648 m: fine.
  EXPECT_EQ(g.check(fix(1.0, 10, 0), 1.0, Vec2(10, 0), P, Vec2(10, 0)).verdict, GnssVerdict::Accepted);
  EXPECT_EQ(g.check(fix(2.0, 23.6, 0), 2.0, Vec2(20, 0), P, Vec2(10, 0)).verdict, GnssVerdict::Accepted);
  // 3.7 m more than the motion: a jump.
  EXPECT_EQ(g.check(fix(3.0, 37.3, 0), 3.0, Vec2(33.6, 0), P, Vec2(10, 0)).verdict, GnssVerdict::RejectedJump);
  // Standing still, a 1.7 m step sideways is a jump too; 1.6 m is not.
  EXPECT_EQ(g.check(fix(4.0, 37.3, 1.7), 4.0, Vec2(37.3, 0), P, Vec2::Zero()).verdict, GnssVerdict::RejectedJump);
  EXPECT_EQ(g.check(fix(5.0, 37.3, 0.1), 5.0, Vec2(37.3, 1.7), P, Vec2::Zero()).verdict, GnssVerdict::Accepted);
}

TEST(GnssGate, RecoversWhenTheFixesAgreeWithEachOtherButNotWithTheState) {
  GnssGate g;
  const Eigen::Matrix2d P = Eigen::Matrix2d::Identity() * 0.01;
  // The state is 5 m off; the fixes, standing still, agree with each other.
  int rejected = 0;
  GnssVerdict last = GnssVerdict::None;
  for (int i = 0; i <= 40; ++i) {
    const auto c = g.check(fix(0.1 * i, 5, 0), 0.1 * i, Vec2::Zero(), P, Vec2::Zero());
    if (c.verdict == GnssVerdict::RejectedInnovation) ++rejected;
    last = c.verdict;
  }
  EXPECT_EQ(rejected, 30) << "rejected for the 3 s of recover_after_s";
  EXPECT_EQ(last, GnssVerdict::DownWeighted);
}

TEST(GnssGate, InvalidAndStaleFixes) {
  GnssGate g;
  const Eigen::Matrix2d P = Eigen::Matrix2d::Identity();
  EXPECT_EQ(g.check(fix(0, 0, 0, 0), 0, Vec2::Zero(), P, Vec2::Zero()).verdict, GnssVerdict::RejectedQuality);
  EXPECT_EQ(g.check(fix(0, NAN, 0, 4), 0, Vec2::Zero(), P, Vec2::Zero()).verdict, GnssVerdict::RejectedQuality);
  EXPECT_EQ(g.check(fix(9.0, 0, 0, 4), 10.0, Vec2::Zero(), P, Vec2::Zero()).verdict, GnssVerdict::RejectedStale);
  GnssGateConfig rtk_only;
  rtk_only.min_fix_quality = 4;
  GnssGate r(rtk_only);
  EXPECT_EQ(r.check(fix(0, 0, 0, 2), 0, Vec2::Zero(), P, Vec2::Zero()).verdict, GnssVerdict::RejectedQuality);
}

}  // namespace
}  // namespace fsd::fusion

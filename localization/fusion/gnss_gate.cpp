#include "localization/fusion/gnss_gate.hpp"

#include <cmath>

namespace fsd::fusion {

double GnssGate::nominal_sigma(const GnssFix& fix) const {
  if (fix.sigma > 0 && std::isfinite(fix.sigma)) return fix.sigma;
  const bool fresh = fix.age_s <= cfg_.max_age_s;
  switch (fix.fix_quality) {
    case 4:
      return fresh ? cfg_.sigma_rtk_fixed : cfg_.sigma_single;
    case 5:
      return fresh ? cfg_.sigma_rtk_float : cfg_.sigma_single;
    case 2:
      return fresh ? cfg_.sigma_dgps : cfg_.sigma_single;
    default:
      return cfg_.sigma_single;
  }
}

void GnssGate::reset() {
  previous_.reset();
  rejected_since_ = -1;
  recovering_ = false;
}

GnssCheck GnssGate::check(const GnssFix& fix, Stamp now, const Vec2& predicted, const Eigen::Matrix2d& cov,
                          const Vec2& motion) {
  GnssCheck c;
  if (fix.fix_quality <= 0 || fix.fix_quality < cfg_.min_fix_quality || !fix.position.allFinite()) {
    c.verdict = GnssVerdict::RejectedQuality;
    return c;
  }
  if (fix.t < now - cfg_.max_delay_s) {
    c.verdict = GnssVerdict::RejectedStale;
    return c;
  }
  c.sigma = nominal_sigma(fix);
  // Corrections too old: the receiver still says RTK, but the position is no better than single-point.
  const bool old_corrections = fix.fix_quality >= 2 && fix.age_s > cfg_.max_age_s && fix.sigma <= 0;

  bool jump = false;
  if (previous_) {
    // Two fixes' noise (√2 σ, 3.5 σ of it) is no jump: white single-point noise would otherwise trip it.
    const double allowed = cfg_.jump_min_m + cfg_.jump_fraction * motion.norm() + 3.5 * std::sqrt(2.0) * c.sigma;
    jump = ((fix.position - *previous_) - motion).norm() > allowed;
  }
  previous_ = fix.position;

  const Vec2 nu = fix.position - predicted;
  const Eigen::Matrix2d S = cov + Eigen::Matrix2d::Identity() * c.sigma * c.sigma;
  c.nis = nu.dot(S.ldlt().solve(nu));
  if (!std::isfinite(c.nis)) c.nis = 1e12;

  // Once recovering, fixes are taken (down-weighted) until they fit the state again.
  if (rejected_since_ >= 0 && fix.t - rejected_since_ >= cfg_.recover_after_s) recovering_ = true;
  if (c.nis <= cfg_.reject_gate_chi2) recovering_ = false;
  const bool recovering = recovering_;
  if (jump || (c.nis > cfg_.reject_gate_chi2 && !recovering)) {
    c.verdict = jump ? GnssVerdict::RejectedJump : GnssVerdict::RejectedInnovation;
    if (rejected_since_ < 0) rejected_since_ = fix.t;
    return c;
  }
  rejected_since_ = -1;
  if (c.nis > cfg_.soft_gate_chi2) {
    c.sigma *= std::sqrt(c.nis / cfg_.soft_gate_chi2);
    c.verdict = GnssVerdict::DownWeighted;
  } else {
    c.verdict = old_corrections ? GnssVerdict::DownWeighted : GnssVerdict::Accepted;
  }
  return c;
}

}  // namespace fsd::fusion

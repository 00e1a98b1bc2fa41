#pragma once
// The GNSS quality gate shared by both filters: decides per fix whether it is used, with which σ, and why not.
//   - fix quality below the minimum: rejected; differential corrections too old: counted as single-point;
//   - stale: older than the filter's time by more than allowed;
//   - jump: the fix moved from the previous one by more than the filter's own dead-reckoned motion over the same
//     interval allows: jump_min_m + jump_fraction × motion + 3.5 √2 σ (multipath steps, a receiver re-converging);
//   - innovation: normalised innovation squared against the predicted position's covariance; between the soft
//     and the hard gate the σ is inflated (down-weighted), beyond the hard gate rejected;
//   - recovery: when fixes have been rejected for a while and the latest is no jump, the filter (not the
//     receiver) is taken to be wrong and the fix is accepted, down-weighted, so the state cannot lock out GNSS.
#include <optional>

#include "localization/fusion/fusion_config.hpp"
#include "localization/fusion/measurements.hpp"

namespace fsd::fusion {

struct GnssCheck {
  GnssVerdict verdict = GnssVerdict::None;
  double sigma = 0;  // m per axis to update with (when accepted or down-weighted)
  double nis = 0;
  bool used() const { return verdict == GnssVerdict::Accepted || verdict == GnssVerdict::DownWeighted; }
};

class GnssGate {
 public:
  explicit GnssGate(const GnssGateConfig& cfg = {}) : cfg_(cfg) {}

  // σ per axis of a fix by its quality (or its own σ when it carries one), before any gating.
  double nominal_sigma(const GnssFix& fix) const;

  // `now`: the filter's time; `predicted`, `cov`: the filter's position and its covariance at the fix;
  // `motion`: the filter's dead-reckoned displacement (map frame) since the previous fix that passed the gate's
  // quality checks. The filter resets its displacement after each call.
  GnssCheck check(const GnssFix& fix, Stamp now, const Vec2& predicted, const Eigen::Matrix2d& cov, const Vec2& motion);
  void reset();

 private:
  GnssGateConfig cfg_;
  std::optional<Vec2> previous_;  // the previous fix's position
  Stamp rejected_since_ = -1;     // first of the current run of rejected fixes (< 0: none)
  bool recovering_ = false;
};

}  // namespace fsd::fusion

#pragma once
// run.localization_source = fused: the Stack's GNSS-INS samples and the VCU's wheel speeds through one fusion
// filter (localization/fusion, localization.fusion.filter). A GNSS sample gives a position fix (rear axle, lever
// arm removed by the driver) with its quality, age and dual-antenna heading, and its yaw rate (ROT) stands for
// the gyro; the mean of the rear wheels is the rear axle's forward speed. Measurements go in by stamp.
#include <memory>
#include <optional>
#include <vector>

#include "common/config.hpp"
#include "common/types.hpp"
#include "localization/fusion/fusion_filter.hpp"

namespace fsd {

class FusedLocalization {
 public:
  explicit FusedLocalization(const Config& cfg);
  // One cycle's input: the GNSS samples since the last cycle and the newest VCU status (if any).
  void add(const std::vector<GnssSample>& gnss, const std::optional<VcuStatus>& vcu);
  // The vehicle state once the filter has a position and a heading.
  std::optional<VehicleState> state(double steering_measured) const;
  fusion::LocalizationState estimate() const { return filter_->state(); }

 private:
  std::unique_ptr<fusion::FusionFilter> filter_;
  Stamp last_vcu_ = -1e300;
};

}  // namespace fsd

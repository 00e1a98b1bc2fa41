#pragma once
// Stage 1, region of interest (paper §III.A.1): a box around the car in the ground plane, the car's own body cut
// out. The height limit of the region ("up to 1 m above the ground") needs the ground plane and is applied when
// the ground stage splits the cloud (GroundSplit); its bound lives here with the box.
#include <cstdint>
#include <vector>

#include "common/car.hpp"
#include "common/config.hpp"
#include "common/types.hpp"

namespace fsd {

struct RoiConfig {
  // The box in the detector's frame (vehicle frame: x forward, y left). The paper's 20 m × 20 m is read as 20 m of
  // reach on every side: the scorecard counts cones within 20 m all around the car (DESIGN.md §8).
  double x_min = -20.0, x_max = 20.0;
  double y_min = -20.0, y_max = 20.0;
  double max_height = 1.0;  // m above the ground plane
  // The car's own body with a margin, cut out: by default the car's description (0.5 m behind the rear axle to
  // 2.4 m ahead, 1.4 m wide) grown by body_margin; cut_out() sets it from a description.
  double body_margin = 0.1;
  double body_x_min = -0.6, body_x_max = 2.5;
  double body_y_min = -0.8, body_y_max = 0.8;
  void cut_out(const CarDescription& car);
};
const ConfigSection<RoiConfig>& roi_section();  // "perception.lidar.roi"

class RoiFilter {
 public:
  explicit RoiFilter(const RoiConfig& cfg = {}) : cfg_(cfg) {}

  bool in_box(float x, float y, double margin = 0.0) const {
    return x >= cfg_.x_min - margin && x <= cfg_.x_max + margin && y >= cfg_.y_min - margin && y <= cfg_.y_max + margin;
  }
  bool in_body(float x, float y) const {
    return x >= cfg_.body_x_min && x <= cfg_.body_x_max && y >= cfg_.body_y_min && y <= cfg_.body_y_max;
  }
  const RoiConfig& config() const { return cfg_; }

 private:
  RoiConfig cfg_;
};

}  // namespace fsd

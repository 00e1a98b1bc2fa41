#include "perception/roi_filter.hpp"

namespace fsd {

const ConfigSection<RoiConfig>& roi_section() {
  static const auto s =
      ConfigSection<RoiConfig>("perception.lidar.roi")
          .number("x_min", &RoiConfig::x_min, -200.0, 0.0, "m", "Region of interest: rear edge (vehicle frame).")
          .number("x_max", &RoiConfig::x_max, 0.0, 200.0, "m", "Region of interest: front edge.")
          .number("y_min", &RoiConfig::y_min, -200.0, 0.0, "m", "Region of interest: right edge.")
          .number("y_max", &RoiConfig::y_max, 0.0, 200.0, "m", "Region of interest: left edge.")
          .number("max_height", &RoiConfig::max_height, 0.2, 5.0, "m",
                  "Region of interest: points higher than this above the ground plane are dropped.")
          .number("body_margin", &RoiConfig::body_margin, 0.0, 2.0, "m",
                  "The car's own body (car.body_length, car.rear_overhang, car.body_width) grown by this is cut out.");
  return s;
}

void RoiConfig::cut_out(const CarDescription& car) {
  body_x_min = -car.rear_overhang - body_margin;
  body_x_max = car.nose() + body_margin;
  body_y_max = car.body_width / 2 + body_margin;
  body_y_min = -body_y_max;
}

}  // namespace fsd

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
          .number("body_x_min", &RoiConfig::body_x_min, -10.0, 10.0, "m", "The car's own body (cut out): rear edge.")
          .number("body_x_max", &RoiConfig::body_x_max, -10.0, 10.0, "m", "The car's own body: front edge.")
          .number("body_y_min", &RoiConfig::body_y_min, -10.0, 10.0, "m", "The car's own body: right edge.")
          .number("body_y_max", &RoiConfig::body_y_max, -10.0, 10.0, "m", "The car's own body: left edge.");
  return s;
}

}  // namespace fsd

#include "perception/camera/occlusion.hpp"

#include <cmath>

namespace fsd {

double hidden_share(cv::Point2d base, double px_per_m, std::span<const ImageSilhouette> nearer) {
  if (!(px_per_m > 0) || nearer.empty()) return 0.0;
  constexpr double kHeight = kSmallConeHeight, kBaseHalf = kSmallConeHalfWidth, kTopHalf = kSmallConeTopHalfWidth;
  constexpr int kRows = 10, kCols = 10;
  int hidden = 0;
  for (int r = 0; r < kRows; ++r) {
    const double z = kHeight * (r + 0.5) / kRows;
    const double half = kBaseHalf + (kTopHalf - kBaseHalf) * z / kHeight;
    const double y = base.y - z * px_per_m;
    for (int c = 0; c < kCols; ++c) {
      const double x = base.x + half * px_per_m * (2.0 * (c + 0.5) / kCols - 1.0);
      for (const auto& o : nearer) {
        const double s = o.px_per_m;
        if (std::abs(x - o.base.x) <= o.half_width * s && y <= o.base.y && y >= o.base.y - o.height * s) {
          ++hidden;
          break;
        }
      }
    }
  }
  return static_cast<double>(hidden) / (kRows * kCols);
}

}  // namespace fsd

#pragma once
// How much of a cone the camera sees behind the candidates in front of it (DESIGN.md §5b, colour). Cones close
// together in depth line up in the image: a timing line's small cone 0.5 m behind a big orange one is four fifths
// hidden from 9 m, and its ROI's colour is the big cone's. The camera stage leaves the colour of a mostly hidden
// candidate unknown rather than naming it after what stands in front.
#include <span>

#include <opencv2/core/types.hpp>

namespace fsd {

// The rules' small cone: the body whose hidden share is measured, and the size of a candidate in front whose size
// the LiDAR did not measure.
inline constexpr double kSmallConeHalfWidth = 0.114, kSmallConeTopHalfWidth = 0.025, kSmallConeHeight = 0.325;  // m
// The big cone's half base width, and the LiDAR height from which a cluster is a big cone (cone_size_filter.hpp).
inline constexpr double kBigConeHalfWidth = 0.1425, kBigConeMinLidarHeight = 0.40;  // m

// A candidate standing in front, as the image shows it: a box of its measured (or a small cone's) size on its base.
struct ImageSilhouette {
  cv::Point2d base;       // pixel of the base point
  double px_per_m = 0;    // image scale there
  double half_width = 0;  // m
  double height = 0;      // m
};

// Share (0..1) of a small cone's body (0.228 m base, 0.325 m tall, standing on `base` at `px_per_m`) that lies
// behind any of `nearer`. Sampled on a grid over the body; 0 when px_per_m is not positive.
double hidden_share(cv::Point2d base, double px_per_m, std::span<const ImageSilhouette> nearer);

}  // namespace fsd

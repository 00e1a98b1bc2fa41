#pragma once
// The ground stage's output: each point of the cropped cloud is ground (within τ of the plane), an obstacle point
// (between τ and the region's height limit above it), below the ground (noise, reflections: dropped) or above the
// region of interest (dropped).
//
// Grazing beams: far from a low sensor a laser meets the ground at a shallow angle, and the band of ±τ around the
// plane is metres long along the beam: a cone standing in it is hit a few centimetres above the ground and would
// pass for ground (a VLP-16 0.35 m up sees the last 3 m before its lowest-but-one ring meets the ground that way).
// Such a return is still metres short of where its laser meets the ground beside it. Where the band is longer than
// `band` along the beam, a band point whose range is shorter by more than `drop` (a share) than the farthest band
// return of its laser within `window` of azimuth on each side is an obstacle point (both sides: a ring whose range
// merely trends along the azimuth is short of one side only). Needs the scan's laser (ring) and firing order,
// which the VLP-16 decoder gives; clouds without rings skip it.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/types.hpp"
#include "perception/ground_surface.hpp"

namespace fsd {

struct GroundSplitCounts {
  std::size_t ground = 0, obstacles = 0, below = 0, above = 0;
  std::size_t grazing = 0;  // obstacle points found by the grazing-beam test (counted in obstacles too)
};

struct GrazingBeams {
  Vec3 sensor = Vec3::Zero();  // sensor origin in the points' frame
  double band = 0.5;           // m along the beam; 0 = off
  double drop = 0.04;          // share of the neighbours' median range
  double window = 0.07;        // rad of azimuth on each side
  int min_neighbours = 6;      // band returns within the windows, half on each side
};

// Keeps its buffers between frames.
class GroundSplitter {
 public:
  // Appends the obstacle points to `obstacles` and, when `ground` is not null, the ground points to it; only points
  // for which `keep(point)` holds are output and counted (the others, e.g. a margin around the region of interest,
  // serve as the grazing test's neighbours). `points` in firing order per laser when `grazing` is given.
  template <class Keep>
  GroundSplitCounts split(const std::vector<Point>& points, const GroundSurface& ground, double threshold,
                          double max_height, std::vector<Point>* ground_out, std::vector<Point>& obstacles,
                          const GrazingBeams* grazing, Keep&& keep);
  GroundSplitCounts split(const std::vector<Point>& points, const GroundSurface& ground, double threshold,
                          double max_height, std::vector<Point>* ground_out, std::vector<Point>& obstacles,
                          const GrazingBeams* grazing = nullptr) {
    return split(points, ground, threshold, max_height, ground_out, obstacles, grazing,
                 [](const Point&) { return true; });
  }

 private:
  enum class Kind : std::uint8_t { Ground, Obstacle, Below, Above };
  void classify(const std::vector<Point>& points, const GroundSurface& ground, double threshold, double max_height);
  std::size_t mark_grazing(const std::vector<Point>& points, const GroundSurface& ground, double threshold,
                           const GrazingBeams& g);
  std::vector<float> height_;
  std::vector<Kind> kind_;
  std::vector<std::vector<std::uint32_t>> by_ring_;
};

template <class Keep>
GroundSplitCounts GroundSplitter::split(const std::vector<Point>& points, const GroundSurface& ground, double threshold,
                                        double max_height, std::vector<Point>* ground_out,
                                        std::vector<Point>& obstacles, const GrazingBeams* grazing, Keep&& keep) {
  GroundSplitCounts c;
  classify(points, ground, threshold, max_height);
  if (grazing) mark_grazing(points, ground, threshold, *grazing);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!keep(points[i])) continue;
    switch (kind_[i]) {
      case Kind::Below:
        ++c.below;
        break;
      case Kind::Above:
        ++c.above;
        break;
      case Kind::Ground:
        ++c.ground;
        if (ground_out) ground_out->push_back(points[i]);
        break;
      case Kind::Obstacle:
        ++c.obstacles;
        c.grazing += height_[i] < threshold;
        obstacles.push_back(points[i]);
        break;
    }
  }
  return c;
}

}  // namespace fsd

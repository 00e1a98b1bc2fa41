#pragma once
// The ground the stages measure heights from: the fitted plane, plus local height corrections on a coarse grid
// where the real ground bends away from one plane (a crowned road, a slope change, an airfield's undulations:
// centimetres over tens of metres, as much as a cone's foot). A cell is corrected only where its returns show a
// flat layer of ground (enough points near one height, spread over a metre or more, and as dense along that spread
// as a laser's ring of ground returns is); a cone, a tyre or a kerb's handful of points never moves the ground, nor
// does a row of cones one laser crosses at the same height where no laser reaches the ground (8–19 m from a 0.35 m
// mount): their returns are short runs metres apart. Cells without such a layer take their neighbours' mean
// correction, else none (the plane); heights between cell centres are interpolated bilinearly.
#include <vector>

#include "common/types.hpp"
#include "perception/ground_plane.hpp"

namespace fsd {

struct LocalGroundConfig {
  double cell = 4.0;        // m; 0 = the plane alone
  double band = 0.25;       // m around the plane searched for the local ground
  double flat = 0.05;       // m: half-width of the flat layer (the ground threshold τ)
  int min_points = 10;      // points in the layer
  double min_extent = 1.0;  // m: the layer's horizontal spread (a cone's ring of points is 0.2 m)
  // The layer's points at least this share of what one ring of ground over its spread returns at its range, one
  // return per `azimuth_step` (rad; 0: no density test).
  double min_fill = 0.5;
  double azimuth_step = 0.0;
  Vec2 sensor = Vec2::Zero();  // where the ranges are measured from (the points' frame)
};

class GroundSurface {
 public:
  GroundSurface() = default;
  GroundSurface(const GroundPlane& plane)
      : plane_(plane),
        k_(plane.inv_norm()) {}  // NOLINT: a plane is a surface
                                 // without corrections

  // Local corrections from `points` (the detector's frame) around the plane.
  void fit_local(const std::vector<Point>& points, const LocalGroundConfig& cfg);

  double offset_at(double x, double y) const;  // the correction above the plane, m
  double z_at(double x, double y) const { return plane_.z_at(x, y) + offset_at(x, y); }
  // Signed distance above the ground (the plane's normal direction; corrections are small and smooth).
  double height_of(double x, double y, double z) const { return (z - plane_.z_at(x, y) - offset_at(x, y)) * k_; }
  Vec3 normal() const { return plane_.normal(); }
  const GroundPlane& plane() const { return plane_; }
  std::size_t corrected_cells() const { return corrected_; }

 private:
  GroundPlane plane_;
  double k_ = 1.0;  // 1 / |(−a, −b, 1)|, for the distance along the normal
  double x0_ = 0, y0_ = 0, cell_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<float> offset_;  // per cell centre
  // Reused between fits.
  std::vector<std::uint32_t> start_, cell_of_;
  std::vector<float> residual_;
  std::size_t corrected_ = 0;
};

}  // namespace fsd

#pragma once
// Smoothing of planned and recorded paths: a Whittaker–Eilers smoother (penalised least squares on second
// differences) of points at uniform spacing. Minimising |p − q|² + λ·Σ|Δ²p|² trades fidelity against curvature
// directly (Δ²p ≈ κ·ds²), has no phase lag, handles closed loops, and is one sparse solve.
#include <vector>

#include "common/geometry.hpp"
#include "control/planning/path.hpp"

namespace fsd {

// λ whose smoother halves a ripple of the given wavelength (m) on points spaced ds apart.
double whittaker_lambda(double cutoff_wavelength, double ds);

// Smoothed copy of `points` (assumed roughly uniformly spaced). Fewer than 3 points come back unchanged.
std::vector<Vec2> whittaker_smooth(const std::vector<Vec2>& points, bool closed, double lambda);

// The same smoother with every point kept within `radius` of where it was (a corridor round a centre line: the
// smoothest line that never strays further than that from it).
std::vector<Vec2> whittaker_smooth_within(const std::vector<Vec2>& points, bool closed, double lambda, double radius);

// Resamples `raw` at ds, smooths with the cutoff wavelength (each point within `radius` of its resampled place
// when radius > 0) and recomputes s, yaw and curvature. Speeds are not kept (the speed profile runs after).
Path smooth_path(const Path& raw, double ds, double cutoff_wavelength, double radius = 0.0);

}  // namespace fsd

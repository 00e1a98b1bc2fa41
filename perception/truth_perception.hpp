#pragma once
// The "truth" perception source (run.perception_source = truth): what an ideal detector would report — the
// virtual car's standing cones within range and field of view, in the vehicle frame, with a small seeded
// position noise and the true colour. It keeps the loop running end to end before perception lands, and stays
// as the reference for control work.
#include <numbers>
#include <random>
#include <vector>

#include "common/config.hpp"
#include "common/types.hpp"

namespace fsd {

struct TruthPerceptionConfig {
  double range = 20.0;           // m: the paper's 20 m ROI
  double fov_deg = 360.0;        // full horizontal field of view centred on x (the VLP-16 sees all round)
  double position_noise = 0.03;  // m, σ per axis
  double min_range = 1.0;        // m: cones under the nose are not seen
};
const ConfigSection<TruthPerceptionConfig>& truth_perception_section();

class TruthPerception {
 public:
  TruthPerception(const TruthPerceptionConfig& cfg, std::uint64_t seed) : cfg_(cfg), rng_(seed) {}
  // `cones`: true standing cones in the map frame; `pose`: true vehicle pose (rear-axle centre).
  ConeDetections detect(Stamp t, const std::vector<Cone>& cones, const Pose2& pose);

 private:
  TruthPerceptionConfig cfg_;
  std::mt19937_64 rng_;
};

}  // namespace fsd

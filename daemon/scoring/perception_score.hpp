#pragma once
// The scorecard's "perception" section (DESIGN.md §8): every perception frame's cone detections against the
// simulated world's standing cones at that instant, placed by the car's true pose. Detections and true cones are
// paired one to one within a gate (common/cone_pairing). Precision over all detections; recall over the true
// cones within 15 m and 20 m of the car; position RMSE over the pairs; colour accuracy over the pairs within
// 12 m (where the camera is expected to tell the colour), and of those the camera verified or that name a colour;
// colour accuracy within 6 m (where the LiDAR's reflectivity tells it without the camera). Where the simulator
// says which cones its LiDAR could see (returned points from) at the frame, recall over those within 15 m too: a
// cone hidden behind another is then told apart from one perception missed.
#include <cstdint>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/types.hpp"

namespace fsd {

class PerceptionScore {
 public:
  explicit PerceptionScore(double gate = 0.5) : gate_(gate) {}
  // `detections` in the vehicle frame; `truth` the standing cones in the map frame; `pose` the true pose;
  // `visible`: the ids of the cones the LiDAR could see at the frame, sorted (none: not known).
  void add_frame(const ConeDetections& detections, const std::vector<Cone>& truth, const Pose2& pose,
                 const std::vector<std::uint32_t>* visible = nullptr);
  int frames() const { return frames_; }
  nlohmann::json to_json() const;

 private:
  double gate_;
  int frames_ = 0;
  std::uint64_t detections_ = 0, true_positives_ = 0;
  std::uint64_t truth_15_ = 0, found_15_ = 0, truth_20_ = 0, found_20_ = 0;
  bool visibility_known_ = false;  // some frame was scored with the visible cones known
  std::uint64_t visible_15_ = 0, found_visible_15_ = 0;
  std::uint64_t pairs_12_ = 0, right_colour_12_ = 0;
  std::uint64_t verified_12_ = 0, verified_right_12_ = 0;  // pairs the camera verified
  std::uint64_t named_12_ = 0, named_right_12_ = 0;        // pairs with a colour named (not unknown)
  std::uint64_t pairs_6_ = 0, right_colour_6_ = 0;
  double sq_error_ = 0;
};

}  // namespace fsd

#pragma once
// The cone map (DESIGN.md §3 "mapping"): cone positions and colours in the map frame, built from detections and
// the vehicle pose. Each detection is associated with the nearest mapped cone inside a gate (else starts a new
// cone); positions are fused in information form, colours by vote. A detection whose colour differs from the mapped
// cone's has a tighter gate: a start line's doubled orange cones stand 0.5 m from the boundary cone between them.
// What the camera rejected (a tyre, a post the LiDAR took for a cone) counts against the mapped cone there: one the
// camera rejected more often than it verified, at least `min_rejections` times, is not reported (it stays mapped,
// so a real cone the camera doubted once comes back with its next verifications). The verdicts count in frames
// `expect_spacing` apart, as the misses below do: a car standing at the start repeats one view sixty times. Without
// a camera nothing is rejected and every LiDAR-only cone is reported. Colour votes likewise, per cone: one vote from
// each place expect_spacing apart (a small cone beside a timing line's big ones, seen 15 m off while the car stands
// at the start, is one vote; a cone first named while the car stands gets that vote).
//
// Ghost pruning: a mapped cone the car came near and did not see is not reported. Each frame, a mapped cone between
// `expect_min_range` and `expect_range` of the car with no detection of the frame paired to it counts a miss; one
// missed at least `min_misses` times and more often than seen in that range is withheld: what looks like a cone
// from far away and does not from near (a tyre stack, a post beside a fence, a piece of fence). Real cones are
// detected near the car in nearly every frame. Frames count only once the car has moved `expect_spacing` since the
// last one counted: a car standing with a cone hidden behind another would otherwise count it out. A cone first
// detected now counts as missed by the frames of the last `expect_memory` metres (and 10 s: not those of another
// lap) that had it in the expected range: a post the car passed unseen and then detected from far behind is the
// same ghost as one it came near after.
//
// Loop closure moves the poses a map was built from (localization/loop_closure): each cone keeps its sightings per
// visit (seen without a gap of more than a few seconds), so that correct() moves each visit with the correction of
// its instant, a cone seen at the start and again on the next lap with the correction of each. Two cones that then
// coincide are one (a cone mapped at the start and again, drifted, at the lap's end).
#include <array>
#include <deque>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "common/config.hpp"
#include "common/types.hpp"

namespace fsd {

struct ConeMapConfig {
  double association_gate = 0.7;  // m: under the 1 m between a start line's cones, 7σ of 0.1 m detection noise
  double colour_conflict_gate =
      0.4;                   // m: a detection of another colour than the mapped cone's is that cone only this close
  int min_observations = 2;  // a cone is reported once seen this often
  double min_support = 2.0;  // ... and once its detections' confidences sum to this (a far one counts less, one
                             // the camera verified counts 1)
  int min_rejections = 5;    // camera rejections before a mapped cone may be withheld (2 withheld true cones)
  double max_range = 20.0;   // detections farther than this are ignored (m)
  double merge_gate = 0.45;  // m: corrected cones this close, first mapped at different times, are one cone
  double expect_min_range = 2.0;  // m: nearer, a cone may be hidden by the car's own body cut-out
  double expect_range = 10.0;     // m: a cone this near is detected in nearly every frame
  int min_misses = 3;             // frames a cone near the car was not detected before it may be withheld; 0: never
  double expect_spacing = 0.5;    // m driven between the frames whose misses and camera verdicts count
  double expect_memory = 30.0;    // m driven: a cone first detected now was missed by the frames of this stretch
};
const ConfigSection<ConeMapConfig>& cone_map_section();

class ConeMap {
 public:
  explicit ConeMap(const ConeMapConfig& cfg = {}) : cfg_(cfg) {}
  // Detections in the vehicle frame, taken at vehicle pose `pose` (map frame).
  // `rejected`: candidates at the same instant the camera saw and judged not to be cones (vehicle frame).
  void update(const ConeDetections& detections, const Pose2& pose, std::span<const Cone> rejected = {});
  // Confirmed cones in the map frame with fused position, covariance and voted colour.
  std::vector<Cone> cones() const;
  std::size_t size() const { return entries_.size(); }
  void clear() {
    entries_.clear();
    expect_at_.reset();
    trail_.clear();
  }
  // Moves every cone with the poses it was seen from: `correction(t)` takes a position placed by the pose of
  // instant t into the corrected map frame (LoopClosure::correction_at). Then merges the cones that coincide
  // (within merge_gate, compatible colours, first mapped in visits that do not overlap: a frame's cones are
  // distinct). Returns the number of merges.
  int correct(const std::function<Pose2(Stamp)>& correction);

 private:
  struct Visit {  // the sightings of one pass, in information form
    Eigen::Matrix2d info = Eigen::Matrix2d::Zero();
    Vec2 info_vec = Vec2::Zero();
    Stamp first = 0, last = 0;
    double t_sum = 0;
    int n = 0;
  };
  struct Entry {
    Eigen::Matrix2d info = Eigen::Matrix2d::Zero();  // Σ⁻¹
    Vec2 info_vec = Vec2::Zero();                    // Σ⁻¹ μ
    Vec2 mean = Vec2::Zero();
    int observations = 0;
    double support = 0;                  // the detections' confidences summed
    int verified = 0, rejected = 0;      // camera verdicts on it, in frames expect_spacing apart
    int near_seen = 0, near_missed = 0;  // frames with it within the expected range: detected, not detected
    std::array<int, 6> colour_votes{};
    std::optional<Vec2> voted_from;  // where the car was at its last colour vote
    std::uint32_t id = 0;
    std::vector<Visit> visits;           // bounded: the oldest two merge beyond kMaxVisits
    Stamp first_from = 0, first_to = 0;  // its first visit's span
  };
  static void add_visit(Entry& e, const Visit& v);
  static void cap_visits(Entry& e);  // at most kMaxVisits: the oldest two merge
  static void refresh(Entry& e);
  ConeMapConfig cfg_;
  std::optional<Vec2> expect_at_;  // where the last frame that counted for ghost pruning was taken
  struct TrailFrame {
    Vec2 position;
    Stamp stamp;
  };
  std::deque<TrailFrame> trail_;  // the frames that counted over the last expect_memory metres (and seconds)
  std::vector<Entry> entries_;
  std::uint32_t next_id_ = 1;
};

}  // namespace fsd

#pragma once
// Scores LiDAR detections against the simulated world's true cones, frame by frame: the scorecard's perception
// measure (daemon/perception_score: one-to-one pairing within 0.5 m, ranges from the car's rear axle) plus the
// position RMSE within 15 m and the colour of the cones within 6 m.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/cone_pairing.hpp"
#include "common/types.hpp"
#include "daemon/scoring/perception_score.hpp"

namespace fsd::test {

struct ColourTally {
  int truth = 0;  // paired cones within the colour range
  int named = 0;  // with a colour
  int right = 0;  // with the right colour
  double accuracy() const { return truth > 0 ? static_cast<double>(right) / truth : 0.0; }
  double named_accuracy() const { return named > 0 ? static_cast<double>(right) / named : 0.0; }
};

class LidarEval {
 public:
  explicit LidarEval(double colour_range = 6.0) : colour_range_(colour_range) {}

  // `detections` in the vehicle frame at `pose` (map ← body, the true pose at detections.stamp).
  void add(const ConeDetections& detections, const std::vector<Cone>& truth, const Pose3& pose) {
    const Pose2 p2 = to_pose2(pose);
    score_.add_frame(detections, truth, p2);
    std::vector<Vec2> est, tru;
    for (const auto& d : detections.cones) est.push_back(p2.transform(d.position.head<2>()));
    for (const auto& t : truth) tru.push_back(t.position.head<2>());
    const std::vector<ConePair> pairs = pair_cones(est, tru, 0.5);
    std::vector<bool> matched(est.size(), false);
    for (const auto& pr : pairs) {
      matched[pr.estimate] = true;
      const double r = (tru[pr.truth] - p2.position()).norm();
      if (r <= 15.0) sq15_ += pr.distance * pr.distance, ++n15_;
      if (r <= colour_range_) {
        ++colour_.truth;
        const ConeColour c = detections.cones[pr.estimate].colour;
        if (c != ConeColour::Unknown) ++colour_.named;
        if (c == truth[pr.truth].colour)
          ++colour_.right;
        else if (c != ConeColour::Unknown)
          ++wrong_colour_[static_cast<int>(truth[pr.truth].colour)][static_cast<int>(c)];
      }
    }
    for (std::size_t i = 0; i < est.size(); ++i)
      if (!matched[i]) false_positives_.push_back(est[i]);
  }

  nlohmann::json score() const { return score_.to_json(); }
  double precision() const { return score()["precision"]; }
  double recall_15() const { return score()["recall_15m"]; }
  double recall_20() const { return score()["recall_20m"]; }
  double rmse_15() const { return n15_ > 0 ? std::sqrt(sq15_ / n15_) : 0.0; }
  const ColourTally& colour() const { return colour_; }
  const std::vector<Vec2>& false_positives() const { return false_positives_; }
  int wrong_colour(ConeColour truth, ConeColour said) const {
    return wrong_colour_[static_cast<int>(truth)][static_cast<int>(said)];
  }

  std::string summary() const {
    char b[400];
    std::snprintf(b, sizeof b,
                  "frames %d, precision %.4f, recall 15 m %.4f, 20 m %.4f, RMSE 15 m %.4f m, colour within %.0f m: "
                  "%.3f of %d (named %.3f, of them right %.3f), false positives %zu",
                  score_.frames(), precision(), recall_15(), recall_20(), rmse_15(), colour_range_, colour_.accuracy(),
                  colour_.truth, colour_.truth > 0 ? static_cast<double>(colour_.named) / colour_.truth : 0.0,
                  colour_.named_accuracy(), false_positives_.size());
    return b;
  }

 private:
  double colour_range_;
  PerceptionScore score_;
  double sq15_ = 0;
  int n15_ = 0;
  ColourTally colour_;
  int wrong_colour_[6][6] = {};
  std::vector<Vec2> false_positives_;
};

}  // namespace fsd::test

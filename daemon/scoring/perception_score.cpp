#include "daemon/scoring/perception_score.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "common/cone_pairing.hpp"

namespace fsd {

void PerceptionScore::add_frame(const ConeDetections& detections, const std::vector<Cone>& truth, const Pose2& pose,
                                const std::vector<std::uint32_t>* visible) {
  ++frames_;
  visibility_known_ = visibility_known_ || visible != nullptr;
  auto is_visible = [visible](const Cone& c) {
    return visible && std::binary_search(visible->begin(), visible->end(), c.id);
  };
  std::vector<Vec2> est, tru;
  for (const auto& d : detections.cones) est.push_back(pose.transform(Vec2(d.position.head<2>())));
  for (const auto& t : truth) tru.push_back(t.position.head<2>());
  const Vec2 car = pose.position();
  detections_ += est.size();
  for (std::size_t i = 0; i < tru.size(); ++i) {
    const double r = (tru[i] - car).norm();
    truth_15_ += r <= 15.0;
    truth_20_ += r <= 20.0;
    visible_15_ += r <= 15.0 && is_visible(truth[i]);
  }
  for (const auto& p : pair_cones(est, tru, gate_)) {
    ++true_positives_;
    sq_error_ += p.distance * p.distance;
    const double r = (tru[p.truth] - car).norm();
    found_15_ += r <= 15.0;
    found_20_ += r <= 20.0;
    found_visible_15_ += r <= 15.0 && is_visible(truth[p.truth]);
    const Cone& d = detections.cones[p.estimate];
    const bool right = d.colour == truth[p.truth].colour;
    if (r <= 12.0) {
      ++pairs_12_;
      right_colour_12_ += right;
      if (d.stage == DetectionStage::Camera) {
        ++verified_12_;
        verified_right_12_ += right;
      }
      if (d.colour != ConeColour::Unknown) {
        ++named_12_;
        named_right_12_ += right;
      }
    }
    if (r <= 6.0) {
      ++pairs_6_;
      right_colour_6_ += right;
    }
  }
}

nlohmann::json PerceptionScore::to_json() const {
  // Shares and the RMSE to 1e-4 (a tenth of a millimetre).
  auto r4 = [](double v) { return std::round(v * 1e4) / 1e4; };
  auto share = [&](std::uint64_t a, std::uint64_t b) { return r4(b > 0 ? static_cast<double>(a) / b : 0.0); };
  nlohmann::json j = {{"frames", frames_},
                      {"detections", detections_},
                      {"precision", share(true_positives_, detections_)},
                      {"recall_15m", share(found_15_, truth_15_)},
                      {"recall_20m", share(found_20_, truth_20_)},
                      {"position_rmse_m", r4(true_positives_ > 0 ? std::sqrt(sq_error_ / true_positives_) : 0.0)},
                      {"colour_accuracy_12m", share(right_colour_12_, pairs_12_)},
                      {"verified_share_12m", share(verified_12_, pairs_12_)},
                      {"verified_colour_accuracy_12m", share(verified_right_12_, verified_12_)},
                      {"named_colour_accuracy_12m", share(named_right_12_, named_12_)},
                      {"colour_accuracy_6m", share(right_colour_6_, pairs_6_)}};
  // Over the frames that knew what the sensor could see (a simulated run with its LiDAR, or its replay).
  if (visibility_known_) j["recall_visible_15m"] = share(found_visible_15_, visible_15_);
  return j;
}

}  // namespace fsd

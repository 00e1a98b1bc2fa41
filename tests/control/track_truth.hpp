#pragma once
// Ground truth for the control tests, computed from the true cones of a track file only, independently of the
// planner: "rungs" join every boundary cone to the nearest cone of the other boundary; their midpoints lie on
// the track's centre line, and midpoints of neighbouring rungs joined by segments trace it. The heading of the
// track at a rung is the rung turned a quarter to the right (left boundary on the left).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/track.hpp"

namespace fsd::test {

struct Rung {
  Vec2 left, right, mid;
  double width;
  double heading;  // direction of travel (rough for a diagonal rung)
  bool nearest;    // joins a cone to the nearest cone of the other boundary
};

inline double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

class TrackTruth {
 public:
  explicit TrackTruth(const Track& track, double max_width = 6.5, double join = 7.0) : track_(track) {
    std::vector<Vec2> left, right;
    for (const auto& c : track.cones) {
      if (c.role == ConeRole::Left) left.push_back(c.position);
      if (c.role == ConeRole::Right) right.push_back(c.position);
      cones_.push_back(c.position);
    }
    auto add = [&](const Vec2& l, const Vec2& r, bool first) {
      const double w = (l - r).norm();
      if (w > max_width || w < 1e-6) return;
      for (auto& q : rungs_)
        if ((q.left - l).norm() < 1e-6 && (q.right - r).norm() < 1e-6) {
          q.nearest = q.nearest || first;
          return;
        }
      const Vec2 across = (l - r) / w;  // right → left
      rungs_.push_back({l, r, 0.5 * (l + r), w, std::atan2(-across.x(), across.y()), first});
    };
    // Each cone to the two nearest of the other boundary: the second rung of a cone is a diagonal one, whose
    // midpoint still lies on the centre line of a straight and fills gaps where cones are sparse.
    for (const auto& l : left) {
      const auto two = nearest_two(right, l);
      for (std::size_t k = 0; k < two.size(); ++k) add(l, *two[k], k == 0);
    }
    for (const auto& r : right) {
      const auto two = nearest_two(left, r);
      for (std::size_t k = 0; k < two.size(); ++k) add(*two[k], r, k == 0);
    }
    // Neighbouring rungs of one stretch of track: close, facing the same way, and each in front of or behind
    // the other (not side by side, which would be the next stretch of a hairpin).
    for (std::size_t i = 0; i < rungs_.size(); ++i)
      for (std::size_t j = i + 1; j < rungs_.size(); ++j) {
        const Vec2 d = rungs_[j].mid - rungs_[i].mid;
        const double len = d.norm();
        if (len > join) continue;
        if (std::abs(wrap_angle(rungs_[i].heading - rungs_[j].heading)) > deg2rad(60)) continue;
        if (len > 0.5) {
          const double along = std::atan2(d.y(), d.x());
          auto aligned = [&](double h) {
            const double a = std::abs(wrap_angle(along - h));
            return a < deg2rad(50) || a > deg2rad(130);
          };
          if (!aligned(rungs_[i].heading) || !aligned(rungs_[j].heading)) continue;
        }
        segments_.push_back({i, j});
      }
  }

  const std::vector<Rung>& rungs() const { return rungs_; }
  const std::vector<Vec2>& cones() const { return cones_; }

  // Distance from p to the centre line (nearest centre segment or rung midpoint).
  double centre_distance(const Vec2& p) const {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& r : rungs_) best = std::min(best, (p - r.mid).norm());
    for (const auto& [i, j] : segments_) best = std::min(best, point_segment_distance(p, rungs_[i].mid, rungs_[j].mid));
    return best;
  }
  // Distance from p to the nearest cone of any colour.
  double cone_clearance(const Vec2& p) const {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& c : cones_) best = std::min(best, (p - c).norm());
    return best;
  }

 private:
  static std::vector<const Vec2*> nearest_two(const std::vector<Vec2>& set, const Vec2& p) {
    std::vector<const Vec2*> all;
    for (const auto& q : set) all.push_back(&q);
    std::sort(all.begin(), all.end(), [&](const Vec2* a, const Vec2* b) { return (*a - p).norm() < (*b - p).norm(); });
    if (all.size() > 2) all.resize(2);
    return all;
  }
  Track track_;
  std::vector<Vec2> cones_;
  std::vector<Rung> rungs_;
  std::vector<std::pair<std::size_t, std::size_t>> segments_;
};

inline const std::vector<std::string>& loop_tracks() {
  static const std::vector<std::string> names{"epfl_track_1",
                                              "epfl_track_2",
                                              "epfl_track_3",
                                              "epfl_track_4",
                                              "epfl_track_5",
                                              "epfl_fsds_competition_1",
                                              "epfl_fsds_competition_2",
                                              "epfl_fsds_competition_3",
                                              "epfl_fsds_default",
                                              "epfl_VSV",
                                              "epfl_VSV_XL",
                                              "epfl_VSV_XS",
                                              "epfl_autoX_Vaudoise_Sponso",
                                              "epfl_21_05_2023",
                                              "amz_fssim_thin"};
  return names;
}

inline Track shared_track(const std::string& name) { return load_track("../shared/tracks/" + name + ".csv"); }


}  // namespace fsd::test

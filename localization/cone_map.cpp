#include "localization/cone_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace fsd {

const ConfigSection<ConeMapConfig>& cone_map_section() {
  static const auto s =
      ConfigSection<ConeMapConfig>("localization.cone_map")
          .number("association_gate", &ConeMapConfig::association_gate, 0.1, 5.0, "m",
                  "A detection this close to a mapped cone is the same cone.")
          .number("colour_conflict_gate", &ConeMapConfig::colour_conflict_gate, 0.05, 5.0, "m",
                  "A detection of another colour than the mapped cone's is that cone only this close.")
          .integer("min_observations", &ConeMapConfig::min_observations, 1, 100, "",
                   "Observations before a cone is reported (rejects one-off ghosts).")
          .integer("min_rejections", &ConeMapConfig::min_rejections, 1, 1000, "",
                   "Camera rejections before a mapped cone the camera rejected more often than it "
                   "verified is withheld (a distractor the LiDAR took for a cone).")
          .number("min_support", &ConeMapConfig::min_support, 0.0, 100.0, "",
                  "A cone is reported once its detections' confidences (1 near or verified by the camera, less far: "
                  "perception.lidar.quality) sum to this: what only the LiDAR saw a few times from far waits.")
          .number("max_range", &ConeMapConfig::max_range, 1.0, 100.0, "m",
                  "Detections beyond this range are not mapped.")
          .number("merge_gate", &ConeMapConfig::merge_gate, 0.01, 5.0, "m",
                  "After a loop closure moved the map, cones this close that were first mapped at different times "
                  "are one cone.")
          .number("expect_min_range", &ConeMapConfig::expect_min_range, 0.0, 50.0, "m",
                  "Ghost pruning: a mapped cone nearer than this to the car may be hidden (the body's cut-out).")
          .number("expect_range", &ConeMapConfig::expect_range, 0.0, 50.0, "m",
                  "Ghost pruning: a mapped cone between expect_min_range and this range of the car is expected "
                  "to be detected in every frame.")
          .integer("min_misses", &ConeMapConfig::min_misses, 0, 1000, "",
                   "Ghost pruning: frames a mapped cone within the expected range went undetected before it is "
                   "withheld, when it was missed there more often than seen (0: never withheld).")
          .number("expect_spacing", &ConeMapConfig::expect_spacing, 0.0, 10.0, "m",
                  "Distance driven between the frames whose misses (ghost pruning) and camera verdicts count (a "
                  "standing car counts once).")
          .number("expect_memory", &ConeMapConfig::expect_memory, 0.0, 200.0, "m",
                  "Ghost pruning: a cone first detected now counts as missed by the frames of the last this many "
                  "metres driven that had it in the expected range (passed unseen, detected from far after).");
  return s;
}

namespace {

constexpr double kVisitGap = 3.0;        // s unseen before a sighting starts a new visit (a lap takes far longer)
constexpr std::size_t kMaxVisits = 8;    // per cone: the oldest two merge beyond (they are long corrected alike)
constexpr std::size_t kMaxTrail = 1024;  // frames remembered for ghost pruning, whatever expect_memory says
constexpr double kTrailAge = 10.0;       // s: older frames are of another pass (a lap takes longer), maybe drifted

ConeColour voted_colour(const std::array<int, 6>& votes) {
  const auto top = std::max_element(votes.begin(), votes.end());
  return *top > 0 ? static_cast<ConeColour>(top - votes.begin()) : ConeColour::Unknown;
}

}  // namespace

void ConeMap::update(const ConeDetections& detections, const Pose2& pose, std::span<const Cone> rejected) {
  // Evidence that a repeated view would inflate (misses, the camera's verdicts) counts in frames expect_spacing
  // apart: a car standing at the start sees the same thing sixty times, and once is what it tells.
  const bool counted = !expect_at_ || (pose.position() - *expect_at_).norm() >= cfg_.expect_spacing;

  // Camera rejections: against the nearest mapped cone within the gate.
  for (const auto& r : rejected) {
    if (!counted) break;
    const Vec2 local = r.position.head<2>();
    if (!local.allFinite() || local.norm() > cfg_.max_range) continue;
    const Vec2 p = pose.transform(local);
    Entry* nearest = nullptr;
    double best = cfg_.association_gate;
    for (auto& e : entries_) {
      const double d = (e.mean - p).norm();
      if (d < best) best = d, nearest = &e;
    }
    if (nearest) ++nearest->rejected;
  }

  const Eigen::Matrix2d R = pose.rotation().toRotationMatrix();
  struct Seen {
    Vec2 p;
    Eigen::Matrix2d info;
    ConeColour colour;
    bool verified;
    double confidence;
  };
  std::vector<Seen> seen;
  seen.reserve(detections.cones.size());
  for (const auto& d : detections.cones) {
    const Vec2 local = d.position.head<2>();
    if (!local.allFinite() || local.norm() > cfg_.max_range) continue;
    // Covariance rotated into the map frame; floor it so a zero covariance cannot make the information infinite.
    Eigen::Matrix2d cov = R * d.covariance * R.transpose();
    cov += Eigen::Matrix2d::Identity() * 1e-4;
    const double confidence = std::isfinite(d.confidence) ? std::clamp(d.confidence, 0.0, 1.0) : 0.0;
    seen.push_back({pose.transform(local), cov.inverse(), d.colour, d.stage == DetectionStage::Camera, confidence});
  }

  // One frame's detections are distinct cones: each joins at most one mapped cone and each mapped cone takes at
  // most one of them, nearest pairs first (global nearest neighbour). Without that, two cones nearer than the
  // gate (a timing line's doubled cones, 0.5 m apart) were fused into one between them.
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < seen.size(); ++i)
    for (std::size_t k = 0; k < entries_.size(); ++k) {
      const double dist = (entries_[k].mean - seen[i].p).norm();
      if (dist >= cfg_.association_gate) continue;
      const ConeColour mapped = voted_colour(entries_[k].colour_votes);
      const bool conflict =
          seen[i].colour != ConeColour::Unknown && mapped != ConeColour::Unknown && mapped != seen[i].colour;
      if (conflict && dist >= cfg_.colour_conflict_gate) continue;
      pairs.emplace_back(dist, i, k);
    }
  std::sort(pairs.begin(), pairs.end());
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> entry_of(seen.size(), kNone);
  std::vector<bool> taken(entries_.size(), false);
  for (const auto& [dist, i, k] : pairs) {
    if (entry_of[i] != kNone || taken[k]) continue;
    entry_of[i] = k;
    taken[k] = true;
  }

  // Ghost pruning's evidence: the mapped cones near the car, detected in this frame or not.
  const auto in_expected_range = [&](const Vec2& cone, const Vec2& car) {
    const double range = (cone - car).norm();
    return range >= cfg_.expect_min_range && range <= cfg_.expect_range;
  };
  if (counted) {
    expect_at_ = pose.position();
    for (std::size_t k = 0; k < entries_.size(); ++k)
      if (in_expected_range(entries_[k].mean, pose.position()))
        ++(taken[k] ? entries_[k].near_seen : entries_[k].near_missed);
    trail_.push_back({pose.position(), detections.stamp});
    double driven = 0;  // from the newest back; what lies beyond expect_memory goes
    for (std::size_t i = trail_.size() - 1; i > 0; --i) {
      driven += (trail_[i].position - trail_[i - 1].position).norm();
      if (driven > cfg_.expect_memory || detections.stamp - trail_[i - 1].stamp > kTrailAge) {
        trail_.erase(trail_.begin(), trail_.begin() + static_cast<std::ptrdiff_t>(i));
        break;
      }
    }
    while (trail_.size() > kMaxTrail) trail_.pop_front();
  }
  const std::size_t trail_past = trail_.size() - (counted ? 1 : 0);  // the frames before this one

  for (std::size_t i = 0; i < seen.size(); ++i) {
    if (entry_of[i] == kNone) {
      // Where the car was near and saw nothing, it missed this cone. Near a mapped neighbour, which may have taken
      // those detections (two cones seen as one from far, split when near; a tyre seen as two), it was missed
      // where the neighbour was: a doubled cone beside a true one starts clean, a piece of a ghost as a ghost.
      const Entry* neighbour = nullptr;
      double nearest = 2.0 * cfg_.association_gate;
      for (const auto& e : entries_)
        if (const double d = (e.mean - seen[i].p).norm(); d < nearest) nearest = d, neighbour = &e;
      int missed = 0;
      if (neighbour)
        missed = neighbour->near_missed;
      else
        for (std::size_t f = 0; f < trail_past; ++f) missed += in_expected_range(seen[i].p, trail_[f].position);
      entry_of[i] = entries_.size();
      Entry& fresh = entries_.emplace_back();
      fresh.id = next_id_++;
      fresh.near_missed = missed;
    }
    Entry& e = entries_[entry_of[i]];
    const Stamp t = detections.stamp;
    if (e.visits.empty() || t - e.visits.back().last > kVisitGap) {
      if (e.visits.empty()) e.first_from = t;
      e.visits.push_back({Eigen::Matrix2d::Zero(), Vec2::Zero(), t, t, 0.0, 0});
      cap_visits(e);
    }
    Visit& v = e.visits.back();
    v.info += seen[i].info;
    v.info_vec += seen[i].info * seen[i].p;
    v.last = t;
    v.t_sum += t;
    ++v.n;
    if (e.visits.size() == 1) e.first_to = t;
    e.info += seen[i].info;
    e.info_vec += seen[i].info * seen[i].p;
    e.mean = e.info.ldlt().solve(e.info_vec);
    ++e.observations;
    e.support += seen[i].verified ? 1.0 : seen[i].confidence;  // the camera's verdict confirms a far one
    e.verified += seen[i].verified && counted;
    const auto c = static_cast<std::size_t>(seen[i].colour);
    // One colour vote per cone per place (expect_spacing apart): a standing car repeats one view.
    if (seen[i].colour != ConeColour::Unknown && c < e.colour_votes.size() &&
        (!e.voted_from || (pose.position() - *e.voted_from).norm() >= cfg_.expect_spacing)) {
      ++e.colour_votes[c];
      e.voted_from = pose.position();
    }
  }
}

void ConeMap::add_visit(Entry& e, const Visit& v) {
  Visit& into = e.visits.front();
  into.info += v.info;
  into.info_vec += v.info_vec;
  into.first = std::min(into.first, v.first);
  into.last = std::max(into.last, v.last);
  into.t_sum += v.t_sum;
  into.n += v.n;
}

void ConeMap::cap_visits(Entry& e) {
  while (e.visits.size() > kMaxVisits) {
    add_visit(e, e.visits[1]);  // into visits[0]: see add_visit
    e.visits.erase(e.visits.begin() + 1);
  }
}

void ConeMap::refresh(Entry& e) {
  e.info.setZero();
  e.info_vec.setZero();
  for (const auto& v : e.visits) e.info += v.info, e.info_vec += v.info_vec;
  if (e.info.determinant() > 0) e.mean = e.info.ldlt().solve(e.info_vec);
}

int ConeMap::correct(const std::function<Pose2(Stamp)>& correction) {
  trail_.clear();  // taken in the frame the correction leaves
  for (auto& e : entries_) {
    for (auto& v : e.visits) {
      if (v.n == 0) continue;
      // The visit's mean position and information, moved rigidly by the correction of its mean instant.
      const Pose2 c = correction(v.t_sum / v.n);
      const Eigen::Matrix2d R = c.rotation().toRotationMatrix();
      const Vec2 mean = c.transform(v.info.ldlt().solve(v.info_vec));
      v.info = R * v.info * R.transpose();
      v.info_vec = v.info * mean;
    }
    refresh(e);
  }
  // Cones that now coincide, nearest pairs first, each merged once per call.
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t a = 0; a < entries_.size(); ++a)
    for (std::size_t b = a + 1; b < entries_.size(); ++b) {
      const Entry &ea = entries_[a], &eb = entries_[b];
      const double d = (ea.mean - eb.mean).norm();
      if (d >= cfg_.merge_gate) continue;
      const ConeColour ca = voted_colour(ea.colour_votes), cb = voted_colour(eb.colour_votes);
      if (ca != cb && ca != ConeColour::Unknown && cb != ConeColour::Unknown) continue;
      if (ea.first_from <= eb.first_to && eb.first_from <= ea.first_to) continue;  // seen together: two cones
      pairs.emplace_back(d, a, b);
    }
  std::sort(pairs.begin(), pairs.end());
  std::vector<char> gone(entries_.size(), 0), used(entries_.size(), 0);
  int merged = 0;
  for (const auto& [d, a, b] : pairs) {
    if (used[a] || used[b]) continue;
    used[a] = used[b] = 1;
    Entry &keep = entries_[a], &from = entries_[b];  // a: the older id (entries are in order of creation)
    for (const auto& v : from.visits) keep.visits.push_back(v);
    std::sort(keep.visits.begin(), keep.visits.end(), [](const Visit& x, const Visit& y) { return x.first < y.first; });
    cap_visits(keep);
    keep.observations += from.observations;
    keep.support += from.support;
    keep.verified += from.verified;
    keep.rejected += from.rejected;
    keep.near_seen += from.near_seen;
    keep.near_missed += from.near_missed;
    for (std::size_t c = 0; c < keep.colour_votes.size(); ++c) keep.colour_votes[c] += from.colour_votes[c];
    refresh(keep);
    gone[b] = 1;
    ++merged;
  }
  std::size_t w = 0;
  for (std::size_t i = 0; i < entries_.size(); ++i)
    if (!gone[i]) entries_[w++] = std::move(entries_[i]);
  entries_.resize(w);
  return merged;
}

std::vector<Cone> ConeMap::cones() const {
  std::vector<Cone> out;
  for (const auto& e : entries_) {
    if (e.observations < cfg_.min_observations || e.support < cfg_.min_support - 1e-9) continue;
    if (e.rejected >= cfg_.min_rejections && e.rejected > e.verified) continue;  // the camera says: not a cone
    if (cfg_.min_misses > 0 && e.near_missed >= cfg_.min_misses && e.near_missed > e.near_seen)
      continue;  // not seen where a cone would have been: not a cone
    Cone c;
    c.position = Vec3(e.mean.x(), e.mean.y(), 0.0);
    c.covariance = e.info.inverse();
    c.id = e.id;
    int total = 0;
    for (int v : e.colour_votes) total += v;
    c.colour = voted_colour(e.colour_votes);
    const int top = *std::max_element(e.colour_votes.begin(), e.colour_votes.end());
    c.confidence = total > 0 ? static_cast<double>(top) / total : 0.0;
    out.push_back(c);
  }
  return out;
}

}  // namespace fsd

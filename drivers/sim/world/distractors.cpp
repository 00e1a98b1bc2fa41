#include "drivers/sim/world/distractors.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "drivers/sim/world/world_random.hpp"

namespace fsd::sim {

const char* to_string(DistractorType t) {
  switch (t) {
    case DistractorType::Tyre:
      return "tyre";
    case DistractorType::TyreStack:
      return "tyre_stack";
    case DistractorType::Post:
      return "post";
    case DistractorType::Fence:
      return "fence";
  }
  return "?";
}

double Distractor::footprint_radius() const {
  if (type == DistractorType::Fence) return 0.0;
  if (type == DistractorType::Tyre && standing) return std::hypot(radius, width / 2);
  return radius;
}

Vec2 Distractor::fence_end() const { return position + length * Vec2(std::cos(yaw), std::sin(yaw)); }

namespace {

constexpr double kClearance = 0.5;       // m between two distractors
constexpr double kFenceSampling = 0.25;  // m between checked points along a fence
constexpr int kAttempts = 300;

class Placer {
 public:
  Placer(const TrackArea& area, const WorldConfig& cfg, std::uint64_t seed) : area_(area), cfg_(cfg), rng_(seed) {}

  void fences() {
    const double min_offset = std::max(cfg_.fence_offset_min, cfg_.distractor_min_offset);
    const double max_offset = std::max(cfg_.fence_offset_max, min_offset);
    for (int s = 0; s < cfg_.fence_segments; ++s) {
      for (int attempt = 0; attempt < kAttempts; ++attempt) {
        // Bends rarely leave room for a long straight fence at the same offset: shorten after failures.
        const double length = cfg_.fence_length * (attempt < 100 ? 1.0 : attempt < 200 ? 0.6 : 0.35);
        const auto anchor = anchor_point(min_offset, max_offset);
        if (!anchor) continue;
        const auto& [centre, outward] = *anchor;
        const Vec2 dir(-outward.y(), outward.x());
        Distractor f;
        f.type = DistractorType::Fence;
        f.position = centre - dir * (length / 2);
        f.yaw = std::atan2(dir.y(), dir.x());
        f.length = length;
        f.height = cfg_.fence_height;
        if (fence_is_clear(f, min_offset)) {
          out_.push_back(f);
          break;
        }
      }
    }
  }

  template <class Make>
  void round_objects(int count, Make&& make) {
    for (int n = 0; n < count; ++n) {
      for (int attempt = 0; attempt < kAttempts; ++attempt) {
        Distractor d = make();
        const double r = d.footprint_radius();
        const double max_offset = std::max(cfg_.distractor_max_offset, cfg_.distractor_min_offset);
        const auto anchor = anchor_point(cfg_.distractor_min_offset + r, max_offset + r);
        if (!anchor) continue;
        d.position = anchor->first;
        if (clear_of_track(d.position, r, cfg_.distractor_min_offset) && clear_of_others(d.position, r)) {
          out_.push_back(d);
          break;
        }
      }
    }
  }

  Distractor tyre() {
    Distractor d;
    d.type = DistractorType::Tyre;
    d.radius = rng_.uniform(0.28, 0.32);
    d.width = rng_.uniform(0.18, 0.23);
    d.standing = rng_.chance(0.3);
    d.height = d.standing ? 2 * d.radius : d.width;
    d.yaw = rng_.uniform(0.0, 2 * std::numbers::pi);
    return d;
  }
  Distractor stack() {
    Distractor d;
    d.type = DistractorType::TyreStack;
    d.radius = rng_.uniform(0.28, 0.32);
    d.width = rng_.uniform(0.18, 0.22);
    d.tyre_count = rng_.uniform_int(2, 4);
    d.height = d.tyre_count * d.width;
    return d;
  }
  Distractor post() {
    Distractor d;
    d.type = DistractorType::Post;
    d.radius = rng_.uniform(0.04, 0.06);
    d.height = rng_.uniform(1.0, 1.4);
    return d;
  }

  std::vector<Distractor> take() { return std::move(out_); }

 private:
  // A point beside a random boundary cone, on the side away from the track, and the outward direction there.
  std::optional<std::pair<Vec2, Vec2>> anchor_point(double min_offset, double max_offset) {
    const auto& cones = area_.cone_positions();
    if (cones.empty()) return std::nullopt;
    const auto i = static_cast<std::size_t>(rng_.uniform_int(0, static_cast<int>(cones.size()) - 1));
    const double offset = rng_.uniform(min_offset, max_offset);
    const double along = rng_.uniform(-2.0, 2.0);
    const auto outward = area_.outward_at_cone(i);
    if (!outward) return std::nullopt;
    const Vec2 tangent(-outward->y(), outward->x());
    return std::pair{cones[i] + *outward * offset + tangent * along, *outward};
  }

  bool clear_of_track(const Vec2& p, double radius, double min_offset) const {
    return area_.distance_to_boundary(p) - radius > min_offset && !area_.on_track(p);
  }

  bool clear_of_others(const Vec2& p, double radius) const {
    for (const auto& o : out_) {
      const double gap = o.type == DistractorType::Fence
                             ? (closest_point_on_segment(p, o.position, o.fence_end()) - p).norm()
                             : (o.position - p).norm() - o.footprint_radius();
      if (gap - radius < kClearance) return false;
    }
    return true;
  }

  bool fence_is_clear(const Distractor& f, double min_offset) const {
    const int samples = static_cast<int>(std::ceil(f.length / kFenceSampling));
    for (int k = 0; k <= samples; ++k) {
      const Vec2 q = f.position + (f.fence_end() - f.position) * (static_cast<double>(k) / samples);
      if (!clear_of_track(q, 0.0, min_offset) || !clear_of_others(q, 0.0)) return false;
    }
    return true;
  }

  const TrackArea& area_;
  const WorldConfig& cfg_;
  Rng rng_;
  std::vector<Distractor> out_;
};

}  // namespace

std::vector<Distractor> place_distractors(const TrackArea& area, const WorldConfig& cfg, std::uint64_t seed) {
  Placer placer(area, cfg, seed);
  if (!cfg.distractors) return {};
  if (cfg.fence) placer.fences();
  placer.round_objects(cfg.tyre_stacks, [&] { return placer.stack(); });
  placer.round_objects(cfg.tyres, [&] { return placer.tyre(); });
  placer.round_objects(cfg.posts, [&] { return placer.post(); });
  return placer.take();
}

}  // namespace fsd::sim

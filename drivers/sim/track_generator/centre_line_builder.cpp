#include "drivers/sim/track_generator/centre_line_builder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace fsd::sim {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
double mod2pi(double a) {
  a = std::fmod(a, kTwoPi);
  return a < 0 ? a + kTwoPi : a;
}
}  // namespace

CentreLineBuilder::CentreLineBuilder(const Pose2& start, double ds) : ds_(ds) {
  samples_.push_back({start.position(), start.yaw, 0.0, 0.0});
}

Pose2 CentreLineBuilder::end() const {
  const auto& b = samples_.back();
  return {b.p.x(), b.p.y(), b.heading};
}

void CentreLineBuilder::push(const Vec2& p, double heading, double kappa, double ds) {
  samples_.push_back({p, heading, kappa, samples_.back().s + ds});
}

void CentreLineBuilder::straight(double length) {
  if (length <= 0) return;
  const Pose2 e = end();
  const Vec2 dir(std::cos(e.yaw), std::sin(e.yaw));
  const int n = std::max(1, static_cast<int>(std::ceil(length / ds_)));
  const double h = length / n;
  for (int k = 1; k <= n; ++k) push(e.position() + dir * (h * k), e.yaw, 0.0, h);
}

void CentreLineBuilder::arc(double radius, double angle) {
  const double len = radius * std::fabs(angle);
  if (len <= 0) return;
  const Pose2 e = end();
  const double sign = angle > 0 ? 1.0 : -1.0;
  // Exact points on the circle (no integration error over long arcs).
  const Vec2 centre = e.position() + sign * radius * Vec2(-std::sin(e.yaw), std::cos(e.yaw));
  const int n = std::max(1, static_cast<int>(std::ceil(len / ds_)));
  for (int k = 1; k <= n; ++k) {
    const double heading = e.yaw + angle * k / n;
    const Vec2 p = centre + sign * radius * Vec2(std::sin(heading), -std::cos(heading));
    push(p, heading, sign / radius, len / n);
  }
}

void CentreLineBuilder::clothoid(double kappa0, double kappa1, double length) {
  if (length <= 0) return;
  const int n = std::max(1, static_cast<int>(std::ceil(length / ds_)));
  const double h = length / n;
  Pose2 e = end();
  Vec2 p = e.position();
  double heading = e.yaw;
  for (int k = 1; k <= n; ++k) {
    // Midpoint rule on each step: the curvature is linear, the heading quadratic.
    const double km = kappa0 + (kappa1 - kappa0) * (k - 0.5) / n;
    const double mid = heading + 0.5 * km * h;
    p += h * Vec2(std::cos(mid), std::sin(mid));
    heading += km * h;
    push(p, heading, kappa0 + (kappa1 - kappa0) * static_cast<double>(k) / n, h);
  }
}

std::vector<std::size_t> CentreLineBuilder::slalom(double half_period, int half_periods, double amplitude, int side) {
  // Local frame: x along the start heading, y = -side·A·(1 - cos(πx/d)); a whole number of steps per half
  // period puts a sample on each extreme x = k·d.
  const Pose2 e = end();
  const double d = half_period, a = amplitude * side, w = std::numbers::pi / d;
  const double total = d * half_periods;
  const int per = std::max(1, static_cast<int>(std::ceil(d / ds_)));
  const int n = per * half_periods;
  std::vector<std::size_t> extremes;
  for (int k = 0; k <= half_periods; ++k) extremes.push_back(samples_.size() - 1 + static_cast<std::size_t>(k * per));
  Vec2 prev = e.position();
  for (int k = 1; k <= n; ++k) {
    const double x = total * k / n;
    const double y = -a * (1.0 - std::cos(w * x));
    const double dy = -a * w * std::sin(w * x), ddy = -a * w * w * std::cos(w * x);
    const Vec2 p = e.transform(Vec2(x, y));
    const double kappa = ddy / std::pow(1.0 + dy * dy, 1.5);
    push(p, e.yaw + std::atan(dy), kappa, (p - prev).norm());
    prev = p;
  }
  return extremes;
}

bool CentreLineBuilder::dubins_to(const Pose2& goal, double radius) {
  // Shkel & Lumelsky's normalised form: start at the origin heading alpha, goal at (d, 0) heading beta.
  const Pose2 s = end();
  const Vec2 delta = goal.position() - s.position();
  const double d = delta.norm() / radius;
  const double theta = mod2pi(std::atan2(delta.y(), delta.x()));
  const double alpha = mod2pi(s.yaw - theta), beta = mod2pi(goal.yaw - theta);
  const double sa = std::sin(alpha), sb = std::sin(beta), ca = std::cos(alpha), cb = std::cos(beta);
  const double cab = std::cos(alpha - beta);
  struct Word {
    std::array<int, 3> turn;  // +1 left, -1 right, 0 straight (middle only)
    std::array<double, 3> len;
    bool ok = false;
  };
  std::array<Word, 6> words;
  // LSL
  {
    const double p2 = 2 + d * d - 2 * cab + 2 * d * (sa - sb);
    if (p2 >= 0) {
      const double tmp = std::atan2(cb - ca, d + sa - sb);
      words[0] = {{1, 0, 1}, {mod2pi(tmp - alpha), std::sqrt(p2), mod2pi(beta - tmp)}, true};
    }
  }
  // RSR
  {
    const double p2 = 2 + d * d - 2 * cab + 2 * d * (sb - sa);
    if (p2 >= 0) {
      const double tmp = std::atan2(ca - cb, d - sa + sb);
      words[1] = {{-1, 0, -1}, {mod2pi(alpha - tmp), std::sqrt(p2), mod2pi(tmp - beta)}, true};
    }
  }
  // LSR
  {
    const double p2 = -2 + d * d + 2 * cab + 2 * d * (sa + sb);
    if (p2 >= 0) {
      const double p = std::sqrt(p2);
      const double tmp = std::atan2(-ca - cb, d + sa + sb) - std::atan2(-2.0, p);
      words[2] = {{1, 0, -1}, {mod2pi(tmp - alpha), p, mod2pi(tmp - beta)}, true};
    }
  }
  // RSL
  {
    const double p2 = -2 + d * d + 2 * cab - 2 * d * (sa + sb);
    if (p2 >= 0) {
      const double p = std::sqrt(p2);
      const double tmp = std::atan2(ca + cb, d - sa - sb) - std::atan2(2.0, p);
      words[3] = {{-1, 0, 1}, {mod2pi(alpha - tmp), p, mod2pi(beta - tmp)}, true};
    }
  }
  // RLR
  {
    const double tmp = (6.0 - d * d + 2 * cab + 2 * d * (sa - sb)) / 8.0;
    if (std::fabs(tmp) <= 1) {
      const double p = mod2pi(kTwoPi - std::acos(tmp));
      const double t = mod2pi(alpha - std::atan2(ca - cb, d - sa + sb) + p / 2);
      words[4] = {{-1, 1, -1}, {t, p, mod2pi(alpha - beta - t + p)}, true};
    }
  }
  // LRL
  {
    const double tmp = (6.0 - d * d + 2 * cab + 2 * d * (sb - sa)) / 8.0;
    if (std::fabs(tmp) <= 1) {
      const double p = mod2pi(kTwoPi - std::acos(tmp));
      const double t = mod2pi(-alpha - std::atan2(ca - cb, d + sa - sb) + p / 2);
      words[5] = {{1, -1, 1}, {t, p, mod2pi(beta - alpha - t + p)}, true};
    }
  }
  const Word* best = nullptr;
  double best_len = std::numeric_limits<double>::infinity();
  for (const auto& w : words) {
    if (!w.ok) continue;
    const double l = w.len[0] + w.len[1] + w.len[2];
    if (l < best_len) best_len = l, best = &w;
  }
  if (!best) return false;
  for (int k = 0; k < 3; ++k) {
    const double l = best->len[k] * radius;
    if (l < ds_) continue;  // a sliver of arc: the pieces either side join as they are
    if (best->turn[k] == 0)
      straight(l);
    else
      arc(radius, best->turn[k] * best->len[k]);
  }
  const Pose2 e = end();
  return (e.position() - goal.position()).norm() < 0.05 && std::fabs(wrap_angle(e.yaw - goal.yaw)) < 0.01;
}

}  // namespace fsd::sim

#pragma once
// A synthetic drive for the fusion tests: the truth integrated at 1 kHz from a known speed and yaw-rate profile,
// and the sensors the filters see made from it with known errors (gyro bias, optical speed scale, lever arm,
// GNSS noise), all from one seeded generator.
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "localization/fusion/measurements.hpp"

namespace fsd::fusion::test {

struct TruthSample {
  Stamp t;
  Pose2 pose;
  double v, r;  // forward speed (no sideslip) and yaw rate at the reference point
  double travelled;
};

struct SyntheticDrive {
  double start_yaw = 0.7;
  double stand_s = 10.0;  // standing still first
  double duration_s = 130.0;
  double gyro_bias = 0.01;    // rad/s
  double gyro_noise = 0.003;  // rad/s
  double speed_scale = 1.02;  // optical reading / truth
  double speed_noise = 0.03;  // m/s
  Vec2 lever{-0.41, 0.27};
  double gnss_sigma = 0.3;  // m, white
  unsigned seed = 7;
  std::function<double(double)> speed = [](double t) { return t < 10 ? 0.0 : std::min(10.0, (t - 10) * 2.0); };
  std::function<double(double)> yaw_rate = [](double t) { return t < 12 ? 0.0 : 0.35 * std::sin(0.15 * (t - 12)); };
  // GNSS fix at time t: return false to drop it, or change it (jumps).
  std::function<bool(GnssFix&)> gnss_filter = [](GnssFix&) { return true; };

  std::vector<TruthSample> truth;
  std::vector<Measurement> measurements;  // in time order

  void generate() {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n01(0.0, 1.0);
    truth.clear();
    measurements.clear();
    Pose2 p{0, 0, start_yaw};
    double travelled = 0;
    const double dt = 0.001;
    const int n = static_cast<int>(duration_s / dt);
    for (int i = 0; i <= n; ++i) {
      const double t = 1000.0 + i * dt;
      const double rel = i * dt;
      const double v = speed(rel), r = yaw_rate(rel) * (v > 0 ? 1.0 : 0.0);
      truth.push_back({t, p, v, r, travelled});
      if (i % 5 == 0) {  // 200 Hz gyro
        ImuSample s{t, Vec3(0, 0, r + gyro_bias + gyro_noise * n01(rng)), Vec3(0, 0, 9.81)};
        measurements.emplace_back(s);
      }
      if (i % 4 == 2) {  // 250 Hz optical at the lever arm: v + r × lever, scaled
        BodySpeed b;
        b.t = t;
        b.lever = lever;
        const double sx = v - r * lever.y(), sy = r * lever.x();
        b.vx = speed_scale * sx + (v > 0 ? speed_noise * n01(rng) : 0.0);
        b.vy = speed_scale * sy + (v > 0 ? speed_noise * n01(rng) : 0.0);
        measurements.emplace_back(b);
      }
      if (i % 100 == 50) {  // 10 Hz GNSS
        GnssFix f;
        f.t = t;
        f.position = Vec2(p.x + gnss_sigma * n01(rng), p.y + gnss_sigma * n01(rng));
        f.fix_quality = 4;
        f.sigma = gnss_sigma;
        if (gnss_filter(f)) measurements.emplace_back(f);
      }
      const double ym = p.yaw + 0.5 * r * dt;
      p.x += v * std::cos(ym) * dt;
      p.y += v * std::sin(ym) * dt;
      p.yaw = wrap_angle(p.yaw + r * dt);
      travelled += v * dt;
    }
  }
  const TruthSample& at(Stamp t) const {
    const auto i = static_cast<std::size_t>(std::lround((t - 1000.0) / 0.001));
    return truth[std::min(i, truth.size() - 1)];
  }
};

}  // namespace fsd::fusion::test

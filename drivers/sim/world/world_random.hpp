#pragma once
// Seeded randomness of the virtual world. Everything is derived from 64-bit hashes with our own conversions (not
// <random>'s distributions, whose output differs between standard libraries), so a seed gives the same world and
// the same sensor noise on every build. Stateless hashes let a sensor draw the noise of firing N without replaying
// the draws before it, so the output does not depend on how the simulation is chunked.
#include <cmath>
#include <cstdint>
#include <numbers>

namespace fsd::sim {

// SplitMix64 finaliser: a good 64-bit mixer.
inline constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

inline constexpr std::uint64_t hash64(std::uint64_t a, std::uint64_t b) { return mix64(a ^ mix64(b)); }
inline constexpr std::uint64_t hash64(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  return hash64(hash64(a, b), c);
}

// One mix for a point of an integer lattice (cheaper than chaining hash64 for noise evaluated per ray).
inline constexpr std::uint64_t lattice_hash(std::uint64_t seed, std::int64_t i, std::int64_t j) {
  return mix64(seed ^ (static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull) ^
               (static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4Full));
}

// Uniform in [0, 1) from the top 53 bits.
inline constexpr double unit_double(std::uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

// Standard normal from two hashes (Box-Muller).
inline double normal_from(std::uint64_t h1, std::uint64_t h2) {
  const double u1 = 1.0 - unit_double(h1);  // (0, 1]
  const double u2 = unit_double(h2);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

// Sequential generator for one-off placement (distractors).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(mix64(seed ^ 0x5EEDF00Dull)) {}
  std::uint64_t next() { return mix64(state_ += 0x9E3779B97F4A7C15ull); }
  double uniform() { return unit_double(next()); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  int uniform_int(int lo, int hi_inclusive) {
    return lo + static_cast<int>(uniform() * static_cast<double>(hi_inclusive - lo + 1));
  }
  bool chance(double p) { return uniform() < p; }

 private:
  std::uint64_t state_;
};

// Smooth value noise in [-1, 1]: hashed lattice values at spacing `cell` (m), bilinear with smoothstep weights.
inline double value_noise(std::uint64_t seed, double x, double y, double cell) {
  const double fx = x / cell, fy = y / cell;
  const double x0 = std::floor(fx), y0 = std::floor(fy);
  const auto ix = static_cast<std::int64_t>(x0), iy = static_cast<std::int64_t>(y0);
  auto lattice = [&](std::int64_t i, std::int64_t j) { return 2.0 * unit_double(lattice_hash(seed, i, j)) - 1.0; };
  auto smooth = [](double t) { return t * t * (3.0 - 2.0 * t); };
  const double sx = smooth(fx - x0), sy = smooth(fy - y0);
  const double a = lattice(ix, iy) + sx * (lattice(ix + 1, iy) - lattice(ix, iy));
  const double b = lattice(ix, iy + 1) + sx * (lattice(ix + 1, iy + 1) - lattice(ix, iy + 1));
  return a + sy * (b - a);
}

}  // namespace fsd::sim

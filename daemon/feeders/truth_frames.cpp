#include "daemon/feeders/truth_frames.hpp"

#include <bit>
#include <cmath>
#include <cstring>

namespace fsd {

namespace {

static_assert(std::endian::native == std::endian::little, "truth frames are written in the host's byte order");

constexpr std::uint8_t kVersion = 1;
constexpr std::size_t kStateSize = 2 + 10 * 8 + 4 + 1;
constexpr std::size_t kConeSize = 3 * 8 + 1 + 4;
constexpr std::size_t kReturnsSize = 4 + 4 + 8;

template <class T>
void put(std::vector<std::uint8_t>& out, T v) {
  const std::size_t at = out.size();
  out.resize(at + sizeof v);
  std::memcpy(out.data() + at, &v, sizeof v);
}

template <class T>
T get(std::span<const std::uint8_t> b, std::size_t& at) {
  T v;
  std::memcpy(&v, b.data() + at, sizeof v);
  at += sizeof v;
  return v;
}

}  // namespace

std::vector<std::uint8_t> encode_truth_state(const TruthStateFrame& f) {
  std::vector<std::uint8_t> out;
  out.reserve(kStateSize);
  put<std::uint8_t>(out, kVersion);
  put<std::uint8_t>(out, f.planner_stalled ? 1 : 0);
  const VehicleState& s = f.state;
  for (double v : {s.stamp, s.pose.x, s.pose.y, s.pose.yaw, s.vx, s.vy, s.yaw_rate, s.ax, s.ay, s.steering})
    put<double>(out, v);
  put<std::uint32_t>(out, f.cones_hit);
  put<std::uint8_t>(out, static_cast<std::uint8_t>(f.as_state));
  return out;
}

std::optional<TruthStateFrame> decode_truth_state(std::span<const std::uint8_t> b) {
  if (b.size() != kStateSize || b[0] != kVersion || b[1] > 1) return std::nullopt;
  std::size_t at = 2;
  double v[10];
  for (double& x : v) {
    x = get<double>(b, at);
    if (!std::isfinite(x)) return std::nullopt;
  }
  TruthStateFrame f;
  f.planner_stalled = b[1] == 1;
  f.cones_hit = get<std::uint32_t>(b, at);
  const auto as = get<std::uint8_t>(b, at);
  if (as > static_cast<std::uint8_t>(AsState::Finished)) return std::nullopt;
  f.as_state = static_cast<AsState>(as);
  VehicleState& s = f.state;
  s.stamp = v[0];
  s.pose = Pose2{v[1], v[2], v[3]};
  s.vx = v[4];
  s.vy = v[5];
  s.yaw_rate = v[6];
  s.ax = v[7];
  s.ay = v[8];
  s.steering = v[9];
  return f;
}

std::vector<std::uint8_t> encode_truth_cones(const std::vector<Cone>& cones) {
  std::vector<std::uint8_t> out;
  out.reserve(5 + cones.size() * kConeSize);
  put<std::uint8_t>(out, kVersion);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(cones.size()));
  for (const auto& c : cones) {
    for (int i = 0; i < 3; ++i) put<double>(out, c.position[i]);
    put<std::uint8_t>(out, static_cast<std::uint8_t>(c.colour));
    put<std::uint32_t>(out, c.id);
  }
  return out;
}

std::optional<std::vector<Cone>> decode_truth_cones(std::span<const std::uint8_t> b, std::size_t max_cones) {
  if (b.size() < 5 || b[0] != kVersion) return std::nullopt;
  std::size_t at = 1;
  const auto n = get<std::uint32_t>(b, at);
  if (n > max_cones || b.size() != 5 + static_cast<std::size_t>(n) * kConeSize) return std::nullopt;
  std::vector<Cone> cones(n);
  for (auto& c : cones) {
    for (int i = 0; i < 3; ++i) {
      c.position[i] = get<double>(b, at);
      if (!std::isfinite(c.position[i])) return std::nullopt;
    }
    const auto colour = get<std::uint8_t>(b, at);
    if (colour > static_cast<std::uint8_t>(ConeColour::Red)) return std::nullopt;
    c.colour = static_cast<ConeColour>(colour);
    c.id = get<std::uint32_t>(b, at);
  }
  return cones;
}

std::vector<std::uint8_t> encode_truth_lidar_returns(const std::vector<TruthLidarReturns>& returns) {
  std::vector<std::uint8_t> out;
  out.reserve(5 + returns.size() * kReturnsSize);
  put<std::uint8_t>(out, kVersion);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(returns.size()));
  for (const auto& r : returns) {
    put<std::uint32_t>(out, r.id);
    put<std::uint32_t>(out, r.returns);
    put<double>(out, r.t);
  }
  return out;
}

std::optional<std::vector<TruthLidarReturns>> decode_truth_lidar_returns(std::span<const std::uint8_t> b,
                                                                         std::size_t max_cones) {
  if (b.size() < 5 || b[0] != kVersion) return std::nullopt;
  std::size_t at = 1;
  const auto n = get<std::uint32_t>(b, at);
  if (n > max_cones || b.size() != 5 + static_cast<std::size_t>(n) * kReturnsSize) return std::nullopt;
  std::vector<TruthLidarReturns> out(n);
  for (auto& r : out) {
    r.id = get<std::uint32_t>(b, at);
    r.returns = get<std::uint32_t>(b, at);
    r.t = get<double>(b, at);
    if (r.id == 0 || r.returns == 0 || !std::isfinite(r.t)) return std::nullopt;
  }
  return out;
}

}  // namespace fsd

// libFuzzer target for the simulator's truth frames as a recording carries them (daemon/feeders/truth_frames):
// the true state, the standing cones and the LiDAR's per-cone returns, which the replayer decodes for its
// scorecard. Byte 0 picks the decoder, the rest is the frame.
// Invariants beyond "no crash": the layouts are canonical, so every accepted frame re-encodes to exactly its
// bytes; every decoded number is finite; ids and counts of the returns are never zero.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "daemon/feeders/truth_frames.hpp"

namespace {

void check(bool ok) {
  if (!ok) std::abort();
}

bool same(std::span<const std::uint8_t> a, const std::vector<std::uint8_t>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::span<const std::uint8_t> frame(data + 1, size - 1);
  switch (data[0] % 3) {
    case 0:
      if (const auto s = fsd::decode_truth_state(frame)) {
        check(std::isfinite(s->state.stamp) && std::isfinite(s->state.pose.x) && std::isfinite(s->state.pose.yaw));
        check(same(frame, fsd::encode_truth_state(*s)));
      }
      break;
    case 1:
      if (const auto c = fsd::decode_truth_cones(frame, 1000)) {
        check(c->size() <= 1000);
        for (const auto& cone : *c) check(cone.position.allFinite());
        check(same(frame, fsd::encode_truth_cones(*c)));
      }
      break;
    default:
      if (const auto r = fsd::decode_truth_lidar_returns(frame, 1000)) {
        check(r->size() <= 1000);
        for (const auto& e : *r) check(e.id != 0 && e.returns != 0 && std::isfinite(e.t));
        check(same(frame, fsd::encode_truth_lidar_returns(*r)));
      }
  }
  return 0;
}

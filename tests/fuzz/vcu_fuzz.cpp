// libFuzzer target for the VCU frame decoder (common/wire/vcu_protocol). Links: fsd_common.
// The first input byte picks the chunk size the rest is fed in, so the resynchronisation paths see every split.
// Invariants checked beyond "no crash": every accepted message re-encodes to a frame that decodes to the same
// fields, and the decoder's buffer stays bounded.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <type_traits>

#include "common/wire/vcu_protocol.hpp"

namespace {

using namespace fsd::wire::vcu;

bool same(const Command& a, const Command& b) {
  return a.steering == b.steering && a.target_speed == b.target_speed && a.brake_hard == b.brake_hard &&
         a.as_request == b.as_request && a.mission == b.mission;
}
bool same(const fsd::VcuStatus& a, const fsd::VcuStatus& b) {
  return a.as_state == b.as_state && a.mission == b.mission && a.res_go == b.res_go &&
         a.res_emergency == b.res_emergency && a.ebs_active == b.ebs_active &&
         a.steering_measured == b.steering_measured && a.wheel_speeds == b.wheel_speeds && a.faults == b.faults;
}

template <class Msg>
void check_round_trip(const Msg& m, std::uint16_t seq) {
  int delivered = 0;
  Decoder again({[&](const Command& c, std::uint16_t s) {
                   if constexpr (std::is_same_v<Msg, Command>) delivered += same(c, m) && s == seq;
                 },
                 [&](const fsd::VcuStatus& st, std::uint16_t s) {
                   if constexpr (std::is_same_v<Msg, fsd::VcuStatus>) delivered += same(st, m) && s == seq;
                 },
                 nullptr});
  again.feed(encode(m, seq));
  if (delivered != 1) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t chunk = 1 + data[0] % 64;
  std::span<const std::uint8_t> rest(data + 1, size - 1);
  Decoder d({[](const Command& c, std::uint16_t s) { check_round_trip(c, s); },
             [](const fsd::VcuStatus& st, std::uint16_t s) { check_round_trip(st, s); }, nullptr},
            DecoderConfig{.restart_after = 1 + data[0] / 64});
  std::size_t fed = 0;
  while (!rest.empty()) {
    const std::size_t n = std::min(chunk, rest.size());
    d.feed(rest.first(n));
    rest = rest.subspan(n);
    fed += n;
    if (d.buffered() > kMaxFrameSize + 256) std::abort();
    if (fed % 997 < n) d.reset();  // an occasional port reopen
  }
  return 0;
}

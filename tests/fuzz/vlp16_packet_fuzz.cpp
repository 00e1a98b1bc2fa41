// libFuzzer target: arbitrary bytes as a VLP-16 data packet (decoder, then the whole scan builder) and as a
// position packet. Besides the sanitizers it checks what the decoder promises for every accepted packet.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "drivers/vlp16/decoder.hpp"
#include "drivers/vlp16/position_packet.hpp"
#include "drivers/vlp16/scan_builder.hpp"

namespace {

void require(bool ok) {
  if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fsd;
  static const LaserTable lasers = LaserTable::builtin();
  static PacketDecoder decoder(lasers, 0.5, 130.0);
  static Vlp16ScanBuilder builder(Vlp16Config{}, lasers, [](Scan&& s) {
    require(!s.points.empty());
    for (const auto& p : s.points) require(std::isfinite(p.t) && std::isfinite(p.x));
  });
  static std::vector<Vlp16Return> out;
  static double receive = 0;
  const std::span<const std::uint8_t> bytes(data, size);

  out.clear();
  PacketHeader h;
  const auto status = decoder.decode(bytes, out, &h);
  require(status == PacketStatus::Ok || out.empty());
  for (const auto& r : out) {
    require(r.azimuth_deg >= 0.0 && r.azimuth_deg < 360.0);
    require(r.distance_m >= 0.5 && r.distance_m <= 130.0);
    require(std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.z));
    require(std::abs(std::hypot(r.x, r.y, r.z - lasers[r.laser].vertical_offset) - r.distance_m) < 1e-6);
    require(r.firing_offset_us >= 0.0 && r.firing_offset_us < h.duration_us());
    require(r.laser < 16 && r.ring < 16);
  }

  receive += 1.327e-3;
  builder.on_data_packet(receive, bytes);

  PositionPacket p;
  if (parse_position_packet(bytes, p) == PositionStatus::Ok) {
    require(p.nmea.size() <= 128);
    require(p.nmea_state != NmeaState::Valid || nmea_checksum_ok(p.nmea));
  }
  return 0;
}

#include "drivers/vlp16/decoder.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace fsd {

namespace w = wire::vlp16;

std::string_view to_string(PacketStatus s) {
  switch (s) {
    case PacketStatus::Ok:
      return "ok";
    case PacketStatus::WrongSize:
      return "wrong size";
    case PacketStatus::BadFlag:
      return "bad block flag";
    case PacketStatus::BadAzimuth:
      return "azimuth out of range";
    case PacketStatus::UnknownReturnMode:
      return "unknown return mode";
    case PacketStatus::UnknownProduct:
      return "unknown product id";
  }
  return "?";
}

bool PacketHeader::dual() const { return return_mode == w::kReturnDual; }

double PacketHeader::duration_us() const {
  return static_cast<double>(dual() ? w::kBlocks / 2 : w::kBlocks) * w::kBlockPeriodUs;
}

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr std::uint16_t kAzimuthCounts = 36000;  // 0.01° per count
constexpr double kCountsPerDeg = 1.0 / w::kAzimuthUnitDeg;

struct SinCos {
  double s, c;
};

// sin/cos of (base + d) for |d| below ~0.03 rad by the angle-sum formula with a 5th-order series of d:
// error < 1e-12, and the decoder needs only one libm call per firing instead of one per laser.
SinCos rotate_small(SinCos base, double d) {
  const double d2 = d * d;
  const double sd = d * (1.0 - d2 / 6.0 * (1.0 - d2 / 20.0));
  const double cd = 1.0 - d2 / 2.0 * (1.0 - d2 / 12.0);
  return {base.s * cd + base.c * sd, base.c * cd - base.s * sd};
}
constexpr double kSmallRotationLimit = 2.0 * kDegToRad;  // per firing; the sensor turns 0.4° at 10 Hz, 0.8° at 20 Hz

std::uint16_t azimuth_counts(std::span<const std::uint8_t> p, std::size_t block) {
  return w::read_u16(p, block * w::kBlockSize + 2);
}

}  // namespace

PacketDecoder::PacketDecoder(LaserTable table, double min_range, double max_range)
    : table_(table), min_range_(min_range), max_range_(max_range) {
  // Firing time of each channel within its firing, and the fraction of the firing's rotation done by then.
  for (std::size_t c = 0; c < kChannels; ++c) {
    const std::size_t seq = c / w::kLasers, laser = c % w::kLasers;
    in_firing_us_[c] = static_cast<double>(seq) * w::kSequencePeriodUs + table_[laser].firing_slot * w::kFiringPeriodUs;
    fraction_[c] = in_firing_us_[c] / w::kBlockPeriodUs;
  }
  if (!(min_range >= 0.0 && min_range < max_range))
    throw std::invalid_argument("vlp16: need 0 <= min_range < max_range, got " + std::to_string(min_range) + " and " +
                                std::to_string(max_range));
}

PacketStatus PacketDecoder::check(std::span<const std::uint8_t> p, PacketHeader& header) {
  if (p.size() != w::kPacketSize) return PacketStatus::WrongSize;
  for (std::size_t b = 0; b < w::kBlocks; ++b) {
    if (p[b * w::kBlockSize] != w::kFlag0 || p[b * w::kBlockSize + 1] != w::kFlag1) return PacketStatus::BadFlag;
    if (azimuth_counts(p, b) >= kAzimuthCounts) return PacketStatus::BadAzimuth;
  }
  const auto mode = p[w::kReturnModeOffset];
  if (mode != w::kReturnStrongest && mode != w::kReturnLast && mode != w::kReturnDual)
    return PacketStatus::UnknownReturnMode;
  const auto product = p[w::kProductOffset];
  if (product != w::kProductVlp16 && product != w::kProductEarlyFirmware) return PacketStatus::UnknownProduct;
  header.timestamp_us = w::read_u32(p, w::kTimestampOffset);
  header.return_mode = mode;
  header.product = product;
  return PacketStatus::Ok;
}

void PacketDecoder::count_rejection(PacketStatus s) {
  switch (s) {
    case PacketStatus::Ok:
      break;
    case PacketStatus::WrongSize:
      ++counters_.wrong_size;
      break;
    case PacketStatus::BadFlag:
      ++counters_.bad_flag;
      break;
    case PacketStatus::BadAzimuth:
      ++counters_.bad_azimuth;
      break;
    case PacketStatus::UnknownReturnMode:
      ++counters_.unknown_return_mode;
      break;
    case PacketStatus::UnknownProduct:
      ++counters_.unknown_product;
      break;
  }
}

PacketStatus PacketDecoder::decode(std::span<const std::uint8_t> p, std::vector<Vlp16Return>& out,
                                   PacketHeader* header_out) {
  PacketHeader h;
  const auto status = check(p, h);
  if (status != PacketStatus::Ok) {
    count_rejection(status);
    return status;
  }
  ++counters_.packets;
  if (header_out) *header_out = h;

  // A firing is one block (single return) or a pair of blocks with the same azimuth (dual: last, strongest).
  const std::size_t blocks_per_firing = h.dual() ? 2 : 1;
  const std::size_t firings = w::kBlocks / blocks_per_firing;
  const ReturnKind single_kind = h.return_mode == w::kReturnLast ? ReturnKind::Last : ReturnKind::Strongest;
  const double t0 = static_cast<double>(h.timestamp_us);

  int step_counts = 0;  // azimuth advance per firing, 0.01°
  for (std::size_t f = 0; f < firings; ++f) {
    const std::size_t block = f * blocks_per_firing;
    const int az = azimuth_counts(p, block);
    // Rotation during this firing = azimuth of the next firing minus this one, modulo the 360° wrap; the last
    // firing of the packet reuses the previous firing's step.
    if (f + 1 < firings)
      step_counts = (azimuth_counts(p, block + blocks_per_firing) - az + kAzimuthCounts) % kAzimuthCounts;
    // Division rather than × 0.01: whole and hundredth degrees come out exact (frames cut at 90.00° cut there).
    const double base_deg = az / kCountsPerDeg;
    const double step_deg = step_counts / kCountsPerDeg;
    const SinCos base{std::sin(base_deg * kDegToRad), std::cos(base_deg * kDegToRad)};
    const bool small_step = step_deg * kDegToRad < kSmallRotationLimit;
    const double firing_start_us = static_cast<double>(f) * w::kBlockPeriodUs;

    for (std::size_t channel = 0; channel < kChannels; ++channel) {
      const std::size_t seq = channel / w::kLasers, laser = channel % w::kLasers;
      const LaserCalibration& cal = table_[laser];

      // Reads one echo; geometry only for the ones kept (a third of a typical packet has no echo).
      const auto emit = [&](std::size_t blk, ReturnKind kind) {
        const std::size_t at = w::channel_offset(blk, seq, laser);
        const std::uint16_t raw = w::read_u16(p, at);
        if (raw == 0) {
          ++counters_.no_return;
          return;
        }
        const double d = raw * w::kDistanceUnit;
        if (d < min_range_ || d > max_range_) {
          ++counters_.out_of_range;
          return;
        }
        const double delta_deg = step_deg * fraction_[channel];
        double azimuth_deg = base_deg + delta_deg;
        if (azimuth_deg >= 360.0) azimuth_deg -= 360.0;
        const SinCos sc = small_step ? rotate_small(base, delta_deg * kDegToRad)
                                     : SinCos{std::sin(azimuth_deg * kDegToRad), std::cos(azimuth_deg * kDegToRad)};
        const double firing_offset_us = firing_start_us + in_firing_us_[channel];
        Vlp16Return& r = out.emplace_back();
        r.t_us = t0 + firing_offset_us;
        r.firing_offset_us = firing_offset_us;
        r.azimuth_deg = azimuth_deg;
        r.distance_m = d;
        const double horizontal = d * cal.cos_elevation;
        r.x = horizontal * sc.c;
        r.y = -horizontal * sc.s;
        r.z = d * cal.sin_elevation + cal.vertical_offset;
        r.laser = static_cast<std::uint8_t>(laser);
        r.intensity = p[at + 2];
        r.ring = cal.ring;
        r.kind = kind;
        ++counters_.returns;
      };

      if (!h.dual()) {
        emit(block, single_kind);
        continue;
      }
      // Dual: the first block of the pair holds the last echo, the second the strongest. Identical echoes
      // (same distance and reflectivity) are one return.
      const std::size_t last_at = w::channel_offset(block, seq, laser);
      const std::size_t strongest_at = w::channel_offset(block + 1, seq, laser);
      const bool same = p[last_at] == p[strongest_at] && p[last_at + 1] == p[strongest_at + 1] &&
                        p[last_at + 2] == p[strongest_at + 2];
      if (same && w::read_u16(p, last_at) != 0) {
        ++counters_.dual_duplicates;
        emit(block, ReturnKind::StrongestAndLast);
      } else {
        emit(block, ReturnKind::Last);
        emit(block + 1, ReturnKind::Strongest);
      }
    }
  }
  return PacketStatus::Ok;
}

}  // namespace fsd

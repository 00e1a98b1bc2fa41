#include "drivers/vlp16/scan_builder.hpp"

#include <cmath>

#include "common/wire/vlp16_format.hpp"

namespace fsd {

Vlp16ScanBuilder::Vlp16ScanBuilder(const Vlp16Config& config, ScanHandler on_scan)
    : Vlp16ScanBuilder(config, LaserTable::load(config.laser_table), std::move(on_scan)) {}

Vlp16ScanBuilder::Vlp16ScanBuilder(const Vlp16Config& config, LaserTable table, ScanHandler on_scan)
    : decoder_(table, config.min_range, config.max_range), frames_(config.frame_cut_deg), on_scan_(std::move(on_scan)) {
  returns_.reserve(2 * wire::vlp16::kBlocks * wire::vlp16::kSequencesPerBlock * wire::vlp16::kLasers);
}

void Vlp16ScanBuilder::count_gap(const PacketHeader& h) {
  if (have_last_ && last_.return_mode == h.return_mode) {
    constexpr double kHourUs = 3.6e9;
    double gap = static_cast<double>(h.timestamp_us) - static_cast<double>(last_.timestamp_us);
    if (gap < -kHourUs / 2) gap += kHourUs;
    const double period = h.duration_us();
    // Only plausible gaps (< 1 s) count; larger steps are clock changes, not losses.
    if (gap > 1.5 * period && gap < 1e6) lost_packets_ += static_cast<std::uint64_t>(std::lround(gap / period)) - 1;
  }
  have_last_ = true;
  last_ = h;
}

PacketStatus Vlp16ScanBuilder::on_data_packet(Stamp receive, std::span<const std::uint8_t> payload) {
  returns_.clear();
  PacketHeader h;
  const auto status = decoder_.decode(payload, returns_, &h);
  if (status != PacketStatus::Ok) return status;
  count_gap(h);
  const Stamp start = clock_.packet_start(receive, h.timestamp_us, h.duration_us());
  frames_.add(start, returns_, on_scan_);
  return status;
}

void Vlp16ScanBuilder::flush() { frames_.flush(on_scan_); }

}  // namespace fsd

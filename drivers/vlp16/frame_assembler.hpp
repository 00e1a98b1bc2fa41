#pragma once
// Cuts the stream of returns into frames (Scan): a frame ends where the azimuth crosses the cut angle.
//
// The cut is decided per return, so a frame holds exactly one revolution from the cut angle on, whatever the
// packet boundaries. After a cut the next one is armed only once the azimuth has moved a quarter turn away from
// the cut angle, so encoder jitter or a reordered packet around the cut never yields a sliver frame. The first
// frame of a stream is partial unless the stream starts just after the cut angle. A frame is also cut when it
// reaches `max_points` (motor stopped: the azimuth never crosses), which bounds memory.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

#include "common/types.hpp"
#include "drivers/vlp16/decoder.hpp"

namespace fsd {

class FrameAssembler {
 public:
  using ScanHandler = std::function<void(Scan&&)>;
  // Dual return at 5 Hz is 116 k returns per revolution.
  static constexpr std::size_t kDefaultMaxPoints = 150'000;

  explicit FrameAssembler(double cut_deg, std::size_t max_points = kDefaultMaxPoints);

  // Adds the returns of one packet whose first firing is at `packet_start` (stack clock); calls `emit` for every
  // completed frame. Point.t = packet_start + firing offset.
  void add(Stamp packet_start, std::span<const Vlp16Return> returns, const ScanHandler& emit);
  // Emits the frame in progress, if it has points (end of a file, shutdown).
  void flush(const ScanHandler& emit);

  std::uint64_t frames() const { return seq_; }
  std::uint64_t forced_cuts() const { return forced_cuts_; }

 private:
  void cut(const ScanHandler& emit);
  double cut_deg_;
  std::size_t max_points_;
  Scan current_;
  bool have_prev_ = false;
  bool armed_ = false;
  double prev_rel_ = 0;  // azimuth of the previous return relative to the cut angle, [0, 360)
  std::uint32_t seq_ = 0;
  std::uint64_t forced_cuts_ = 0;
};

}  // namespace fsd

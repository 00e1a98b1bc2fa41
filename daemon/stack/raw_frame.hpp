#pragma once
// The Stack's one input (DESIGN.md §3): a raw frame exactly as it arrived from a device, stamped with its receive
// time on the run's clock. The car's driver threads, the virtual car's lockstep loop and the MCAP replayer all
// hand frames to Stack::feed through this; the recorder taps the same frames, so a recording replays through the
// very same decoders. In simulator runs the ground truth (the true state and cones, for the truth sources and the
// scorecard) travels the same way, so that a recording of a simulated run replays against its own truth.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>

#include "common/time.hpp"
#include "common/types.hpp"
#include "common/wire/vcu_protocol.hpp"

namespace fsd {

struct TelemetrySnapshot;
struct ParamChange;

enum class RawChannel : std::uint8_t {
  Vlp16Data = 0,          // VLP-16 data packet (UDP 2368 payload, 1206 bytes)
  Vlp16Position = 1,      // VLP-16 position packet (UDP 8308 payload, 512 bytes)
  Nmea = 2,               // GNSS-INS serial bytes, any chunking
  Camera = 3,             // one JPEG frame
  VcuRx = 4,              // VCU protocol bytes from the VCU
  VcuTx = 5,              // VCU protocol bytes to the VCU (recorded, never fed)
  TruthState = 6,         // simulator: the true vehicle state (truth_frames.hpp)
  TruthCones = 7,         // simulator: the standing cones, when they change
  TruthScan = 8,          // simulator without a simulated LiDAR: the ideal detector's scan tick
  TruthLidarReturns = 9,  // simulator: the returns its LiDAR sent from each cone (the scorecard's, unused by the stack)
};
inline constexpr int kRawChannels = 10;
std::string_view to_string(RawChannel c);
std::optional<RawChannel> raw_channel_from_string(std::string_view s);

struct RawFrame {
  RawChannel channel = RawChannel::Nmea;
  Stamp t = 0;  // receive time on the run's clock
  std::span<const std::uint8_t> bytes;
};

// Sees every frame the Stack takes, every control cycle and its output, in the order the Stack takes them (the recorder).
// Called on the Stack's thread: must not block (hand over to a bounded queue).
class StackTap {
 public:
  virtual ~StackTap() = default;
  virtual void on_frame(const RawFrame& frame) = 0;
  virtual void on_cycle(Stamp now) = 0;
  // At the end of that cycle: the command and AS request it handed to the VCU session (the replay compares them).
  virtual void on_output(Stamp /*now*/, const ControlCommand& /*command*/, wire::vcu::AsRequest /*request*/) {}
  // What the Stack made of it, every 4th cycle (the dashboard's snapshot), shared and never changed afterwards;
  // only to taps that want it (building a snapshot costs: the Stack skips it when nobody does).
  virtual bool wants_snapshots() const { return false; }
  virtual void on_snapshot(const std::shared_ptr<const TelemetrySnapshot>& /*snapshot*/) {}
  // A live parameter change, in the cycle `now` that applied it.
  virtual void on_param(Stamp /*now*/, const ParamChange& /*change*/) {}
};

}  // namespace fsd

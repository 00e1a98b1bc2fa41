#pragma once
// The simulator's ground truth as raw frames (RawChannel::TruthState / TruthCones / TruthLidarReturns), so that it reaches the
// truth sources through Stack::feed like any sensor and a recording of a simulated run carries it. A small
// versioned little-endian binary layout; decoding checks every length and value (recordings are untrusted input).
//
//   TruthState: u8 version (1), u8 flags (bit 0: the planner is stalled by the fault schedule),
//               10 × f64: t, x, y, yaw, vx, vy, yaw_rate, ax, ay, steering (VehicleState, map frame),
//               u32 cones hit so far, u8 the VCU stand-in's AS state (what the scorecard judges)
//   TruthCones: u8 version (1), u32 count, count × (3 × f64 x y z, u8 colour, u32 id)
//   TruthLidarReturns: u8 version (1), u32 count, count × (u32 cone id, u32 returns, f64 t of the last return)
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/types.hpp"

namespace fsd {

struct TruthStateFrame {
  VehicleState state;
  bool planner_stalled = false;  // fault injection (sim.faults): the stack's planner produces nothing
  std::uint32_t cones_hit = 0;
  AsState as_state = AsState::Off;  // the true AS state of the simulated VCU
};

std::vector<std::uint8_t> encode_truth_state(const TruthStateFrame& f);
std::optional<TruthStateFrame> decode_truth_state(std::span<const std::uint8_t> bytes);

std::vector<std::uint8_t> encode_truth_cones(const std::vector<Cone>& cones);
// At most `max_cones` (a layout has a few hundred); nullopt for anything malformed.
std::optional<std::vector<Cone>> decode_truth_cones(std::span<const std::uint8_t> bytes,
                                                    std::size_t max_cones = 100000);

// The returns the simulated LiDAR sent from one cone (id as in TruthCones) in a stretch of firings.
struct TruthLidarReturns {
  std::uint32_t id = 0;
  std::uint32_t returns = 0;
  Stamp t = 0;
};

std::vector<std::uint8_t> encode_truth_lidar_returns(const std::vector<TruthLidarReturns>& returns);
// At most `max_cones` entries; nullopt for anything malformed (a zero count or id, a time not finite).
std::optional<std::vector<TruthLidarReturns>> decode_truth_lidar_returns(std::span<const std::uint8_t> bytes,
                                                                         std::size_t max_cones = 100000);

}  // namespace fsd

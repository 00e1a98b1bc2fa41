#pragma once
// `fsd localize --mcap FILE`: the fusion filter on a recording's raw frames (docs/localization.md). The recorded
// NMEA bytes go through the GNSS-INS driver and the recorded VCU status frames through the protocol decoder, with
// the recording's own configuration (drivers.gnss.*: its origin and lever arm; localization.fusion.*), into the
// same FusedLocalization the Stack runs as run.localization_source = fused, in arrival order, one step per
// recorded control cycle. The poses are in the run's map frame, stamped on the run's clock.
#include <cstdint>
#include <string>
#include <vector>

#include "localization/fusion/measurements.hpp"

namespace fsd {

struct McapLocalization {
  std::vector<fusion::LocalizationState> states;  // one per cycle once the filter has a pose
  std::uint64_t gnss_samples = 0, vcu_statuses = 0, cycles = 0;
};

// `filter`: empty = the recording's localization.fusion.filter. Throws mcap::McapError / RecordingError for a file
// that is no recording and ConfigError for a configuration this fsd refuses.
McapLocalization localize_recording(const std::string& file, const std::string& filter);

}  // namespace fsd

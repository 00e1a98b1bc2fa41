#include "daemon/cli/localize_mcap.hpp"

#include <nlohmann/json.hpp>

#include "common/logging.hpp"
#include "common/mcap/byte_io.hpp"
#include "common/mcap/fsd_profile.hpp"
#include "daemon/feeders/replay_run.hpp"
#include "daemon/recording/recording_reader.hpp"
#include "daemon/stack/fused_localization.hpp"
#include "drivers/gnss/gnss_driver.hpp"

namespace fsd {

McapLocalization localize_recording(const std::string& file, const std::string& filter) {
  mcap::MappedFile mapped(file);
  RecordingReader reader(mapped.bytes());
  const auto* recorded = reader.metadata(mcap::kConfigMetadata);
  if (!recorded) throw RecordingError("no " + std::string(mcap::kConfigMetadata) + " metadata: not an fsd recording");
  Config cfg = replay_config(*recorded, "", *logger("localize"));
  if (!filter.empty()) cfg.set("localization.fusion.filter", nlohmann::json(filter), "--filter");

  McapLocalization out;
  FusedLocalization fused(cfg);
  std::vector<GnssSample> pending;
  GnssDriver gnss(read_gnss_config(cfg), [&](const GnssSample& s) { pending.push_back(s); });
  std::optional<VcuStatus> status;
  Stamp rx = 0;
  wire::vcu::Decoder vcu(wire::vcu::Decoder::Handlers{nullptr,
                                                      [&](const VcuStatus& s, std::uint16_t) {
                                                        status = s;
                                                        status->stamp = rx;
                                                        ++out.vcu_statuses;
                                                      },
                                                      nullptr});
  while (const auto e = reader.next()) {
    if (e->kind == RecordingEvent::Kind::Frame) {
      rx = e->t;
      if (e->channel == RawChannel::Nmea) gnss.feed(e->bytes, e->t);
      if (e->channel == RawChannel::VcuRx) vcu.feed(e->bytes);
    } else if (e->kind == RecordingEvent::Kind::Cycle) {
      ++out.cycles;
      out.gnss_samples += pending.size();
      fused.add(pending, status);
      pending.clear();
      const auto est = fused.estimate();
      if (est.initialised && (out.states.empty() || est.stamp > out.states.back().stamp)) out.states.push_back(est);
    }
  }
  return out;
}

}  // namespace fsd

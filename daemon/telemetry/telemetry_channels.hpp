#pragma once
// The channel table: every channel the daemon publishes, declared once (topic, schema, rates, when it is sent,
// builder from a snapshot). The dashboard's Telemetry and the recording's DerivedChannels both follow it, the
// server advertises it, and the dashboard subscribes to what is advertised: adding a channel is one row here (and
// a field of TelemetrySnapshot if it needs new data).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "daemon/telemetry/telemetry.hpp"
#include "web/channels.hpp"

namespace fsd {

// What a builder makes: a payload, or (scene channels) the whole scene as entities, which the dashboard sends as
// changes (web::SceneDelta) and a recording writes whole.
struct ChannelPayload {
  std::string json;
  std::optional<std::vector<nlohmann::json>> entities;
};

struct ChannelUse {
  web::CarShape car;
  bool recording = false;  // the recording's variant (e.g. a thinner point cloud)
};

struct TelemetryChannel {
  web::ChannelSpec spec = {};
  bool truth = false;  // the simulator's ground truth: only in sim runs' dashboards, never recorded
  // Rates: the dashboard's in wall time (smooth over Wi-Fi also while a headless run races), the recording's on
  // the run's clock. 0: only when `changed` says so; nullopt: never (not published / not recorded).
  std::optional<double> live_hz = {}, record_hz = {};
  // Sent only when the data is new: its identity in the snapshot (a pointer), null when there is none.
  std::function<std::shared_ptr<const void>(const TelemetrySnapshot&)> source = {};
  // Sent at once, whatever the rate, when this key changes (the AS state, the newest fault).
  std::function<std::string(const TelemetrySnapshot&)> changed = {};
  // nullopt: nothing to send for this snapshot. Without a builder the channel is fed elsewhere (the log's sink).
  std::function<std::optional<ChannelPayload>(const TelemetrySnapshot&, const ChannelUse&)> build = {};
};

// Every channel, in the order advertised.
const std::vector<TelemetryChannel>& telemetry_channels();
// The specs of the rows that pass `keep`.
std::vector<web::ChannelSpec> channel_specs(const std::function<bool(const TelemetryChannel&)>& keep);

// When each row of the table is due, on one time line (wall seconds or the run's clock): a row with a source when its
// data is new and its rate allows, a periodic row at its rate and at once when its `changed` key moves.
class ChannelPacer {
 public:
  // `rate` picks the row's rate (live or recorded); rows whose rate is nullopt or that fail `use` are never due.
  ChannelPacer(const std::vector<TelemetryChannel>& rows,
               std::function<std::optional<double>(const TelemetryChannel&)> rate,
               std::function<bool(const TelemetryChannel&)> use = {});
  // The indexes of the rows due at `now` for snapshot `s`. `fresh`: `s` was not seen before (otherwise only rows
  // whose data is still unsent are considered).
  std::vector<std::size_t> due(const TelemetrySnapshot& s, double now, bool fresh = true);

 private:
  struct Row {
    bool active = false;
    double period = 0;  // 0: never by rate
    double next = 0;
    std::shared_ptr<const void> last_source;
    std::optional<std::string> last_key;
  };
  const std::vector<TelemetryChannel>& rows_;
  std::vector<Row> state_;
};

}  // namespace fsd

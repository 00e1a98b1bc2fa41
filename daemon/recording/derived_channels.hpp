#pragma once
// The derived channels a recording carries beside the raw frames (docs/recording.md): what the Stack made of them,
// JSON-encoded with the dashboard's own Foxglove schemas, so a recording opens in Foxglove Studio with the scene,
// the plots, the AS state, the faults and the log. Replay never reads them (it recomputes everything from the raw
// frames); they are for people and tools. Rates are on the run's clock, so a headless run records the same
// messages as a real-time one.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/params.hpp"
#include "daemon/telemetry/telemetry.hpp"
#include "daemon/telemetry/telemetry_channels.hpp"
#include "web/channels.hpp"

namespace fsd {

inline constexpr const char* kParamChangesTopic = "/params/changes";  // fsd.ParamChange, one per accepted change

struct DerivedMessage {
  std::string topic;
  Stamp t = 0;
  std::string payload;  // JSON text
};

// Every derived channel a recording may carry (topic, schema name, JSON schema), in a fixed order.
std::vector<web::ChannelSpec> derived_channel_specs();

// {"t", "key", "old", "new", "who"}: who changed a parameter, from what to what.
std::string param_change_json(const ParamChange& c);

// Turns the Stack's snapshots (every 4th cycle) into recorded messages, by the channel table's recording rates
// on the run's clock (daemon/telemetry/telemetry_channels.cpp): the vehicle state and the car at every snapshot (25 Hz),
// the detections when they changed (at most 4 Hz), perception's split of the newest scan (1 Hz, thinned), the
// cone map and the paths when they changed (at most 1 Hz: tens of kB of JSON each, and they change slowly; whole
// scenes, not the dashboard's changes, so that any message of a file shows the whole scene), the AS status at 5 Hz
// and whenever it changes state, the fault list whenever it changes. Runs on the recorder's writer thread.
class DerivedChannels {
 public:
  explicit DerivedChannels(web::CarShape car = {});
  std::vector<DerivedMessage> messages(const TelemetrySnapshot& s);

 private:
  ChannelUse use_;
  ChannelPacer pacer_;
};

}  // namespace fsd

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
#include "daemon/telemetry.hpp"
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

// Turns the Stack's snapshots (every 4th cycle) into recorded messages: the vehicle state and the car at every
// snapshot, the detections when they changed (at most detections_hz), perception's split of the newest scan (at
// most cloud_hz, thinned), the cone map and the paths when they changed
// (at most map_hz: they are the big ones, tens of kB of JSON each, and change slowly), the AS status at status_hz
// and whenever it changes state, the fault list whenever it grows or changes. Runs on the recorder's writer thread.
struct DerivedRates {
  double detections_hz = 4, map_hz = 1, status_hz = 5;
  double cloud_hz = 1;              // perception's labelled cloud (ground / obstacles), when it runs
  std::size_t cloud_points = 2000;  // ... thinned to this many points (~45 kB of JSON)
};

class DerivedChannels {
 public:
  explicit DerivedChannels(web::CarShape car = {}, DerivedRates rates = {}) : car_(car), rates_(rates) {}
  std::vector<DerivedMessage> messages(const TelemetrySnapshot& s);

 private:
  web::CarShape car_;
  DerivedRates rates_;
  std::shared_ptr<const std::vector<Cone>> cone_map_;
  std::shared_ptr<const ConeDetections> detections_;
  std::shared_ptr<const web::PathSet> paths_;
  std::shared_ptr<const LabelledCloud> cloud_;
  Stamp detections_at_ = -1e300, map_at_ = -1e300, status_at_ = -1e300, cloud_at_ = -1e300;
  AsState as_state_ = AsState::Off;
  std::size_t faults_ = 0;
  std::string last_fault_;
};

}  // namespace fsd

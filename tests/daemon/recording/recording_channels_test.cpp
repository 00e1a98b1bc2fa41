// The derived channels of a recording (daemon/recording/derived_channels.hpp): what the Stack made of its frames, the log and
// the parameter changes, JSON-encoded with the dashboard's schemas so that Foxglove Studio shows them. Read back
// with the MCAP reader and compared with what went in, or with the simulator's truth.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/mcap/linear_reader.hpp"
#include "common/params.hpp"
#include "daemon/recording/recorder.hpp"
#include "daemon/telemetry/telemetry.hpp"
#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd {
namespace {

using nlohmann::json;

struct ChannelRead {
  std::string encoding, schema_name, schema_encoding;
  std::vector<std::pair<double, json>> messages;  // log time (s), payload
};

std::map<std::string, ChannelRead> read_json_channels(const std::string& file) {
  std::ifstream f(file, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  mcap::LinearReader reader(bytes);
  std::map<std::uint16_t, mcap::Schema> schemas;
  std::map<std::uint16_t, std::string> topic_of;
  std::map<std::string, ChannelRead> out;
  while (auto r = reader.next()) {
    if (const auto* s = std::get_if<mcap::Schema>(&r->record)) schemas[s->id] = *s;
    if (const auto* c = std::get_if<mcap::Channel>(&r->record)) {
      if (c->message_encoding != "json") continue;
      topic_of[c->id] = c->topic;
      auto& ch = out[c->topic];
      ch.encoding = c->message_encoding;
      ch.schema_name = schemas.at(c->schema_id).name;
      ch.schema_encoding = schemas.at(c->schema_id).encoding;
      EXPECT_TRUE(json::accept(schemas.at(c->schema_id).data)) << c->topic << ": schema is not JSON";
    }
    if (const auto* m = std::get_if<mcap::Message>(&r->record)) {
      const auto it = topic_of.find(m->channel_id);
      if (it != topic_of.end())
        out[it->second].messages.emplace_back(static_cast<double>(m->log_time) / 1e9, json::parse(m->data));
    }
  }
  EXPECT_TRUE(reader.complete());
  return out;
}

TEST(RecordingChannels, ParameterChangesLogLinesAndSnapshotsAreRecordedAsTheyCame) {
  const auto file = test::scratch_path("derived_unit.mcap");
  {
    RecordingContents rc;
    Recorder rec(file, RecordSettings{}, rc);
    rec.on_cycle(2.0);
    ParamChange c;
    c.t = 12345.0;  // the registry's wall clock: the recording keeps the run's
    c.key = "control.speed.v_max";
    c.old_value = 9.0;
    c.new_value = 7.5;
    c.who = "web 10.0.0.2 (token ok)";
    rec.on_param(2.0, c);
    rec.on_log({web::LogLevel::Warning, "gnss", "fix lost"});
    auto snap = std::make_shared<TelemetrySnapshot>();
    snap->t = 2.0;
    snap->state.pose = {3.0, 4.0, 0.5};
    snap->state.vx = 6.0;
    snap->as.as_state = AsState::Emergency;
    snap->faults.push_back({1.9, "vcu_link", "heartbeat lost", "emergency stop", true});
    std::vector<Cone> cones(2);
    cones[0].position = Vec3(5, 1, 0);
    cones[0].colour = ConeColour::Blue;
    cones[1].position = Vec3(5, -1, 0);
    cones[1].colour = ConeColour::Yellow;
    snap->cone_map = std::make_shared<const std::vector<Cone>>(cones);
    rec.on_snapshot(snap);
    // Half a second later perception has split a scan: 3 ground points and 2 obstacle points, drawn at the pose.
    auto later = std::make_shared<TelemetrySnapshot>(*snap);
    later->t = 2.5;
    auto cloud = std::make_shared<LabelledCloud>();
    cloud->stamp = 2.45;
    cloud->ground.resize(3);
    cloud->obstacles.resize(2);
    later->cloud = cloud;
    later->cloud_pose = Pose2{3.0, 4.0, 0.5}.to_pose3();
    rec.on_snapshot(later);
    rec.close();
    EXPECT_EQ(rec.stats().dropped, 0u);
  }
  const auto ch = read_json_channels(file);
  ASSERT_TRUE(ch.count("/params/changes"));
  ASSERT_EQ(ch.at("/params/changes").messages.size(), 1u);
  const json& p = ch.at("/params/changes").messages[0].second;
  EXPECT_EQ(p["key"], "control.speed.v_max");
  EXPECT_EQ(p["old"], 9.0);
  EXPECT_EQ(p["new"], 7.5);
  EXPECT_EQ(p["who"], "web 10.0.0.2 (token ok)");
  EXPECT_EQ(p["t"], 2.0);
  EXPECT_DOUBLE_EQ(ch.at("/params/changes").messages[0].first, 2.0);

  ASSERT_TRUE(ch.count("/log"));
  EXPECT_EQ(ch.at("/log").schema_name, "foxglove.Log");
  ASSERT_EQ(ch.at("/log").messages.size(), 1u);
  EXPECT_EQ(ch.at("/log").messages[0].second["message"], "fix lost");
  EXPECT_EQ(ch.at("/log").messages[0].second["name"], "gnss");
  EXPECT_DOUBLE_EQ(ch.at("/log").messages[0].first, 2.0);  // the newest cycle's time

  ASSERT_TRUE(ch.count("/vehicle/state"));
  const json& v = ch.at("/vehicle/state").messages.at(0).second;
  EXPECT_EQ(v["x"], 3.0);
  EXPECT_EQ(v["speed"], 6.0);
  ASSERT_TRUE(ch.count("/as/status"));
  EXPECT_EQ(ch.at("/as/status").messages.at(0).second["as_state"], "Emergency");
  ASSERT_TRUE(ch.count("/faults"));
  EXPECT_NE(ch.at("/faults").messages.at(0).second.dump().find("heartbeat lost"), std::string::npos);
  ASSERT_TRUE(ch.count("/map/cones"));
  EXPECT_EQ(ch.at("/map/cones").schema_name, "foxglove.SceneUpdate");
  EXPECT_EQ(ch.at("/map/cones").schema_encoding, "jsonschema");
  ASSERT_TRUE(ch.count("/lidar/points"));  // only the snapshot with perception's cloud
  ASSERT_EQ(ch.at("/lidar/points").messages.size(), 1u);
  const json& pc = ch.at("/lidar/points").messages[0].second;
  EXPECT_EQ(pc["point_stride"], 16);
  EXPECT_EQ(pc["data"].get<std::string>().size(), 108u);  // 5 points × 16 bytes, base64
  EXPECT_EQ(pc["pose"]["position"]["x"], 3.0);
  EXPECT_FALSE(ch.count("/camera/image"));
}

TEST(RecordingChannels, ARecordedRunCarriesItsStateSceneStatusAndLogAtTheirRates) {
  const auto file = test::scratch_path("derived_run.mcap");
  const auto report = test::scratch_path("derived_run.json");
  const auto cfg = test::scratch_path("derived_run_cfg.json");
  std::ofstream(cfg) << test::truth_sources();
  std::string out;
  ASSERT_EQ(test::run_fsd("run --sim --headless --until-finished --mission acceleration --track "
                          "../shared/tracks/epfl_acceleration.csv --config " +
                              cfg + " --record " + file + " --report " + report,
                          &out),
            0)
      << out;
  std::ifstream rf(report);
  const json live = json::parse(rf);
  const auto ch = read_json_channels(file);
  const double sim_time = live["sim_time_s"].get<double>();

  // The state at 25 Hz of the run's clock, every snapshot; its speed is the truth's (localization = truth).
  ASSERT_TRUE(ch.count("/vehicle/state"));
  const auto& states = ch.at("/vehicle/state").messages;
  EXPECT_NEAR(static_cast<double>(states.size()), sim_time * 25, 2.0);
  double v_max = 0;
  for (const auto& [t, m] : states) v_max = std::max(v_max, m["speed"].get<double>());
  ASSERT_FALSE(live["laps"].empty());
  EXPECT_NEAR(v_max, live["laps"][0]["v_max_m_s"].get<double>(), 0.3);
  EXPECT_EQ(ch.at("/vehicle/car").messages.size(), states.size());

  // The AS status at 5 Hz and on every change of state; the last one says how the run ended.
  ASSERT_TRUE(ch.count("/as/status"));
  EXPECT_EQ(ch.at("/as/status").messages.back().second["as_state"], live["as_state"]);
  EXPECT_GE(static_cast<double>(ch.at("/as/status").messages.size()), sim_time * 5 - 2);
  // The cone map and the paths (tens of kB of JSON each) at most once a second, the detections at most 4 Hz.
  ASSERT_TRUE(ch.count("/map/cones"));
  EXPECT_LE(static_cast<double>(ch.at("/map/cones").messages.size()), sim_time + 1);
  ASSERT_TRUE(ch.count("/planning/paths"));
  EXPECT_LE(static_cast<double>(ch.at("/planning/paths").messages.size()), sim_time + 1);
  ASSERT_TRUE(ch.count("/perception/cones"));
  EXPECT_LE(static_cast<double>(ch.at("/perception/cones").messages.size()), sim_time * 4 + 1);
  EXPECT_GT(ch.at("/perception/cones").messages.size(), 0u);
  EXPECT_GT(ch.at("/map/cones").messages.size(), 0u);
  // The run's log: its first line names the mission and the layout.
  ASSERT_TRUE(ch.count("/log"));
  bool driving = false;
  for (const auto& [t, m] : ch.at("/log").messages)
    driving |= m["message"].get<std::string>().find("driving acceleration on epfl_acceleration") != std::string::npos;
  EXPECT_TRUE(driving) << ch.at("/log").messages.size() << " log lines";
  EXPECT_EQ(live["recording"]["log_dropped"], 0);
  EXPECT_GT(live["recording"]["derived_written"].get<double>(), static_cast<double>(states.size()));
}

}  // namespace
}  // namespace fsd

#include "daemon/telemetry/telemetry.hpp"

#include <algorithm>
#include <chrono>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "daemon/telemetry/telemetry_channels.hpp"
#include "web/log_sink.hpp"
#include "web/scene_delta.hpp"
#include "web/server.hpp"

namespace fsd {

namespace {

// /api/state: the newest snapshot in short (the channels carry the rest).
nlohmann::json state_json(const TelemetrySnapshot& s) {
  const auto& v = s.state;
  nlohmann::json j = {
      {"t", s.t},
      {"as_state", std::string(to_string(s.as.as_state))},
      {"mission", std::string(to_string(s.as.mission))},
      {"lap", s.as.lap},
      {"laps_completed", s.as.laps_completed},
      {"laps_total", s.as.laps_total},
      {"lap_times", s.as.lap_times},
      {"control_mode", s.as.control_mode},
      {"finished", s.as.finished},
      {"vehicle",
       {{"x", v.pose.x},
        {"y", v.pose.y},
        {"yaw", v.pose.yaw},
        {"speed", v.speed()},
        {"yaw_rate", v.yaw_rate},
        {"target_speed", s.target_speed}}},
      {"faults", static_cast<int>(s.faults.size())},
  };
  if (s.truth) j["truth"] = {{"speed", s.truth->speed}, {"cones_hit", s.truth->cones_hit}};
  return j;
}

}  // namespace

Telemetry::Telemetry(web::WebServer& server, bool truth, web::CarShape car)
    : server_(server),
      truth_(truth),
      ids_(web::add_channels(server, channel_specs([truth](const TelemetryChannel& c) { return truth || !c.truth; }))),
      car_(car),
      published_(
          server.metrics().counter("fsd_telemetry_snapshots_total", "Snapshots the control loop handed to telemetry")),
      skipped_(server.metrics().counter("fsd_telemetry_snapshots_skipped_total",
                                        "Snapshots replaced by a newer one before the telemetry thread took them")),
      thread_([this] { loop(); }) {
  server_.set_state_provider([slot = latest_]() -> nlohmann::json {
    const auto snap = slot->get();
    if (!snap || !*snap) return {{"t", nullptr}, {"as_state", nullptr}};
    return state_json(**snap);
  });
}

Telemetry::~Telemetry() { stop(); }

void Telemetry::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void Telemetry::publish(std::shared_ptr<const TelemetrySnapshot> snapshot) {
  latest_->set(std::move(snapshot));
  published_.inc();
}

void Telemetry::loop() {
  using clock = std::chrono::steady_clock;
  const auto& rows = telemetry_channels();
  // Rates in wall time: the dashboard wants smooth real-time updates, also while a headless run races through
  // simulated time.
  ChannelPacer pacer(
      rows, [](const TelemetryChannel& c) { return c.live_hz; },
      [this](const TelemetryChannel& c) { return truth_ || !c.truth; });
  std::vector<web::ChannelId> ids(rows.size(), 0);
  std::vector<std::optional<web::SceneDelta>> scenes(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (const auto it = ids_.by_topic.find(rows[i].spec.topic); it != ids_.by_topic.end()) ids[i] = it->second;
    if (rows[i].spec.options.delta) scenes[i].emplace();
  }
  const ChannelUse use{car_, false};
  const auto start = clock::now();
  std::uint64_t seen = 0;
  std::shared_ptr<const TelemetrySnapshot> snap;
  while (!stop_) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const std::uint64_t before = seen;
    if (const auto newer = latest_->get_if_newer(seen)) {
      if (seen > before + 1) skipped_.inc(seen - before - 1);
      snap = *newer;
    }
    if (!snap) continue;
    const TelemetrySnapshot& s = *snap;
    const double now = std::chrono::duration<double>(clock::now() - start).count();
    // Without a new snapshot only data still unsent (a rate-limited scene) can be due.
    for (const std::size_t i : pacer.due(s, now, seen != before)) {
      auto p = rows[i].build(s, use);
      if (!p) continue;
      if (!p->entities) {
        server_.publish(ids[i], s.t, std::move(p->json));
      } else if (!scenes[i]) {
        server_.publish(ids[i], s.t, web::scene_update_json(*p->entities));
      } else if (auto u = scenes[i]->update(s.t, *p->entities)) {
        server_.publish(ids[i], s.t, std::move(u->delta), std::move(u->full));
      }
    }
  }
}

LogForwarding::LogForwarding(web::WebServer& server, web::ChannelId log_channel, const Clock& clock,
                             spdlog::level::level_enum level)
    : LogForwarding(web::make_log_sink(server, log_channel, clock, level)) {}

LogForwarding::LogForwarding(std::shared_ptr<spdlog::sinks::sink> sink) : sink_(std::move(sink)) {
  // The default logger's sinks are what fsd::logger() copies into loggers it creates later.
  auto attach = [this](const std::shared_ptr<spdlog::logger>& l) {
    auto& sinks = l->sinks();
    if (std::find(sinks.begin(), sinks.end(), sink_) == sinks.end()) sinks.push_back(sink_);
  };
  attach(spdlog::default_logger());
  spdlog::apply_all(attach);
}

LogForwarding::~LogForwarding() { detach(); }

void LogForwarding::detach() {
  if (!sink_) return;
  auto remove = [this](const std::shared_ptr<spdlog::logger>& l) {
    auto& sinks = l->sinks();
    sinks.erase(std::remove(sinks.begin(), sinks.end(), sink_), sinks.end());
  };
  remove(spdlog::default_logger());
  spdlog::apply_all(remove);
  sink_.reset();
}

}  // namespace fsd

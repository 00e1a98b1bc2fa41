#include "daemon/feeders/replay_run.hpp"

#include <chrono>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/clock.hpp"
#include "common/logging.hpp"
#include "common/mcap/byte_io.hpp"
#include "common/mcap/fsd_profile.hpp"
#include "daemon/cli/cli.hpp"
#include "daemon/feeders/truth_frames.hpp"
#include "daemon/recording/recording_reader.hpp"
#include "daemon/scoring/sim_scoring.hpp"
#include "daemon/stack/settings.hpp"
#include "daemon/stack/stack.hpp"
#include "daemon/telemetry/sim_truth.hpp"
#include "drivers/camera/camera_calibration.hpp"

namespace fsd {

Config replay_config(const mcap::StringMap& recorded, const std::string& config_file, spdlog::logger& log) {
  const auto schema = config_schema();
  Config cfg(schema);
  const std::string origin = "the recording's " + std::string(mcap::kConfigMetadata);
  for (const auto& [key, text] : recorded) {
    if (!schema->find(key)) {
      log.warn("recording: configuration key '{}' is unknown to this fsd: ignored", key);
      continue;
    }
    nlohmann::json v;
    try {
      v = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception&) {
      throw ConfigError(origin + ": key '" + key + "' is not JSON");
    }
    cfg.set(key, v, origin);
  }
  if (!config_file.empty()) {
    std::ifstream f(config_file);
    if (!f) throw ConfigError(config_file + ": cannot be read");
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(f);
    } catch (const nlohmann::json::exception& e) {
      throw ConfigError(config_file + ": not JSON: " + e.what());
    }
    cfg.merge(j, config_file);
  }
  return cfg;
}

namespace {

// Compares what the Stack hands the VCU session each cycle with the recording's.
struct OutputTap final : StackTap {
  std::optional<std::vector<std::uint8_t>> last;
  void on_frame(const RawFrame&) override {}
  void on_cycle(Stamp) override {}
  void on_output(Stamp now, const ControlCommand& c, wire::vcu::AsRequest r) override {
    last = encode_command({now, c, r});
  }
};

}  // namespace

struct ReplayRun::Impl {
  std::string file;
  bool headless, until_finished;
  double rate;
  std::shared_ptr<spdlog::logger> log = logger("replay");
  mcap::MappedFile mapped;
  RecordingReader reader;
  RecordedRun recorded;
  Config cfg;
  RunSettings run;
  std::unique_ptr<Stack> stack;
  RunMetrics* metrics = nullptr;  // the dashboard's /metrics
  OutputTap outputs;
  Track track;
  std::unique_ptr<SimScoring> scoring;
  std::optional<TruthStateFrame> truth;
  std::shared_ptr<const std::vector<web::TruthCone>> dashboard_cones;  // the recorded standing cones, for /truth/*

  // Results.
  std::uint64_t compared = 0, mismatches = 0, vcu_compared = 0, vcu_mismatches = 0, unanswered = 0;
  std::optional<Stamp> first_mismatch;
  std::vector<std::vector<std::uint8_t>> cycle_vcu_tx;  // the recorded bytes to the VCU in this cycle
  Stamp t_first = 0, t_last = 0;
  bool any_cycle = false;
  double wall_time = 0;
  nlohmann::json car_summary;

  explicit Impl(const RunOptions& o)
      : file(o.replay),
        headless(o.headless),
        until_finished(o.until_finished),
        rate(o.rate),
        mapped(o.replay),
        reader(mapped.bytes()),
        recorded(recorded_run_from_metadata(*reader.metadata(mcap::kRunMetadata))),
        cfg(replay_config(*reader.metadata(mcap::kConfigMetadata), o.config_file, *log)),
        run(run_section().read(cfg)) {
    StackOptions so;
    so.mission = recorded.mission;
    so.laps = recorded.laps;
    so.simulator = recorded.simulator;
    so.start = recorded.start;
    // In lockstep the lap-2 build runs inside the step that asks for it, as the headless run did; a replay with
    // the dashboard of a real-time recording builds it on the worker, as that run did.
    so.lap_build_worker = !headless && !recorded.lockstep;
    so.plan_worker = so.lap_build_worker;
    so.loop_closure_worker = so.lap_build_worker;
    so.scan_worker = so.lap_build_worker;
    if (recorded.camera_latency) {
      nlohmann::json j;
      try {
        j = nlohmann::json::parse(recorded.camera_calibration);
      } catch (const nlohmann::json::exception&) {
        throw RecordingError("the recording's camera calibration is not JSON");
      }
      try {
        so.camera = StackOptions::Camera{parse_camera_calibration(j, "the recording's camera calibration"),
                                         *recorded.camera_latency};
      } catch (const CalibrationError& e) {
        throw RecordingError(e.what());
      }
    }
    stack = std::make_unique<Stack>(cfg, so);
    stack->add_tap(&outputs);
    if (recorded.simulator) {
      const auto convention = ColourConvention::named(run.colours);
      // The attached bytes, named as the recorded run.track names them (the scorecard's "track").
      if (const auto csv = reader.attachment(kTrackAttachment))
        track = parse_track(*csv, run.track, convention);
      else
        track = load_track(run.track, convention);
      scoring = std::make_unique<SimScoring>(track, recorded.mission, run, *stack);
    }
    for (const auto& i : reader.issues()) log->warn("{}: {}", file, i.what);
  }

  void note_mismatch(Stamp t, const char* what) {
    if (!first_mismatch) {
      first_mismatch = t;
      log->warn("{}: the {} computed at t = {:.3f} s differs from the recorded one (first mismatch)", file, what, t);
    }
  }

  // The frame into the Stack, the simulator's truth into the scorecard first (as the live run scored it).
  void on_frame(const RecordingEvent& e) {
    if (scoring && e.channel == RawChannel::TruthState) {
      if (auto s = decode_truth_state(e.bytes)) {
        truth = *s;
        scoring->on_truth(truth_from_state(s->state));
      }
    } else if (scoring && e.channel == RawChannel::TruthCones) {
      if (auto c = decode_truth_cones(e.bytes)) {
        dashboard_cones = std::make_shared<const std::vector<web::TruthCone>>(truth_cones(*c));
        scoring->set_truth_cones(std::move(*c));
      }
    } else if (scoring && e.channel == RawChannel::TruthLidarReturns) {
      if (auto r = decode_truth_lidar_returns(e.bytes)) scoring->add_lidar_returns(*r);
    } else if (e.channel == RawChannel::VcuTx) {
      if (recorded.mode == "sim")
        cycle_vcu_tx.push_back(e.bytes);
      else {
        // On the car the link's sender thread encoded these, when it sent them.
        ++vcu_compared;
        if (stack->vcu().command_frame(e.t) != e.bytes) ++vcu_mismatches;
      }
    }
    stack->feed({e.channel, e.t, e.bytes});
  }

  void on_cycle(Stamp t) {
    if (recorded.mode == "sim") {
      // The simulator's lockstep: the Command due now, then the step.
      std::size_t k = 0;
      stack->vcu().tick(t, [&](std::vector<std::uint8_t> bytes) {
        ++vcu_compared;
        if (k >= cycle_vcu_tx.size() || cycle_vcu_tx[k] != bytes) {
          ++vcu_mismatches;
          note_mismatch(t, "VCU command frame");
        }
        ++k;
      });
      if (k != cycle_vcu_tx.size()) vcu_mismatches += cycle_vcu_tx.size() - std::min(k, cycle_vcu_tx.size());
      cycle_vcu_tx.clear();
    } else {
      stack->vcu().check_timeout(t);
    }
    outputs.last.reset();
    if (metrics) metrics->on_cycle_start();
    stack->step(t);
    if (scoring && truth) scoring->after_step(truth->as_state, static_cast<int>(truth->cones_hit));
    if (!any_cycle) t_first = t;
    any_cycle = true;
    t_last = t;
  }

  void on_command(const RecordingEvent& e) {
    if (!outputs.last) {
      ++unanswered;  // a command whose cycle marker was lost
      return;
    }
    ++compared;
    if (*outputs.last != e.bytes) {
      ++mismatches;
      note_mismatch(e.t, "command");
    }
    outputs.last.reset();
  }

  int run_loop(const std::atomic<bool>& stop) {
    const auto wall0 = std::chrono::steady_clock::now();
    SimulatedClock pace(rate);
    std::optional<Stamp> t0;
    log->info("replaying {} ({} run, {}{}) {}", file, recorded.mode, to_string(recorded.mission),
              recorded.lockstep ? ", recorded in lockstep" : "",
              headless ? std::string("headless") : fmt::format("at {:g}x real time", rate));
    while (!stop.load(std::memory_order_relaxed)) {
      auto e = reader.next();
      if (!e) break;
      if (e->kind == RecordingEvent::Kind::Frame) {
        on_frame(*e);
      } else if (e->kind == RecordingEvent::Kind::Command) {
        on_command(*e);
      } else {
        if (!headless) {
          if (!t0) t0 = e->t;
          if (!pace.sleep_until(e->t - *t0)) break;
        }
        on_cycle(e->t);
      }
    }
    wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    for (const auto& i : reader.issues()) log->warn("{}: {}", file, i.what);
    if (const auto cut = reader.truncated_at())
      log->warn("{}: cut off at offset {}: replayed up to its last complete chunk (t = {:.3f} s)", file, *cut, t_last);
    const auto& c = reader.counters();
    log->info(
        "replay over at t = {:.2f} s: {} frames, {} cycles in {:.2f} s ({:.1f}x real time); commands: {} "
        "compared, {} mismatched; VCU frames: {} compared, {} mismatched",
        t_last, c.frames, c.cycles, wall_time, wall_time > 0 ? (t_last - t_first) / wall_time : 0.0, compared,
        mismatches, vcu_compared, vcu_mismatches);
    if (scoring) scoring->finish(wall_time);
    int rc = kExitOk;
    if (recorded.lockstep && (mismatches > 0 || vcu_mismatches > 0)) {
      log->error("{}: the replay did not repeat the recorded run bit for bit ({} command mismatch(es))", file,
                 mismatches);
      rc = kExitMissionFailed;
    }
    if (until_finished && scoring && !scoring->card().mission_succeeded()) rc = kExitMissionFailed;
    return rc;
  }

  nlohmann::json replay_json() const {
    const auto& c = reader.counters();
    nlohmann::json issues = nlohmann::json::array();
    for (const auto& i : reader.issues())
      issues.push_back({{"kind", mcap::to_string(i.kind)}, {"offset", i.offset}, {"what", i.what}});
    nlohmann::json j = {
        {"file", file},
        {"recorded_mode", recorded.mode},
        {"recorded_lockstep", recorded.lockstep},
        {"frames", c.frames},
        {"cycles", c.cycles},
        {"inexact_frames", c.inexact_frames},
        {"bad_messages", c.bad_messages},
        {"commands_compared", compared},
        {"command_mismatches", mismatches},
        {"commands_without_cycle", unanswered},
        {"vcu_frames_compared", vcu_compared},
        {"vcu_frame_mismatches", vcu_mismatches},
        {"first_mismatch_t", first_mismatch ? nlohmann::json(*first_mismatch) : nlohmann::json()},
        {"complete", reader.complete()},
        {"truncated_at", reader.truncated_at() ? nlohmann::json(*reader.truncated_at()) : nlohmann::json()},
        {"issues", issues},
        {"replayed_s", any_cycle ? t_last - t_first : 0.0},
        {"wall_time_s", wall_time},
        {"speed_x", wall_time > 0 && any_cycle ? (t_last - t_first) / wall_time : 0.0}};
    return j;
  }

  nlohmann::json report() const {
    nlohmann::json j;
    if (scoring) {
      j = scoring->card().to_json();
      // The live run's measurement of its injected faults (the replay has the truth but not the car's schedule).
      if (const auto* m = reader.metadata(kInjectedFaultsMetadata); m && m->count("json")) {
        auto injected = nlohmann::json::parse(m->at("json"), nullptr, false);
        if (!injected.is_discarded()) j["injected_faults"] = std::move(injected);
      }
    } else {
      j["mode"] = "replay";
      j["mission"] = std::string(to_string(recorded.mission));
      j["as_state"] = std::string(to_string(stack->as_state()));
      j["sim_time_s"] = any_cycle ? t_last - t_first : 0.0;
      j["wall_time_s"] = wall_time;
      j["latency_ms"] = latency_json(stack->latencies());
      j["faults"] = faults_json(stack->faults());
    }
    j["replay"] = replay_json();
    return j;
  }
};

ReplayRun::ReplayRun(const RunOptions& options) : impl_(std::make_unique<Impl>(options)) {}
ReplayRun::~ReplayRun() = default;
const Config& ReplayRun::config() const { return impl_->cfg; }
bool ReplayRun::simulator() const { return impl_->recorded.simulator; }
int ReplayRun::run(const std::atomic<bool>& stop) { return impl_->run_loop(stop); }
nlohmann::json ReplayRun::report() const { return impl_->report(); }
void ReplayRun::set_telemetry(Telemetry* telemetry) {
  if (!impl_->scoring) return impl_->stack->set_telemetry(telemetry);
  // A simulated run's recorded truth on the dashboard's /truth/* channels, as the live run showed it.
  impl_->stack->set_telemetry(telemetry, [this](TelemetrySnapshot& s) {
    if (impl_->truth)
      s.truth = truth_state(truth_from_state(impl_->truth->state), static_cast<int>(impl_->truth->cones_hit));
    s.truth_cones = impl_->dashboard_cones;
  });
}
void ReplayRun::set_metrics(RunMetrics* metrics) {
  impl_->metrics = metrics;
  impl_->stack->set_metrics(metrics);
}
void ReplayRun::set_params(ParamRegistry* params) { impl_->stack->set_params(params); }

const Stack& ReplayRun::stack() const { return *impl_->stack; }

}  // namespace fsd

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/clock.hpp"
#include "common/logging.hpp"
#include "common/mcap/records.hpp"
#include "common/params.hpp"
#include "common/track.hpp"
#include "daemon/cli/cli.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/cli/run_options.hpp"
#include "daemon/dds/perception_role.hpp"
#include "daemon/feeders/hardware_run.hpp"
#include "daemon/feeders/replay_run.hpp"
#include "daemon/feeders/sim_run.hpp"
#include "daemon/recording/recording_reader.hpp"
#include "daemon/scoring/map_export.hpp"
#include "daemon/scoring/vs_truth.hpp"
#include "daemon/service/journal_log.hpp"
#include "daemon/service/recordings_folder.hpp"
#include "daemon/service/resource_paths.hpp"
#include "daemon/service/service_notifier.hpp"
#include "daemon/stack/settings.hpp"
#include "daemon/stack/stack.hpp"
#include "daemon/telemetry/dashboard.hpp"

namespace fsd {

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop.store(true); }

// Whether the configuration file sets `section.key` itself (it was validated by Config::load already).
bool file_sets(const std::string& file, const std::string& section, const std::string& key) {
  if (file.empty()) return false;
  std::ifstream f(file);
  const auto j = nlohmann::json::parse(f, nullptr, false, /*ignore_comments=*/true);
  return j.is_object() && j.contains(section) && j[section].is_object() && j[section].contains(key);
}

// The command line's values override the configuration's, validated the same way.
Config load_config(const RunOptions& o) {
  Config cfg = o.config_file.empty() ? Config(config_schema()) : Config::load(config_schema(), o.config_file);
  if (o.track) cfg.set("run.track", *o.track, "--track");
  if (o.mission) cfg.set("run.mission", *o.mission, "--mission");
  if (o.laps) cfg.set("run.laps", *o.laps, "--laps");
  if (o.seed) cfg.set("run.seed", *o.seed, "--seed");
  if (o.port) cfg.set("web.port", *o.port, "--port");
  // The virtual car is a desk run: its dashboard stays on this machine unless the file says otherwise (the car's
  // default, every interface, is for the pit lane's Wi-Fi).
  if (o.sim && !file_sets(o.config_file, "web", "bind")) cfg.set("web.bind", std::string("127.0.0.1"), "--sim");
  locate_resources(cfg);  // the model and the dashboard, wherever fsd was started from
  return cfg;
}

// Writes the run's report (`--report`) when asked; the run's exit status unless the file cannot be written.
int finish(int rc, const std::string& path, const nlohmann::json& report) {
  if (path.empty()) return rc;
  std::ofstream f(path);
  if (!f) {
    std::cerr << "fsd run: cannot write the report to " << path << "\n";
    return kExitBadInput;
  }
  f << report.dump(2) << "\n";
  return rc;
}

// A report or map that could not be written would be found missing only after the run: checked before anything
// starts. A file that did not exist is not left behind by the check (a refused run writes nothing).
void require_writable(const char* flag, const std::string& path) {
  if (path.empty()) return;
  std::error_code ec;
  const bool existed = std::filesystem::exists(path, ec);
  {
    std::ofstream f(path, std::ios::app);
    if (!f)
      throw std::invalid_argument(std::string(flag) + " " + path + ": cannot be written (" + std::strerror(errno) +
                                  ")");
  }
  if (!existed) std::filesystem::remove(path, ec);
}

// --map-out: the Stack's cone map at the end of the run, as a track file.
void export_map(const std::string& path, const Stack& stack) {
  if (path.empty()) return;
  const Pose2 start = stack.first_pose().value_or(Pose2{});
  const std::string name = std::filesystem::path(path).stem().string();
  const MapExport m = map_as_track(stack.cone_map(), start, stack.convention(), name);
  write_map_csv(path, m);
  logger("run")->info("cone map: {} cone(s) written to {}{}", m.track.cones.size(), path,
                      m.without_role ? " (" + std::to_string(m.without_role) + " without a colour left out)" : "");
}

// --vs-truth: the same layout and seed once more, headless, on the truth sources; "vs_truth" of the report.
nlohmann::json drive_on_truth(const Config& cfg, const RunOptions& o, const nlohmann::json& estimated) {
  RunOptions ref = o;
  ref.headless = true;
  ref.workers = false;
  ref.record.clear();
  ref.report.clear();
  ref.map_out.clear();
  logger("run")->info("--vs-truth: driving the same layout and seed on the truth sources");
  SimRun truth_run(truth_reference_config(cfg), ref);
  truth_run.run(g_stop);
  return vs_truth(estimated, truth_run.scorecard().to_json());
}

int run_command(const RunOptions& given) {
  RunOptions o = given;
  if (!o.role.empty() && (o.sim || !o.replay.empty() || !o.record.empty()))
    throw std::invalid_argument(
        "--role perception runs the perception stages on this computer's sensors: --sim, "
        "--replay and --record do not apply");
  if (!o.replay.empty() && (o.sim || !o.record.empty() || o.track || o.mission || o.laps || o.seed))
    throw std::invalid_argument(
        "--replay takes the run from the recording: --sim, --record, --track, --mission, "
        "--laps and --seed do not apply (a --config file overrides recorded keys)");
  if (o.vs_truth && !o.sim)
    throw std::invalid_argument("--vs-truth drives the virtual car a second time on the truth sources: it needs --sim");
  if (!(o.rate > 0.0 && o.rate <= 1000.0)) throw std::invalid_argument("--rate must be in (0, 1000]");
  require_writable("--report", o.report);
  require_writable("--map-out", o.map_out);
  // A replay's configuration is the recording's (daemon/feeders/replay_run.hpp).
  std::unique_ptr<ReplayRun> replay;
  if (!o.replay.empty()) {
    try {
      replay = std::make_unique<ReplayRun>(o);
    } catch (const mcap::McapError& e) {
      std::cerr << "fsd run: " << o.replay << ": " << e.what() << "\n";
      return kExitBadInput;
    } catch (const RecordingError& e) {
      std::cerr << "fsd run: " << o.replay << ": " << e.what() << "\n";
      return kExitBadInput;
    }
  }
  Config cfg = replay ? replay->config() : load_config(o);
  init_logging(daemon_section().read(cfg).log_level);
  log_to_journal_if_there();
  const ServiceSettings service = service_section().read(cfg);
  ServiceNotifier notifier(service);
  // The service's recordings: every run records to service.recordings_dir (held under its size cap) unless told.
  if (!service.recordings_dir.empty() && o.record.empty() && !replay && o.role.empty()) {
    o.record = next_recording_path(service);
    prune_recordings(service);
    logger("run")->info("recording to {}", o.record);
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  RealClock clock;
  ParamRegistry params(cfg, &clock);
  std::unique_ptr<Dashboard> dashboard;
  // After the run's own checks (a bad device or mission exits 2 before anything listens), unless --headless.
  auto start_dashboard = [&](bool truth_channels) {
    if (o.headless) return true;
    dashboard = std::make_unique<Dashboard>(cfg, params, clock, truth_channels);
    try {
      dashboard->start();
    } catch (const std::exception& e) {
      std::cerr << "fsd run: " << e.what() << "\n";
      return false;
    }
    std::cout << "fsd: dashboard at " << dashboard->url() << "  (Ctrl-C stops)" << std::endl;
    return true;
  };
  // Either run (sim or the car) the same way: the dashboard after the run's own checks, then drive until done.
  auto drive = [&](auto& run, bool truth_channels, auto report) -> int {
    if (!start_dashboard(truth_channels)) return kExitBadInput;
    if constexpr (requires { run.set_loop_hook([] {}); }) run.set_loop_hook([&notifier] { notifier.on_cycle(); });
    if (dashboard) {
      run.set_telemetry(&dashboard->telemetry());
      run.set_metrics(&dashboard->metrics());
      run.set_params(&params);
    }
    const int rc = run.run(g_stop);
    notifier.stopping();
    if (!o.record.empty()) prune_recordings(service, o.record);
    if (dashboard) dashboard->stop();
    const int done = finish(rc, o.report, report(run));
    try {
      export_map(o.map_out, run.stack());
    } catch (const std::exception& e) {  // checked writable at the start; the disk may have filled since
      std::cerr << "fsd run: " << e.what() << "\n";
      return kExitBadInput;
    }
    return done;
  };
  if (!o.role.empty()) {
    // Split mode's perception process: no dashboard, no report; until SIGINT/SIGTERM.
    dds::PerceptionRole role(cfg, o);
    role.on_loop([&notifier] { notifier.on_cycle(); });
    const int rc = role.run(g_stop);
    notifier.stopping();
    return rc;
  }
  if (replay) return drive(*replay, replay->simulator(), [](const ReplayRun& r) { return r.report(); });
  if (!o.sim) {
    // The car's own interfaces (daemon/feeders/hardware_run.hpp); bad devices or missions throw and exit 2.
    HardwareRun run(cfg, o);
    return drive(run, false, [](const HardwareRun& r) { return r.report(); });
  }
  SimRun run(cfg, o);
  return drive(run, true, [&](const SimRun& r) {
    nlohmann::json report = r.scorecard().to_json();
    if (o.vs_truth && !g_stop) report["vs_truth"] = drive_on_truth(cfg, o, report);
    return report;
  });
}

}  // namespace

void add_run_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("run", "Run the daemon: with --sim on the virtual car with the full stack");
  static RunOptions o;
  cmd->add_option("--config", o.config_file, "configuration file (JSON); default: compiled-in defaults")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--sim", o.sim, "drive the virtual car in-process");
  cmd->add_option("--track", o.track, "track file (EUFS/FSDS CSV), overrides run.track");
  cmd->add_option("--mission", o.mission, "trackdrive|autocross|acceleration|skidpad|inspection|ebs_test");
  cmd->add_option("--laps", o.laps, "laps of trackdrive, overrides run.laps");
  cmd->add_option("--seed", o.seed, "seed of the virtual car's random processes");
  cmd->add_option("--port", o.port, "dashboard port, overrides web.port");
  cmd->add_option("--replay", o.replay,
                  "replay a recording through the stack (its configuration and mission; --config overrides keys)");
  cmd->add_option("--record", o.record, "record the run to this MCAP file (with --sim or on the car)");
  cmd->add_option("--rate", o.rate, "replay with the dashboard at this multiple of real time (default 1)");
  cmd->add_flag("--headless", o.headless, "no dashboard; the simulation runs as fast as the CPU allows (lockstep)");
  cmd->add_flag("--workers", o.workers,
                "with --headless: lap 2's build and the loop closure's solve on the stack's worker threads, as on the "
                "car, the simulation held to real time while one runs (the run is then not repeatable bit for bit)");
  cmd->add_flag("--until-finished", o.until_finished,
                "stop when the mission is over; exit 1 if it failed (not finished, cones hit, no stop)");
  cmd->add_option("--report", o.report, "write the scorecard (JSON) here at the end");
  cmd->add_option("--map-out", o.map_out,
                  "write the cone map here at the end, as a track file (EUFS CSV: drive it with --sim --track)");
  cmd->add_flag("--vs-truth", o.vs_truth,
                "with --sim: also drive the same layout and seed on the truth sources; the report gains vs_truth "
                "(lap times and cross-track errors side by side: what the estimates cost)");
  cmd->add_option("--role", o.role,
                  "split mode: perception = the LiDAR and camera stages here, their frames over DDS "
                  "to the daemon that drives (run.perception_source = dds; docs/dds.md)")
      ->check(CLI::IsMember({"perception"}));
  // A start never aborts: what the usage errors (std::invalid_argument, configuration and track errors, handled by
  // run_cli) do not cover, a model that does not load, a port, a device, is still exit 2 with its message.
  cmd->callback([&exit_code] {
    try {
      exit_code = run_command(o);
    } catch (const std::invalid_argument&) {
      throw;
    } catch (const ConfigError&) {
      throw;
    } catch (const TrackError&) {
      throw;
    } catch (const std::exception& e) {
      std::cerr << "fsd run: " << e.what() << "\n";
      exit_code = kExitBadInput;
    }
  });
}

}  // namespace fsd

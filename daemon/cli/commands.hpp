#pragma once
// One function per `fsd` subcommand; each adds itself to the app and, when chosen, runs and stores its exit code.
namespace CLI {
class App;
}

namespace fsd {

void add_version_command(CLI::App& app, int& exit_code);
void add_config_command(CLI::App& app, int& exit_code);
void add_run_command(CLI::App& app, int& exit_code);
void add_sim_command(CLI::App& app, int& exit_code);
void add_lidar_dump_command(CLI::App& app, int& exit_code);
void add_detect_command(CLI::App& app, int& exit_code);
void add_calibrate_homography_command(CLI::App& app, int& exit_code);
void add_mcap_command(CLI::App& app, int& exit_code);
void add_track_command(CLI::App& app, int& exit_code);
void add_classify_command(CLI::App& app, int& exit_code);
void add_train_classifier_command(CLI::App& app, int& exit_code);
void add_localize_command(CLI::App& app, int& exit_code);

}  // namespace fsd

#include "daemon/cli/cli.hpp"

#include <iostream>

#include <CLI/CLI.hpp>

#include "common/config.hpp"
#include "common/track.hpp"
#include "daemon/cli/commands.hpp"

namespace fsd {

int run_cli(int argc, char** argv) {
  CLI::App app{"fsd: autonomy daemon of a Formula Student Driverless car (see README.md)"};
  app.require_subcommand(1);
  int exit_code = kExitOk;
  add_version_command(app, exit_code);
  add_config_command(app, exit_code);
  add_run_command(app, exit_code);
  add_sim_command(app, exit_code);
  add_lidar_dump_command(app, exit_code);
  add_detect_command(app, exit_code);
  add_calibrate_homography_command(app, exit_code);
  add_mcap_command(app, exit_code);
  add_track_command(app, exit_code);
  add_classify_command(app, exit_code);
  add_train_classifier_command(app, exit_code);
  add_localize_command(app, exit_code);
  // CLI11 says only "A subcommand is required" for a first word it does not know: name it.
  if (argc > 1 && argv[1][0] != '-') {
    const std::string word = argv[1];
    bool known = false;
    for (const auto* sub : app.get_subcommands([](CLI::App*) { return true; }))
      known = known || sub->get_name() == word;
    if (!known) {
      std::cerr << "fsd: unknown subcommand '" << word << "' (fsd --help lists them)\n";
      return kExitBadInput;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);  // prints help or the usage error
    return rc == 0 ? kExitOk : kExitBadInput;
  } catch (const ConfigError& e) {
    std::cerr << "fsd: configuration error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const TrackError& e) {
    std::cerr << "fsd: track error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "fsd: " << e.what() << "\n";
    return kExitBadInput;
  }
  return exit_code;
}

}  // namespace fsd

#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/car.hpp"
#include "daemon/cli/cli.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/stack/settings.hpp"

namespace fsd {

void add_config_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("config", "Show the configuration's defaults and reference, or check a file");
  cmd->require_subcommand(1);

  cmd->add_subcommand("defaults", "Print the complete default configuration as JSON (deploy/config/default.json)")
      ->callback([&exit_code] {
        std::cout << config_schema()->defaults().dump(2) << "\n";
        exit_code = kExitOk;
      });

  cmd->add_subcommand("doc", "Print the reference table of every configuration key (Markdown)")->callback([&exit_code] {
    std::cout << config_schema()->markdown();
    exit_code = kExitOk;
  });

  auto* check = cmd->add_subcommand("check", "Validate a configuration file; exit 2 with the bad key if invalid");
  static std::string file;
  check->add_option("FILE", file, "configuration file")->required();
  check->callback([&exit_code] {
    const Config cfg = Config::load(config_schema(), file);  // throws ConfigError naming key and file
    read_car(cfg);  // the car's keys must describe one car (throws ConfigError)
    std::cout << file << ": ok\n";
    exit_code = kExitOk;
  });
}

}  // namespace fsd

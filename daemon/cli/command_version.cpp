#include <iostream>

#include <CLI/CLI.hpp>

#include "daemon/cli/commands.hpp"

namespace fsd {

void add_version_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("version", "Print the version of fsd");
  cmd->callback([&exit_code] {
    std::cout << "fsd " << FSD_VERSION << "\n";
    exit_code = 0;
  });
}

}  // namespace fsd

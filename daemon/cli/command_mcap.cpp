#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "common/mcap/byte_io.hpp"
#include "common/mcap/inspect.hpp"
#include "common/mcap/linear_reader.hpp"
#include "common/mcap/recover.hpp"
#include "daemon/cli/cli.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/cli/mcap_report.hpp"

namespace fsd {
namespace {

void add_info(CLI::App& mcap_cmd, int& exit_code) {
  auto* cmd = mcap_cmd.add_subcommand(
      "info",
      "What a recording holds: profile, library, duration, channels with message counts, chunks, "
      "metadata, attachments, summary, damage. Reads the whole file, so it works on cut-off files");
  static std::string file;
  static bool json = false;
  cmd->add_option("FILE", file, "MCAP file")->required();
  cmd->add_flag("--json", json, "print one JSON object instead of text");
  cmd->callback([&exit_code] {
    try {
      const mcap::MappedFile mapped(file);
      const auto info = mcap::inspect(mapped.bytes());
      if (json) {
        std::cout << mcap_info_json(file, info).dump(2) << "\n";
      } else {
        std::cout << format_mcap_info(file, info);
      }
      exit_code = kExitOk;
    } catch (const mcap::McapError& e) {
      std::cerr << "fsd: " << file << ": " << e.what() << "\n";
      exit_code = kExitBadInput;
    }
  });
}

void add_recover(CLI::App& mcap_cmd, int& exit_code) {
  auto* cmd = mcap_cmd.add_subcommand(
      "recover",
      "Rewrite a recording cut off mid-write (or with damaged chunks) into a whole file with a full "
      "summary, keeping every intact message; prints what was kept and lost");
  static std::string in, out;
  cmd->add_option("IN", in, "damaged MCAP file")->required();
  cmd->add_option("OUT", out, "new MCAP file (must not be IN)")->required();
  cmd->callback([&exit_code] {
    std::error_code ec;
    if (std::filesystem::exists(out) && std::filesystem::equivalent(in, out, ec)) {
      std::cerr << "fsd: " << out << ": is the input file; write the recovered file elsewhere\n";
      exit_code = kExitBadInput;
      return;
    }
    std::optional<mcap::MappedFile> mapped;
    try {
      mapped.emplace(in);
      mcap::check_magic(mapped->bytes());
    } catch (const mcap::McapError& e) {
      std::cerr << "fsd: " << in << ": " << e.what() << "\n";
      exit_code = kExitBadInput;
      return;
    }
    std::optional<mcap::FileSink> sink;
    try {
      sink.emplace(out);
    } catch (const mcap::McapError& e) {
      std::cerr << "fsd: " << e.what() << "\n";
      exit_code = kExitBadInput;
      return;
    }
    try {
      const auto report = mcap::recover(mapped->bytes(), *sink);
      sink->close();
      std::cout << format_recover_report(in, out, report);
      exit_code = kExitOk;
    } catch (const mcap::NothingToRecover& e) {
      std::cerr << "fsd: " << in << ": " << e.what() << "\n";
      exit_code = kExitBadInput;
    } catch (const mcap::McapError& e) {  // the output failed (a full disk, ...)
      std::cerr << "fsd: " << e.what() << "\n";
      exit_code = kExitMissionFailed;
    }
    if (exit_code != kExitOk) {
      sink.reset();
      std::filesystem::remove(out, ec);  // no half-written file left behind
    }
  });
}

}  // namespace

void add_mcap_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("mcap", "MCAP recordings: info FILE | recover IN OUT (docs/recording.md)");
  cmd->require_subcommand(1);
  add_info(*cmd, exit_code);
  add_recover(*cmd, exit_code);
}

}  // namespace fsd

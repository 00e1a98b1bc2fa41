#include <cstdio>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "daemon/cli/cli.hpp"
#include "daemon/cli/commands.hpp"
#include "drivers/vlp16/pcap_dump.hpp"

namespace fsd {

void add_lidar_dump_command(CLI::App& app, int& exit_code) {
  auto* cmd =
      app.add_subcommand("lidar-dump",
                         "VLP-16 returns of a capture file: a summary, or with --csv one row per valid return "
                         "(t_us,laser,azimuth_deg,distance_m,intensity,x,y,z; sensor frame, x forward, y left, z up)");
  static std::string file;
  static bool csv = false;
  static std::string laser_table;
  cmd->add_option("FILE", file, "capture file (pcap or pcapng) with VLP-16 data packets on UDP port 2368")->required();
  cmd->add_flag("--csv", csv, "print the returns as CSV instead of the summary");
  cmd->add_option("--laser-table", laser_table, "laser calibration CSV (default: the built-in VLP-16 table)");
  cmd->callback([&exit_code] {
    Vlp16Config config;
    config.laser_table = laser_table;
    try {
      if (csv) {
        std::string out(kLidarDumpCsvHeader);
        out += '\n';
        dump_vlp16_pcap(file, config, [&out](const Vlp16Return& r) {
          append_csv_row(out, r);
          if (out.size() > (1 << 16)) {
            std::fwrite(out.data(), 1, out.size(), stdout);
            out.clear();
          }
        });
        std::fwrite(out.data(), 1, out.size(), stdout);
        std::fflush(stdout);
      } else {
        const auto summary = dump_vlp16_pcap(file, config, [](const Vlp16Return&) {});
        std::cout << format_summary(file, summary);
      }
      exit_code = kExitOk;
    } catch (const PcapError& e) {
      std::fflush(stdout);
      std::cerr << "fsd lidar-dump: " << e.what() << "\n";
      exit_code = kExitBadInput;
    } catch (const LaserTableError& e) {
      std::cerr << "fsd lidar-dump: " << e.what() << "\n";
      exit_code = kExitBadInput;
    }
  });
}

}  // namespace fsd

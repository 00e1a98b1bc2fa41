// `fsd sim`: the virtual car alone, for a daemon in another process or on another computer. It speaks the real
// wire formats on the real transports: VLP-16 UDP packets to drivers.vlp16's port on sim.udp_host, NMEA on one
// pseudo-terminal and the VCU protocol on another (their paths are printed), optionally a pcap of the LiDAR.
#include <atomic>
#include <csignal>
#include <iostream>
#include <utility>

#include <CLI/CLI.hpp>
#include <boost/asio.hpp>
#include <nlohmann/json.hpp>

#include "common/clock.hpp"
#include "common/logging.hpp"
#include "daemon/cli/cli.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/stack/settings.hpp"
#include "drivers/serial/pseudo_terminal.hpp"
#include "drivers/sim/sensors/pcap_writer.hpp"
#include "drivers/sim/virtual_car.hpp"
#include "drivers/vlp16/config.hpp"

namespace fsd {

namespace {

std::atomic<bool> g_sim_stop{false};
extern "C" void on_sim_signal(int) { g_sim_stop.store(true); }

struct SimOptions {
  std::string config_file, track, lidar_pcap, udp_host = "127.0.0.1";
  double duration = 0;  // s, 0: until interrupted
  std::optional<int> seed;
  bool fast = false;
};

int run_sim(const SimOptions& o) {
  Config cfg = o.config_file.empty() ? Config(config_schema()) : Config::load(config_schema(), o.config_file);
  if (!o.track.empty()) cfg.set("run.track", o.track, "--track");
  if (o.seed) cfg.set("run.seed", *o.seed, "--seed");
  init_logging(daemon_section().read(cfg).log_level);
  const RunSettings run = run_section().read(cfg);
  const Track track = load_track(run.track, ColourConvention::named(run.colours));
  if (track.duplicates_dropped > 0)
    logger("sim")->warn("{}: {} row(s) repeat a cone already listed; each cone is placed once", run.track,
                        track.duplicates_dropped);
  const auto vlp = read_vlp16_config(cfg);

  boost::asio::io_context io;
  boost::asio::ip::udp::socket udp(io);
  boost::system::error_code ec;
  const auto addr = boost::asio::ip::make_address(o.udp_host, ec);
  if (ec) throw std::invalid_argument("--udp-host: not an IP address: " + o.udp_host);
  const boost::asio::ip::udp::endpoint lidar_to(addr, static_cast<unsigned short>(vlp.data_port));
  udp.open(lidar_to.protocol());

  PseudoTerminal gnss_pty, vcu_pty;
  std::unique_ptr<sim::PcapWriter> pcap;
  if (!o.lidar_pcap.empty()) pcap = std::make_unique<sim::PcapWriter>(o.lidar_pcap);
  std::uint64_t udp_errors = 0;

  sim::SensorSinks sinks;
  sinks.lidar = [&](Stamp t, std::span<const std::uint8_t> b) {
    udp.send_to(boost::asio::buffer(b.data(), b.size()), lidar_to, 0, ec);
    if (ec) ++udp_errors;  // nobody listening is fine; count it
    if (pcap) pcap->write(t, b);
  };
  sinks.gnss = [&](Stamp, std::span<const std::uint8_t> b) { gnss_pty.write(b); };
  sinks.vcu_status = [&](Stamp, std::span<const std::uint8_t> b) { vcu_pty.write(b); };
  auto settings = sim::read_virtual_car_settings(cfg);
  sim::VirtualCar car(track, settings, static_cast<std::uint64_t>(run.seed), sinks);

  std::cout << "fsd sim: " << track.name << ", seed " << run.seed << "\n"
            << "  VLP-16 UDP -> " << lidar_to << "\n"
            << "  GNSS-INS NMEA on " << gnss_pty.slave_path() << "  (drivers.gnss)\n"
            << "  VCU link on " << vcu_pty.slave_path() << "  (set drivers.vcu.device to this)\n"
            << std::flush;
  std::signal(SIGINT, on_sim_signal);
  std::signal(SIGTERM, on_sim_signal);
  SimulatedClock clock(1.0);
  std::array<std::uint8_t, 4096> buf{};
  for (Stamp t = 0.005; !g_sim_stop.load(); t += 0.005) {
    if (o.duration > 0 && t > o.duration + 1e-9) break;
    if (!o.fast && !clock.sleep_until(t)) break;
    while (const std::size_t n = vcu_pty.read(buf, 0.0)) car.feed_vcu(t, std::span(buf.data(), n));
    car.advance_to(t);
  }
  if (pcap) pcap->flush();
  std::cout << "fsd sim: " << car.lidar_packets() << " LiDAR packets in " << car.now() << " s, " << car.cones_hit()
            << " cone(s) hit" << std::endl;
  return kExitOk;
}

}  // namespace

void add_sim_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("sim", "The virtual car alone, on UDP and pseudo-terminals, for a daemon elsewhere");
  static SimOptions o;
  cmd->add_option("--config", o.config_file, "configuration file (JSON)")->check(CLI::ExistingFile);
  cmd->add_option("--track", o.track, "track file (EUFS/FSDS CSV)");
  cmd->add_option("--duration", o.duration, "simulated seconds to run (0: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--lidar-pcap", o.lidar_pcap, "also write the VLP-16 packets to this pcap file");
  cmd->add_option("--seed", o.seed, "seed of the random processes");
  cmd->add_option("--udp-host", o.udp_host, "where the VLP-16 packets go (default 127.0.0.1)");
  cmd->add_flag("--fast", o.fast, "do not pace in real time (for writing pcaps quickly)");
  cmd->callback([&exit_code] { exit_code = run_sim(o); });
}

}  // namespace fsd

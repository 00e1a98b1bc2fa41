#include "daemon/feeders/hardware_stats.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace fsd {

namespace {

double rate(std::uint64_t a, std::uint64_t b, double dt) { return dt > 0 && b >= a ? (b - a) / dt : 0.0; }

std::uint64_t serial_errors(const SerialCounters& c) { return c.errors + c.open_failures; }

}  // namespace

std::string rates_line(const HardwareCounters& a, const HardwareCounters& b) {
  const double dt = b.t - a.t;
  const auto& la = a.lidar;
  const auto& lb = b.lidar;
  std::string s = fmt::format(
      "lidar {:.0f} pkt/s {:.1f} scan/s [kernel drops {}, rejected {}, lost {}, socket errors {}], "
      "position {:.1f} pkt/s PPS {} [rejected {}] | "
      "gnss {:.1f} Hz, good {:.1f} Hz [bad checksum {}, malformed {}, garbage bytes {}, port errors {}] | "
      "vcu status {:.0f} Hz, command {:.0f} Hz [timeouts {}, rejected {}, lost {}, port errors {}]",
      rate(la.udp.datagrams, lb.udp.datagrams, dt), rate(la.scans, lb.scans, dt), lb.udp.kernel_drops,
      lb.decode.rejected(), lb.lost_packets, lb.udp.errors,
      rate(la.position_udp.datagrams, lb.position_udp.datagrams, dt), to_string(lb.pps), lb.position.rejected(),
      rate(a.gnss.nmea.samples, b.gnss.nmea.samples, dt), rate(a.gnss.nmea.good_samples, b.gnss.nmea.good_samples, dt),
      b.gnss.nmea.bad_checksum, b.gnss.nmea.malformed, b.gnss.nmea.framing.garbage_bytes, serial_errors(b.gnss.port),
      rate(a.vcu.session.statuses, b.vcu.session.statuses, dt),
      rate(a.vcu.session.commands_sent, b.vcu.session.commands_sent, dt), b.vcu.session.status_timeouts,
      b.vcu.session.rx.rejected_total(), b.vcu.session.rx.lost, serial_errors(b.vcu.port));
  if (b.camera) {
    const std::uint64_t before = a.camera ? a.camera->frames : 0;
    s += fmt::format(" | camera {:.1f} fps [dropped {}, read failures {}, open failures {}]",
                     rate(before, b.camera->frames, dt), b.camera->dropped, b.camera->read_failures,
                     b.camera->open_failures);
  }
  s += fmt::format(" | control {:.0f} Hz [overruns {}, frames dropped {}]",
                   rate(a.control_cycles, b.control_cycles, dt), b.control_overruns, b.frames_dropped);
  return s;
}

nlohmann::json counters_json(const HardwareCounters& c) {
  using nlohmann::json;
  const auto serial = [](const SerialCounters& p) {
    return json{{"bytes_in", p.bytes_in},
                {"bytes_out", p.bytes_out},
                {"opens", p.opens},
                {"open_failures", p.open_failures},
                {"errors", p.errors},
                {"gaps", p.gaps},
                {"writes_dropped", p.writes_dropped}};
  };
  json j;
  const auto& l = c.lidar;
  j["vlp16"] = {{"datagrams", l.udp.datagrams},
                {"bytes", l.udp.bytes},
                {"kernel_drops", l.udp.kernel_drops},
                {"socket_errors", l.udp.errors},
                {"packets", l.decode.packets},
                {"rejected", l.decode.rejected()},
                {"returns", l.decode.returns},
                {"lost_packets", l.lost_packets},
                {"scans", l.scans},
                {"position",
                 {{"datagrams", l.position_udp.datagrams},
                  {"packets", l.position.packets},
                  {"rejected", l.position.rejected()},
                  {"pps", std::string(to_string(l.pps))},
                  {"nmea_valid", l.position.nmea_valid},
                  {"nmea_absent", l.position.nmea_absent},
                  {"nmea_bad_checksum", l.position.nmea_bad_checksum},
                  {"nmea_malformed", l.position.nmea_malformed}}}};
  const auto& g = c.gnss.nmea;
  j["gnss"] = {{"bytes", g.framing.bytes},
               {"garbage_bytes", g.framing.garbage_bytes},
               {"lines", g.lines},
               {"bad_checksum", g.bad_checksum},
               {"missing_checksum", g.missing_checksum},
               {"malformed", g.malformed},
               {"sentences", g.sentences},
               {"samples", g.samples},
               {"good_samples", g.good_samples},
               {"port", serial(c.gnss.port)}};
  const auto& v = c.vcu.session;
  j["vcu"] = {{"commands_sent", v.commands_sent},
              {"safe_commands_sent", v.safe_commands_sent},
              {"statuses", v.statuses},
              {"status_timeouts", v.status_timeouts},
              {"frames", v.rx.frames},
              {"rejected", v.rx.rejected_total()},
              {"lost", v.rx.lost},
              {"garbage_bytes", v.rx.garbage_bytes},
              {"port", serial(c.vcu.port)}};
  if (c.camera)
    j["camera"] = {{"frames", c.camera->frames},
                   {"dropped", c.camera->dropped},
                   {"read_failures", c.camera->read_failures},
                   {"open_failures", c.camera->open_failures},
                   {"reconnects", c.camera->reconnects},
                   {"size_mismatches", c.camera->size_mismatches}};
  else
    j["camera"] = nullptr;
  j["control"] = {{"cycles", c.control_cycles}, {"overruns", c.control_overruns}, {"frames_dropped", c.frames_dropped}};
  return j;
}

}  // namespace fsd

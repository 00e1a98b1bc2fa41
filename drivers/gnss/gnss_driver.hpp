#pragma once
// GNSS-INS driver: NMEA 0183 bytes in, GnssSample out. A pure byte-stream consumer; the daemon wires a serial
// port (or a recording) to feed() from one thread and receives samples by callback on that thread.
//
//   bytes ─► NmeaLineSplitter ─► nmea::unframe (checksum) ─► parse_sentence ─► EpochAssembler ─► sample
//
// A sample per receiver epoch (see epoch_assembler.hpp for when it is emitted):
//   - lat/lon/alt: the antenna position the receiver reports, alt_m above the WGS-84 ellipsoid
//     (GGA altitude + geoid separation); enu: the rear-axle centre in the local ENU frame, i.e. the antenna
//     position minus the lever arm rotated by heading, pitch and roll (only the height part of the lever arm when
//     the epoch has no heading);
//   - heading/course: NMEA degrees clockwise from true north turned into ENU yaw (counter-clockwise from east);
//   - roll/pitch: ISO 8855 (roll positive right side down, pitch positive nose down) from PASHR;
//   - yaw_rate: from ROT (degrees per minute, positive turning right) as rad/s, positive turning left;
//   - good: fix quality, satellites, HDOP, differential age, heading and RMC validity per GnssConfig, and an origin.
// An epoch with GGA quality 0 or empty coordinates still gives a sample (fix_quality 0, good false, enu zero) so
// that watchdogs see the stream alive and the fix lost; an epoch without GGA gives none.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>

#include "common/geodesy.hpp"
#include "common/types.hpp"
#include "drivers/gnss/epoch_assembler.hpp"
#include "drivers/gnss/gnss_config.hpp"
#include "drivers/gnss/nmea_line_splitter.hpp"

namespace fsd {

struct GnssCounters {
  NmeaLineSplitter::Counters framing;  // bytes, garbage, overlong, truncated, bad characters
  std::uint64_t lines = 0;             // complete lines handed to the checksum check
  std::uint64_t missing_checksum = 0;
  std::uint64_t bad_checksum = 0;  // malformed or mismatching '*HH'
  std::uint64_t bad_address = 0;
  std::uint64_t unsupported = 0;  // valid sentences this driver does not use (GSV, ZDA, ...)
  std::uint64_t malformed = 0;    // a field that cannot be what the sentence defines there
  std::uint64_t sentences = 0;    // parsed and used
  std::uint64_t late_sentences = 0;
  std::uint64_t epochs_without_gga = 0;
  std::uint64_t samples = 0;
  std::uint64_t good_samples = 0;
};

class GnssDriver {
 public:
  using SampleCallback = std::function<void(const GnssSample&)>;

  // Throws std::invalid_argument for a config the section's bounds cannot catch (unknown min_fix or emit_on).
  GnssDriver(const GnssConfig& config, SampleCallback on_sample);

  // Bytes as they arrive from the port, in any chunking; `receive_time` is when this chunk arrived.
  void feed(std::span<const std::uint8_t> bytes, Stamp receive_time);

  GnssCounters counters() const;
  // The local ENU origin, once configured or taken from the first good fix.
  const std::optional<LocalEnu>& origin() const { return origin_; }
  // Sentence type that ends an epoch, configured or learnt; nullopt while still learning.
  std::optional<SentenceType> epoch_ender() const { return assembler_.ender(); }

 private:
  void on_line(std::string_view line, Stamp t);
  void on_epoch(const Epoch& e);

  GnssConfig config_;
  int min_fix_rank_;
  Vec3 lever_;
  SampleCallback on_sample_;
  NmeaLineSplitter splitter_;
  EpochAssembler assembler_;
  std::optional<LocalEnu> origin_;
  GnssCounters counters_;
};

}  // namespace fsd

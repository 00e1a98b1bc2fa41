#include "drivers/vlp16/position_packet.hpp"

#include "common/wire/nmea.hpp"

#include <algorithm>

#include "common/wire/vlp16_format.hpp"

namespace fsd {

namespace w = wire::vlp16;

std::string_view to_string(PpsState s) {
  switch (s) {
    case PpsState::Absent:
      return "absent";
    case PpsState::Synchronizing:
      return "synchronizing";
    case PpsState::Locked:
      return "locked";
    case PpsState::Error:
      return "error";
  }
  return "?";
}

std::string_view to_string(NmeaState s) {
  switch (s) {
    case NmeaState::Absent:
      return "absent";
    case NmeaState::Valid:
      return "valid";
    case NmeaState::BadChecksum:
      return "bad checksum";
    case NmeaState::Malformed:
      return "malformed";
  }
  return "?";
}

std::string_view to_string(PositionStatus s) {
  switch (s) {
    case PositionStatus::Ok:
      return "ok";
    case PositionStatus::WrongSize:
      return "wrong size";
    case PositionStatus::BadPpsState:
      return "bad PPS state";
  }
  return "?";
}

namespace {

// Framing and checksum are the NMEA codec's (common/wire/nmea.hpp); a wrong checksum is still well formed.
bool well_formed(std::string_view s) {
  const auto e = nmea::unframe(s).error;
  return e == nmea::FrameError::None || e == nmea::FrameError::ChecksumMismatch;
}

}  // namespace

bool nmea_checksum_ok(std::string_view s) { return nmea::unframe(s).error == nmea::FrameError::None; }

PositionStatus parse_position_packet(std::span<const std::uint8_t> p, PositionPacket& out) {
  if (p.size() != w::kPositionPacketSize) return PositionStatus::WrongSize;
  const auto pps = p[w::kPositionPpsOffset];
  if (pps > static_cast<std::uint8_t>(PpsState::Error)) return PositionStatus::BadPpsState;
  out.timestamp_us = w::read_u32(p, w::kPositionTimestampOffset);
  out.pps = static_cast<PpsState>(pps);

  const auto field = p.subspan(w::kPositionNmeaOffset, w::kPositionNmeaMax);
  const auto nul = std::find(field.begin(), field.end(), std::uint8_t{0});
  std::string text(field.begin(), nul);
  while (!text.empty() && (text.back() == '\r' || text.back() == '\n')) text.pop_back();
  const bool printable = std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7F; });
  if (nul == field.end() || !printable || (!text.empty() && !well_formed(text))) {
    out.nmea_state = NmeaState::Malformed;
    out.nmea.clear();
  } else {
    out.nmea_state = text.empty()             ? NmeaState::Absent
                     : nmea_checksum_ok(text) ? NmeaState::Valid
                                              : NmeaState::BadChecksum;
    out.nmea = std::move(text);
  }
  return PositionStatus::Ok;
}

PositionStatus PositionPacketParser::parse(std::span<const std::uint8_t> packet, PositionPacket& out) {
  const auto status = parse_position_packet(packet, out);
  switch (status) {
    case PositionStatus::Ok:
      ++counters_.packets;
      break;
    case PositionStatus::WrongSize:
      ++counters_.wrong_size;
      return status;
    case PositionStatus::BadPpsState:
      ++counters_.bad_pps_state;
      return status;
  }
  switch (out.nmea_state) {
    case NmeaState::Valid:
      ++counters_.nmea_valid;
      break;
    case NmeaState::Absent:
      ++counters_.nmea_absent;
      break;
    case NmeaState::BadChecksum:
      ++counters_.nmea_bad_checksum;
      break;
    case NmeaState::Malformed:
      ++counters_.nmea_malformed;
      break;
  }
  return status;
}

}  // namespace fsd

#include "common/wire/vcu_protocol.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <boost/crc.hpp>

namespace fsd::wire::vcu {

namespace {

using Bytes = std::vector<std::uint8_t>;

// Scaled integer of a physical value; saturates at the type's range, NaN → 0.
template <class Int>
Int scaled(double value, double unit) {
  if (std::isnan(value)) return 0;
  const double counts = std::round(value / unit);
  const double lo = std::numeric_limits<Int>::min(), hi = std::numeric_limits<Int>::max();
  return static_cast<Int>(std::clamp(counts, lo, hi));
}

void put_u16(Bytes& b, std::uint16_t v) {
  b.push_back(static_cast<std::uint8_t>(v & 0xFF));
  b.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put_i16(Bytes& b, std::int16_t v) { put_u16(b, static_cast<std::uint16_t>(v)); }
void put_u32(Bytes& b, std::uint32_t v) {
  put_u16(b, static_cast<std::uint16_t>(v & 0xFFFF));
  put_u16(b, static_cast<std::uint16_t>(v >> 16));
}
std::uint16_t get_u16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
std::int16_t get_i16(const std::uint8_t* p) { return static_cast<std::int16_t>(get_u16(p)); }
std::uint32_t get_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(get_u16(p)) | (static_cast<std::uint32_t>(get_u16(p + 2)) << 16);
}

constexpr std::uint8_t kMaxAsState = static_cast<std::uint8_t>(AsState::Finished);
constexpr std::uint8_t kMaxMission = static_cast<std::uint8_t>(Mission::EbsTest);
constexpr std::uint8_t kMaxAsRequest = static_cast<std::uint8_t>(AsRequest::Emergency);
constexpr std::uint8_t kStatusFlagsKnown = kStatusResGo | kStatusResEmergency | kStatusEbsActive;

std::optional<Command> parse_command(std::span<const std::uint8_t> p) {
  if (p.size() != kCommandPayloadSize) return std::nullopt;
  if ((p[4] & ~kCmdBrakeHard) != 0 || p[5] > kMaxAsRequest || p[6] > kMaxMission || p[7] != 0) return std::nullopt;
  Command c;
  c.steering = get_i16(&p[0]) * kAngleUnit;
  c.target_speed = get_u16(&p[2]) * kSpeedUnit;
  c.brake_hard = (p[4] & kCmdBrakeHard) != 0;
  c.as_request = static_cast<AsRequest>(p[5]);
  c.mission = static_cast<Mission>(p[6]);
  return c;
}

std::optional<VcuStatus> parse_status(std::span<const std::uint8_t> p) {
  if (p.size() != kStatusPayloadSize) return std::nullopt;
  if (p[0] > kMaxAsState || p[1] > kMaxMission || (p[2] & ~kStatusFlagsKnown) != 0 || p[3] != 0) return std::nullopt;
  VcuStatus s;
  s.as_state = static_cast<AsState>(p[0]);
  s.mission = static_cast<Mission>(p[1]);
  s.res_go = (p[2] & kStatusResGo) != 0;
  s.res_emergency = (p[2] & kStatusResEmergency) != 0;
  s.ebs_active = (p[2] & kStatusEbsActive) != 0;
  s.steering_measured = get_i16(&p[4]) * kAngleUnit;
  for (std::size_t i = 0; i < 4; ++i) s.wheel_speeds[i] = get_i16(&p[6 + 2 * i]) * kSpeedUnit;
  s.faults = get_u32(&p[14]);
  return s;
}

}  // namespace

std::string_view to_string(AsRequest r) {
  switch (r) {
    case AsRequest::None:
      return "none";
    case AsRequest::Ready:
      return "ready";
    case AsRequest::Finished:
      return "finished";
    case AsRequest::Emergency:
      return "emergency";
  }
  return "?";
}

std::string_view to_string(Reject r) {
  switch (r) {
    case Reject::BadCrc:
      return "bad_crc";
    case Reject::Truncated:
      return "truncated";
    case Reject::BadVersion:
      return "bad_version";
    case Reject::Oversized:
      return "oversized";
    case Reject::UnknownType:
      return "unknown_type";
    case Reject::BadPayload:
      return "bad_payload";
    case Reject::Replayed:
      return "replayed";
    case Reject::OutOfOrder:
      return "out_of_order";
  }
  return "?";
}

std::uint64_t DecoderCounters::rejected_total() const {
  std::uint64_t n = 0;
  for (auto v : rejected) n += v;
  return n;
}

Command make_command(const ControlCommand& c, AsRequest request, Mission mission) {
  return Command{c.steering, c.target_speed, c.brake_hard, request, mission};
}

std::uint16_t crc16(std::span<const std::uint8_t> bytes) {
  boost::crc_optimal<16, 0x1021, 0xFFFF, 0, false, false> crc;
  crc.process_bytes(bytes.data(), bytes.size());
  return crc.checksum();
}

std::vector<std::uint8_t> encode_frame(MessageType type, std::uint16_t seq, std::span<const std::uint8_t> payload,
                                       std::uint8_t version) {
  if (payload.size() > kMaxPayload) throw std::invalid_argument("VCU frame payload larger than 64 bytes");
  Bytes f;
  f.reserve(kHeaderSize + payload.size() + kCrcSize);
  f.push_back(kSync0);
  f.push_back(kSync1);
  f.push_back(static_cast<std::uint8_t>(payload.size()));
  f.push_back(version);
  f.push_back(static_cast<std::uint8_t>(type));
  put_u16(f, seq);
  f.insert(f.end(), payload.begin(), payload.end());
  put_u16(f, crc16(std::span(f).subspan(2)));
  return f;
}

std::vector<std::uint8_t> encode(const Command& c, std::uint16_t seq) {
  Bytes p;
  p.reserve(kCommandPayloadSize);
  put_i16(p, scaled<std::int16_t>(c.steering, kAngleUnit));
  put_u16(p, scaled<std::uint16_t>(c.target_speed, kSpeedUnit));
  p.push_back(c.brake_hard ? kCmdBrakeHard : 0);
  p.push_back(static_cast<std::uint8_t>(c.as_request));
  p.push_back(static_cast<std::uint8_t>(c.mission));
  p.push_back(0);
  return encode_frame(MessageType::Command, seq, p);
}

std::vector<std::uint8_t> encode(const VcuStatus& s, std::uint16_t seq) {
  Bytes p;
  p.reserve(kStatusPayloadSize);
  p.push_back(static_cast<std::uint8_t>(s.as_state));
  p.push_back(static_cast<std::uint8_t>(s.mission));
  p.push_back(static_cast<std::uint8_t>((s.res_go ? kStatusResGo : 0) | (s.res_emergency ? kStatusResEmergency : 0) |
                                        (s.ebs_active ? kStatusEbsActive : 0)));
  p.push_back(0);
  put_i16(p, scaled<std::int16_t>(s.steering_measured, kAngleUnit));
  for (double w : s.wheel_speeds) put_i16(p, scaled<std::int16_t>(w, kSpeedUnit));
  put_u32(p, s.faults);
  return encode_frame(MessageType::Status, seq, p);
}

bool SendSchedule::due(Stamp now) {
  constexpr Duration kSlack = 1e-9;  // absorbs the rounding of the caller's own time steps
  if (now + kSlack < next()) return false;
  const auto behind = static_cast<std::uint64_t>(std::floor((now - origin_) / period_ + kSlack)) + 1;
  n_ = std::max(n_ + 1, behind);
  return true;
}

Decoder::Decoder(Handlers h, DecoderConfig cfg) : h_(std::move(h)), cfg_(cfg) { buf_.reserve(2 * kMaxFrameSize); }

void Decoder::feed(std::span<const std::uint8_t> bytes) {
  // Appends in bounded pieces so the buffer never holds more than one frame plus one piece.
  constexpr std::size_t kPiece = 256;
  while (!bytes.empty()) {
    const std::size_t n = std::min(kPiece, bytes.size());
    buf_.insert(buf_.end(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
    bytes = bytes.subspan(n);
    parse();
  }
}

void Decoder::reset() {
  if (!buf_.empty()) {
    if (buf_[0] == kSync0) {
      reject(Reject::Truncated, 0);
    } else {
      counters_.garbage_bytes += buf_.size();
    }
  }
  buf_.clear();
  last_seq_.reset();
  last_old_seq_.reset();
  old_run_ = 0;
}

void Decoder::parse() {
  std::size_t pos = 0;
  while (pos < buf_.size()) {
    // Hunt for the sync pair; a lone 0xA5 at the end may be the start of one.
    if (buf_[pos] != kSync0 || (pos + 1 < buf_.size() && buf_[pos + 1] != kSync1)) {
      ++counters_.garbage_bytes;
      ++pos;
      continue;
    }
    if (pos > 0) {
      buf_.erase(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(pos));
      pos = 0;
    }
    const std::size_t used = try_frame();
    if (used == 0) return;  // need more bytes
    pos = used;
  }
  buf_.erase(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(std::min(pos, buf_.size())));
}

std::size_t Decoder::try_frame() {
  // buf_ starts with a sync pair (or a lone 0xA5 at its end).
  if (buf_.size() < kHeaderSize) return 0;
  const std::size_t len = buf_[2];
  const std::uint16_t seq = get_u16(&buf_[5]);
  if (len > kMaxPayload) {
    reject(Reject::Oversized, seq);
    return 1;  // resynchronise from the next byte
  }
  const std::size_t frame_size = kHeaderSize + len + kCrcSize;
  if (buf_.size() < frame_size) return 0;

  const auto frame = std::span(buf_).first(frame_size);
  if (crc16(frame.subspan(2, kHeaderSize - 2 + len)) != get_u16(&frame[kHeaderSize + len])) {
    // A sync pair inside the frame means this one was cut short and the next frame started: resume there.
    for (std::size_t i = 2; i + 1 < frame_size; ++i) {
      if (frame[i] == kSync0 && frame[i + 1] == kSync1) {
        reject(Reject::Truncated, seq);
        return i;
      }
    }
    reject(Reject::BadCrc, seq);
    return 1;
  }
  if (frame[3] != kVersion) {
    reject(Reject::BadVersion, seq);
    return frame_size;
  }
  const auto payload = frame.subspan(kHeaderSize, len);
  const auto type = frame[4];
  if (type == static_cast<std::uint8_t>(MessageType::Command) && h_.on_command) {
    const auto c = parse_command(payload);
    if (!c) {
      reject(Reject::BadPayload, seq);
    } else if (accept_sequence(seq)) {
      ++counters_.frames;
      h_.on_command(*c, seq);
    }
  } else if (type == static_cast<std::uint8_t>(MessageType::Status) && h_.on_status) {
    const auto s = parse_status(payload);
    if (!s) {
      reject(Reject::BadPayload, seq);
    } else if (accept_sequence(seq)) {
      ++counters_.frames;
      h_.on_status(*s, seq);
    }
  } else {
    reject(Reject::UnknownType, seq);
  }
  return frame_size;
}

bool Decoder::accept_sequence(std::uint16_t seq) {
  if (last_seq_) {
    // Serial-number arithmetic: the signed 16-bit difference orders counters across the wrap.
    const auto d = static_cast<std::int16_t>(static_cast<std::uint16_t>(seq - *last_seq_));
    if (d == 0) {
      reject(Reject::Replayed, seq);
      return false;
    }
    if (d < 0) {
      const bool in_run =
          last_old_seq_ && static_cast<std::int16_t>(static_cast<std::uint16_t>(seq - *last_old_seq_)) > 0;
      old_run_ = in_run ? old_run_ + 1 : 1;
      last_old_seq_ = seq;
      if (cfg_.restart_after <= 0 || old_run_ < cfg_.restart_after) {
        reject(Reject::OutOfOrder, seq);
        return false;
      }
      ++counters_.restarts;
    } else {
      counters_.lost += static_cast<std::uint64_t>(d - 1);
    }
  }
  last_seq_ = seq;
  last_old_seq_.reset();
  old_run_ = 0;
  return true;
}

void Decoder::reject(Reject r, std::uint16_t seq) {
  ++counters_.rejected[static_cast<std::size_t>(r)];
  if (h_.on_reject) h_.on_reject(r, seq);
}

}  // namespace fsd::wire::vcu

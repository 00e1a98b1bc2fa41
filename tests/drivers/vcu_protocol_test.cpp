// The VCU frame codec against hand-built bytes (the frames below were written out by hand from the layout in
// docs/vcu-protocol.md and their CRCs computed with Python's binascii.crc_hqx(body, 0xFFFF), an independent
// CRC-16/CCITT-FALSE implementation).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string_view>

#include "common/wire/vcu_protocol.hpp"

namespace fsd::wire::vcu {
namespace {

using Bytes = std::vector<std::uint8_t>;

const Bytes kCommandFrame = {0xa5, 0x5a, 0x08, 0x01, 0x01, 0x34, 0x12, 0xd2, 0x04,
                             0xd2, 0x04, 0x01, 0x01, 0x03, 0x00, 0xfd, 0xa7};
const Bytes kStatusFrame = {0xa5, 0x5a, 0x12, 0x01, 0x81, 0xff, 0xff, 0x02, 0x03, 0x05, 0x00, 0x3c, 0xf6, 0xe8,
                            0x03, 0xff, 0xff, 0xff, 0x7f, 0x00, 0x80, 0x21, 0x00, 0x00, 0x80, 0xa1, 0x48};

// Collects what a decoder delivers.
struct Sink {
  std::vector<std::pair<Command, std::uint16_t>> commands;
  std::vector<std::pair<VcuStatus, std::uint16_t>> statuses;
  Decoder decoder{Decoder::Handlers{[this](const Command& c, std::uint16_t s) { commands.emplace_back(c, s); },
                                    [this](const VcuStatus& st, std::uint16_t s) { statuses.emplace_back(st, s); },
                                    nullptr}};
  void feed(const Bytes& b) { decoder.feed(b); }
  std::uint64_t rejected(Reject r) const { return decoder.counters().count(r); }
};

Bytes cat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

Bytes command_frame(std::uint16_t seq, double steering = 0.0) {
  return encode(Command{steering, 1.0, false, AsRequest::None, Mission::Trackdrive}, seq);
}

TEST(VcuProtocol, CrcMatchesThePublishedCheckValue) {
  constexpr std::string_view check = "123456789";
  const Bytes b(check.begin(), check.end());
  EXPECT_EQ(crc16(b), 0x29B1);
}

TEST(VcuProtocol, CommandEncodesToTheDocumentedBytes) {
  Command c;
  c.steering = 0.1234;
  c.target_speed = 12.34;
  c.brake_hard = true;
  c.as_request = AsRequest::Ready;
  c.mission = Mission::Trackdrive;
  EXPECT_EQ(encode(c, 0x1234), kCommandFrame);
  EXPECT_EQ(kCommandFrame.size(), kCommandFrameSize);
}

TEST(VcuProtocol, StatusEncodesToTheDocumentedBytes) {
  VcuStatus s;
  s.as_state = AsState::Driving;
  s.mission = Mission::Trackdrive;
  s.res_go = true;
  s.ebs_active = true;
  s.steering_measured = -0.25;
  s.wheel_speeds = {10.0, -0.01, 327.67, -327.68};
  s.faults = 0x80000021;
  EXPECT_EQ(encode(s, 0xFFFF), kStatusFrame);
  EXPECT_EQ(kStatusFrame.size(), kStatusFrameSize);
}

TEST(VcuProtocol, DecodesTheDocumentedBytes) {
  Sink k, vcu;  // one decoder per direction: the sequence counter is the sender's
  vcu.feed(kCommandFrame);
  k.feed(kStatusFrame);
  k.commands = vcu.commands;
  ASSERT_EQ(k.commands.size(), 1u);
  const auto& [c, cseq] = k.commands[0];
  EXPECT_EQ(cseq, 0x1234);
  EXPECT_DOUBLE_EQ(c.steering, 1234 * 1e-4);
  EXPECT_DOUBLE_EQ(c.target_speed, 1234 * 0.01);
  EXPECT_TRUE(c.brake_hard);
  EXPECT_EQ(c.as_request, AsRequest::Ready);
  EXPECT_EQ(c.mission, Mission::Trackdrive);

  ASSERT_EQ(k.statuses.size(), 1u);
  const auto& [s, sseq] = k.statuses[0];
  EXPECT_EQ(sseq, 0xFFFF);
  EXPECT_EQ(s.as_state, AsState::Driving);
  EXPECT_EQ(s.mission, Mission::Trackdrive);
  EXPECT_TRUE(s.res_go);
  EXPECT_FALSE(s.res_emergency);
  EXPECT_TRUE(s.ebs_active);
  EXPECT_DOUBLE_EQ(s.steering_measured, -2500 * 1e-4);
  EXPECT_DOUBLE_EQ(s.wheel_speeds[0], 1000 * 0.01);
  EXPECT_DOUBLE_EQ(s.wheel_speeds[1], -1 * 0.01);
  EXPECT_DOUBLE_EQ(s.wheel_speeds[2], 32767 * 0.01);
  EXPECT_DOUBLE_EQ(s.wheel_speeds[3], -32768 * 0.01);
  EXPECT_EQ(s.faults, 0x80000021u);
  EXPECT_EQ(k.decoder.counters().frames, 1u);
  EXPECT_EQ(k.decoder.counters().rejected_total(), 0u);
}

TEST(VcuProtocol, CommandRoundTripsEveryEnumValueAndTheRangeEnds) {
  const AsRequest requests[] = {AsRequest::None, AsRequest::Ready, AsRequest::Finished, AsRequest::Emergency};
  const Mission missions[] = {Mission::None,      Mission::Acceleration, Mission::Skidpad, Mission::Trackdrive,
                              Mission::Autocross, Mission::Inspection,   Mission::EbsTest};
  Sink k;
  std::uint16_t seq = 0;
  for (auto r : requests) {
    for (auto m : missions) {
      k.feed(encode(Command{-0.5, 0.0, false, r, m}, seq++));
      ASSERT_EQ(k.commands.size(), seq);
      EXPECT_EQ(k.commands.back().first.as_request, r);
      EXPECT_EQ(k.commands.back().first.mission, m);
      EXPECT_DOUBLE_EQ(k.commands.back().first.steering, -5000 * 1e-4);
      EXPECT_FALSE(k.commands.back().first.brake_hard);
    }
  }
  // (value sent, value received): ends of the scaled ranges, saturation, rounding and NaN.
  const std::pair<double, double> steering[] = {{3.2767, 3.2767},   {-3.2768, -3.2768}, {10.0, 3.2767},
                                                {-10.0, -3.2768},   {0.00004, 0.0},     {-0.00016, -0.0002},
                                                {std::nan(""), 0.0}};
  for (auto [sent, got] : steering) {
    k.feed(encode(Command{sent, 0.0, false, AsRequest::None, Mission::None}, seq++));
    EXPECT_NEAR(k.commands.back().first.steering, got, 1e-12) << sent;
  }
  const std::pair<double, double> speed[] = {{0.0, 0.0},
                                             {655.35, 655.35},
                                             {1e9, 655.35},
                                             {-3.0, 0.0},
                                             {std::numeric_limits<double>::infinity(), 655.35},
                                             {std::nan(""), 0.0},
                                             {0.005, 0.01}};
  for (auto [sent, got] : speed) {
    k.feed(encode(Command{0.0, sent, true, AsRequest::None, Mission::None}, seq++));
    EXPECT_NEAR(k.commands.back().first.target_speed, got, 1e-12) << sent;
  }
  EXPECT_EQ(k.decoder.counters().rejected_total(), 0u);
}

TEST(VcuProtocol, StatusRoundTripsEveryStateAndFlag) {
  const AsState states[] = {AsState::Off, AsState::Ready, AsState::Driving, AsState::Emergency, AsState::Finished};
  Sink k;
  std::uint16_t seq = 100;
  for (auto st : states) {
    for (int flags = 0; flags < 8; ++flags) {
      VcuStatus s;
      s.as_state = st;
      s.mission = Mission::EbsTest;
      s.res_go = flags & 1;
      s.res_emergency = flags & 2;
      s.ebs_active = flags & 4;
      s.steering_measured = -3.2768;
      s.wheel_speeds = {-327.68, 327.67, 500.0, -0.004};
      s.faults = 0xFFFFFFFF;
      k.feed(encode(s, seq++));
      const auto& r = k.statuses.back().first;
      EXPECT_EQ(r.as_state, st);
      EXPECT_EQ(r.mission, Mission::EbsTest);
      EXPECT_EQ(r.res_go, bool(flags & 1));
      EXPECT_EQ(r.res_emergency, bool(flags & 2));
      EXPECT_EQ(r.ebs_active, bool(flags & 4));
      EXPECT_DOUBLE_EQ(r.steering_measured, -3.2768);
      EXPECT_DOUBLE_EQ(r.wheel_speeds[0], -327.68);
      EXPECT_DOUBLE_EQ(r.wheel_speeds[1], 327.67);
      EXPECT_DOUBLE_EQ(r.wheel_speeds[2], 327.67);  // saturated
      EXPECT_DOUBLE_EQ(r.wheel_speeds[3], 0.0);
      EXPECT_EQ(r.faults, 0xFFFFFFFFu);
    }
  }
  EXPECT_EQ(k.statuses.size(), 40u);
}

TEST(VcuProtocol, AnyChunkingGivesTheSameFrames) {
  Bytes stream;
  for (std::uint16_t s = 0; s < 20; ++s) {
    const auto f = command_frame(s, s * 0.01);
    stream.insert(stream.end(), f.begin(), f.end());
  }
  for (std::size_t chunk : {1u, 2u, 3u, 7u, 16u, 17u, 100u, 1000u}) {
    Sink k;
    for (std::size_t i = 0; i < stream.size(); i += chunk) {
      const auto n = std::min(chunk, stream.size() - i);
      k.decoder.feed(std::span(stream).subspan(i, n));
    }
    ASSERT_EQ(k.commands.size(), 20u) << chunk;
    EXPECT_NEAR(k.commands[19].first.steering, 0.19, 1e-12);
    EXPECT_EQ(k.decoder.buffered(), 0u);
  }
}

TEST(VcuProtocol, CorruptFrameIsRejectedAndTheNextOneDecodes) {
  for (std::size_t i = 2; i < kCommandFrame.size(); ++i) {
    Sink k;
    Bytes bad = kCommandFrame;
    bad[i] ^= 0x10;
    k.feed(cat({bad, command_frame(0x2000)}));
    ASSERT_EQ(k.commands.size(), 1u) << "byte " << i;
    EXPECT_EQ(k.commands[0].second, 0x2000);
    // A corrupt length byte makes the frame swallow the next one's start: counted truncated instead.
    const auto kind = i == 2 ? Reject::Truncated : Reject::BadCrc;
    EXPECT_EQ(k.rejected(kind), 1u) << "byte " << i;
  }
}

TEST(VcuProtocol, TruncatedFrameIsRejectedAndTheNextOneDecodes) {
  Sink k;
  const Bytes cut(kStatusFrame.begin(), kStatusFrame.begin() + 12);
  k.feed(cat({cut, kCommandFrame}));
  EXPECT_EQ(k.rejected(Reject::Truncated), 1u);
  ASSERT_EQ(k.commands.size(), 1u);
  EXPECT_EQ(k.commands[0].second, 0x1234);
  EXPECT_TRUE(k.statuses.empty());

  // A partial frame pending when the stream is reset (port lost) is counted truncated too.
  k.feed(Bytes(kStatusFrame.begin(), kStatusFrame.begin() + 5));
  k.decoder.reset();
  EXPECT_EQ(k.rejected(Reject::Truncated), 2u);
  EXPECT_EQ(k.decoder.buffered(), 0u);
}

TEST(VcuProtocol, WrongVersionIsRejected) {
  Sink k;
  const Bytes payload(kCommandFrame.begin() + 7, kCommandFrame.end() - 2);
  k.feed(encode_frame(MessageType::Command, 1, payload, 2));
  k.feed(encode_frame(MessageType::Command, 2, payload, 0));
  EXPECT_EQ(k.rejected(Reject::BadVersion), 2u);
  EXPECT_TRUE(k.commands.empty());
  k.feed(encode_frame(MessageType::Command, 3, payload));
  EXPECT_EQ(k.commands.size(), 1u);
}

TEST(VcuProtocol, OversizedLengthIsRejectedAndResynchronises) {
  Sink k;
  // Header claiming 65 payload bytes: the largest allowed is 64.
  const Bytes oversized = {0xa5, 0x5a, 65, 0x01, 0x01, 0x00, 0x00};
  k.feed(cat({oversized, kCommandFrame}));
  EXPECT_EQ(k.rejected(Reject::Oversized), 1u);
  EXPECT_EQ(k.commands.size(), 1u);
  EXPECT_THROW(encode_frame(MessageType::Command, 0, Bytes(65, 0)), std::invalid_argument);
}

TEST(VcuProtocol, UnknownTypeAndBadPayloadAreRejected) {
  Sink k;
  Bytes payload(kCommandFrame.begin() + 7, kCommandFrame.end() - 2);
  k.feed(encode_frame(static_cast<MessageType>(0x42), 1, payload));
  EXPECT_EQ(k.rejected(Reject::UnknownType), 1u);

  Bytes p = payload;
  p[5] = 4;  // AS request beyond Emergency
  k.feed(encode_frame(MessageType::Command, 2, p));
  p = payload;
  p[6] = 7;  // mission beyond EbsTest
  k.feed(encode_frame(MessageType::Command, 3, p));
  p = payload;
  p[4] = 0x02;  // reserved flag bit
  k.feed(encode_frame(MessageType::Command, 4, p));
  k.feed(encode_frame(MessageType::Command, 5, Bytes(payload.begin(), payload.end() - 1)));  // short
  Bytes status(kStatusFrame.begin() + 7, kStatusFrame.end() - 2);
  status[0] = 5;  // AS state beyond Finished
  k.feed(encode_frame(MessageType::Status, 6, status));
  EXPECT_EQ(k.rejected(Reject::BadPayload), 5u);
  EXPECT_TRUE(k.commands.empty());
  EXPECT_TRUE(k.statuses.empty());
}

TEST(VcuProtocol, ReceiverRejectsTheDirectionItDoesNotExpect) {
  Decoder vcu_side({[](const Command&, std::uint16_t) {}, nullptr, nullptr});
  vcu_side.feed(kStatusFrame);
  EXPECT_EQ(vcu_side.counters().count(Reject::UnknownType), 1u);
  vcu_side.feed(kCommandFrame);
  EXPECT_EQ(vcu_side.counters().frames, 1u);
}

TEST(VcuProtocol, ReplayedAndOutOfOrderFramesAreRejected) {
  Sink k;
  k.feed(command_frame(10));
  k.feed(command_frame(10));  // replay
  k.feed(command_frame(9));   // older
  k.feed(command_frame(11));
  k.feed(command_frame(11));
  k.feed(command_frame(5));
  k.feed(command_frame(14));  // 12 and 13 lost
  EXPECT_EQ(k.rejected(Reject::Replayed), 2u);
  EXPECT_EQ(k.rejected(Reject::OutOfOrder), 2u);
  ASSERT_EQ(k.commands.size(), 3u);
  EXPECT_EQ(k.commands[2].second, 14);
  EXPECT_EQ(k.decoder.counters().lost, 2u);
}

TEST(VcuProtocol, SequenceWrapsAround) {
  Sink k;
  for (std::uint32_t s = 65530; s < 65530 + 12; ++s) k.feed(command_frame(static_cast<std::uint16_t>(s)));
  EXPECT_EQ(k.commands.size(), 12u);
  EXPECT_EQ(k.commands.back().second, 5);
  EXPECT_EQ(k.decoder.counters().rejected_total(), 0u);
  k.feed(command_frame(65535));  // older across the wrap
  EXPECT_EQ(k.rejected(Reject::OutOfOrder), 1u);
  k.feed(command_frame(2));
  EXPECT_EQ(k.rejected(Reject::OutOfOrder), 2u);
}

TEST(VcuProtocol, FollowsASenderThatRestartedItsCounter) {
  Sink k;
  k.feed(command_frame(1000));
  // The VCU rebooted and counts from 0 again: the first four frames look old, the fifth in a row is accepted.
  for (std::uint16_t s = 0; s < 5; ++s) k.feed(command_frame(s));
  EXPECT_EQ(k.rejected(Reject::OutOfOrder), 4u);
  EXPECT_EQ(k.decoder.counters().restarts, 1u);
  ASSERT_EQ(k.commands.size(), 2u);
  EXPECT_EQ(k.commands.back().second, 4);
  k.feed(command_frame(5));
  EXPECT_EQ(k.commands.size(), 3u);
}

TEST(VcuProtocol, OldFramesOutOfOrderAmongThemselvesNeverRestart) {
  Sink k;
  k.feed(command_frame(1000));
  for (std::uint16_t s : {500, 400, 300, 200, 100, 50, 10}) k.feed(command_frame(s));
  EXPECT_EQ(k.rejected(Reject::OutOfOrder), 7u);
  EXPECT_EQ(k.decoder.counters().restarts, 0u);
}

TEST(VcuProtocol, GarbageBetweenFramesResynchronises) {
  Sink k;
  const Bytes garbage = {0x00, 0xa5, 0x13, 0x5a, 0xa5, 0xa5, 0xff, 0x5a};
  // A false sync with a plausible header inside the garbage must not swallow the real frame after it.
  const Bytes false_sync = {0xa5, 0x5a, 0x08, 0x01, 0x01, 0x00};
  k.feed(
      cat({garbage, kCommandFrame, garbage, false_sync, command_frame(0x1235), garbage, encode(VcuStatus{}, 0x1236)}));
  ASSERT_EQ(k.commands.size(), 2u);
  EXPECT_EQ(k.commands[1].second, 0x1235);
  EXPECT_EQ(k.statuses.size(), 1u);
  EXPECT_GE(k.decoder.counters().garbage_bytes, 3 * garbage.size() - 3);
}

TEST(VcuProtocol, ResetRestartsSequenceTracking) {
  Sink k;
  k.feed(command_frame(500));
  k.decoder.reset();
  k.feed(command_frame(3));
  EXPECT_EQ(k.commands.size(), 2u);
  EXPECT_EQ(k.decoder.counters().rejected_total(), 0u);
}

}  // namespace
}  // namespace fsd::wire::vcu

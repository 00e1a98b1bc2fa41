#pragma once
// Groups the sentences of one receiver epoch (one navigation solution) so that position, velocity, heading,
// attitude and yaw rate of the same instant become one sample.
//
// When an epoch ends: a receiver sends the sentences of an epoch back to back in a fixed order, and only GGA,
// RMC and PASHR carry the UTC time. So
//   - the epoch closes as soon as its last sentence type (the "ender") arrives: lowest latency, no timer;
//   - otherwise (no ender known yet, or the ender was lost) it closes when a sentence carries a different UTC
//     time, or when a second untimed sentence of a type it already has arrives (one epoch of extra latency);
//   - emit_on = auto learns the ender as the sentence just before the UTC time changes. This assumes that the
//     untimed sentences (VTG, HDT, ROT) follow the timed ones of their epoch, as GNSS-INS receivers commonly
//     send them (GGA first); for a receiver that sends an untimed sentence first, configure the ender. The
//     learnt ender is forgotten when a timed sentence of an already closed epoch arrives (it was not the last)
//     and relearnt after 3 epochs in a row closed without it;
//   - a timed sentence of an epoch already closed, or a second one of the same type and time (two talkers),
//     is late: counted and dropped.
// Untimed sentences join the open epoch.
#include <cstdint>
#include <functional>
#include <optional>

#include "common/time.hpp"
#include "drivers/gnss/nmea_sentences.hpp"

namespace fsd {

struct Epoch {
  std::optional<double> utc_s;  // from the first timed sentence
  Stamp receive_time = 0;       // of the epoch's first sentence
  std::optional<GgaSentence> gga;
  std::optional<RmcSentence> rmc;
  std::optional<VtgSentence> vtg;
  std::optional<HdtSentence> hdt;
  std::optional<PashrSentence> pashr;
  std::optional<RotSentence> rot;
  unsigned types = 0;  // bit per SentenceType
  SentenceType last = SentenceType::GGA;

  bool has(SentenceType t) const { return (types >> static_cast<unsigned>(t)) & 1u; }
  void add(const Sentence& s, Stamp t);
};

class EpochAssembler {
 public:
  using Sink = std::function<void(const Epoch&)>;
  // `ender`: the sentence type that ends each epoch, or nullopt to learn it.
  EpochAssembler(std::optional<SentenceType> ender, Sink sink);

  void add(const Sentence& s, Stamp receive_time);

  std::optional<SentenceType> ender() const { return ender_; }
  std::uint64_t late_sentences() const { return late_; }

 private:
  void close(bool by_ender);

  bool learn_;
  std::optional<SentenceType> ender_;
  Sink sink_;
  Epoch open_;
  std::optional<double> last_closed_utc_;
  SentenceType previous_ = SentenceType::GGA;  // type of the last sentence added
  int misses_ = 0;
  std::uint64_t late_ = 0;
};

}  // namespace fsd

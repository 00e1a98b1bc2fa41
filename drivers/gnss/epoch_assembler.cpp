#include "drivers/gnss/epoch_assembler.hpp"

#include <cmath>

namespace fsd {
namespace {

constexpr int kMissesBeforeRelearn = 3;

// Receivers write the time with 2 or 3 decimals; sentences of one epoch agree to well under a millisecond.
bool same_time(double a, double b) { return std::abs(a - b) < 5e-4; }

unsigned bit(SentenceType t) { return 1u << static_cast<unsigned>(t); }

}  // namespace

void Epoch::add(const Sentence& s, Stamp t) {
  if (types == 0) receive_time = t;
  if (!utc_s) utc_s = utc_of(s);
  std::visit(
      [this](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, GgaSentence>)
          gga = v;
        else if constexpr (std::is_same_v<T, RmcSentence>)
          rmc = v;
        else if constexpr (std::is_same_v<T, VtgSentence>)
          vtg = v;
        else if constexpr (std::is_same_v<T, HdtSentence>)
          hdt = v;
        else if constexpr (std::is_same_v<T, PashrSentence>)
          pashr = v;
        else
          rot = v;
      },
      s);
  last = type_of(s);
  types |= bit(last);
}

EpochAssembler::EpochAssembler(std::optional<SentenceType> ender, Sink sink)
    : learn_(!ender), ender_(ender), sink_(std::move(sink)) {}

void EpochAssembler::add(const Sentence& s, Stamp receive_time) {
  const SentenceType type = type_of(s);
  if (const std::optional<double> utc = utc_of(s)) {
    if (open_.utc_s) {
      if (same_time(*utc, *open_.utc_s)) {
        if (open_.has(type)) {  // the same solution again, e.g. from a second talker
          ++late_;
          return;
        }
      } else {
        close(false);
        if (learn_ && (!ender_ || misses_ >= kMissesBeforeRelearn)) {
          ender_ = previous_;
          misses_ = 0;
        }
      }
    } else if (last_closed_utc_ && same_time(*utc, *last_closed_utc_)) {
      ++late_;
      if (learn_) ender_.reset();  // the learnt ender was not the epoch's last sentence
      return;
    }
  } else if (open_.has(type)) {
    close(false);
  }
  open_.add(s, receive_time);
  previous_ = type;
  if (ender_ && type == *ender_) close(true);
}

void EpochAssembler::close(bool by_ender) {
  if (by_ender)
    misses_ = 0;
  else if (ender_)
    ++misses_;
  last_closed_utc_ = open_.utc_s;
  const Epoch done = std::move(open_);
  open_ = Epoch{};
  sink_(done);
}

}  // namespace fsd

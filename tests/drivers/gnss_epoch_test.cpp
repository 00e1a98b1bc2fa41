// Epoch assembly: which sentences end up in one sample, and when it is emitted.
#include <gtest/gtest.h>

#include <vector>

#include "drivers/gnss/epoch_assembler.hpp"

namespace fsd {
namespace {

GgaSentence gga(double utc) {
  GgaSentence g;
  g.utc_s = utc;
  g.quality = 4;
  return g;
}
RmcSentence rmc(double utc) {
  RmcSentence r;
  r.utc_s = utc;
  r.valid = true;
  return r;
}
PashrSentence pashr(double utc) {
  PashrSentence p;
  p.utc_s = utc;
  return p;
}
HdtSentence hdt(double heading) { return HdtSentence{heading}; }
RotSentence rot(double rate) { return RotSentence{rate, true}; }
VtgSentence vtg() { return VtgSentence{}; }

struct Recorder {
  std::vector<Epoch> epochs;
  EpochAssembler::Sink sink() {
    return [this](const Epoch& e) { epochs.push_back(e); };
  }
};

// One epoch in the order of the virtual car's GNSS-INS: GGA RMC VTG HDT PASHR ROT.
void send_epoch(EpochAssembler& a, int k, Stamp t) {
  const double utc = 36000.0 + 0.02 * k;
  a.add(gga(utc), t);
  a.add(rmc(utc), t);
  a.add(vtg(), t);
  a.add(hdt(k), t);
  a.add(pashr(utc), t);
  a.add(rot(10.0 * k), t);
}

TEST(EpochAssembler, LearnsTheLastSentenceAndThenEmitsWithoutDelay) {
  Recorder r;
  EpochAssembler a(std::nullopt, r.sink());
  send_epoch(a, 0, 0.0);
  EXPECT_TRUE(r.epochs.empty());  // nothing tells yet that the epoch is over
  EXPECT_FALSE(a.ender());
  send_epoch(a, 1, 0.02);
  // Epoch 0 closed when epoch 1's GGA changed the time, which taught that ROT ends an epoch; epoch 1 then
  // closed on its own ROT, and so does epoch 2.
  EXPECT_EQ(a.ender(), SentenceType::ROT);
  ASSERT_EQ(r.epochs.size(), 2u);
  send_epoch(a, 2, 0.04);
  ASSERT_EQ(r.epochs.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const Epoch& e = r.epochs[k];
    EXPECT_EQ(e.types, 0x3Fu);
    EXPECT_DOUBLE_EQ(*e.utc_s, 36000.0 + 0.02 * k);
    EXPECT_DOUBLE_EQ(*e.hdt->heading_deg, k);  // the heading of its own epoch
    EXPECT_DOUBLE_EQ(*e.rot->rate_deg_per_min, 10.0 * k);
    EXPECT_DOUBLE_EQ(e.receive_time, 0.02 * k);
  }
  EXPECT_EQ(a.late_sentences(), 0u);
}

TEST(EpochAssembler, LostEnderClosesAtTheNextEpochAndIsKept) {
  Recorder r;
  EpochAssembler a(SentenceType::ROT, r.sink());
  send_epoch(a, 0, 0.0);
  ASSERT_EQ(r.epochs.size(), 1u);
  const double utc = 36000.02;
  a.add(gga(utc), 0.02);
  a.add(hdt(1), 0.02);  // ROT of this epoch lost on the line
  EXPECT_EQ(r.epochs.size(), 1u);
  send_epoch(a, 2, 0.04);
  ASSERT_EQ(r.epochs.size(), 3u);
  EXPECT_EQ(r.epochs[1].types, (1u << 0) | (1u << 3));
  EXPECT_DOUBLE_EQ(*r.epochs[1].utc_s, utc);
  EXPECT_DOUBLE_EQ(*r.epochs[2].utc_s, 36000.04);
  EXPECT_EQ(a.ender(), SentenceType::ROT);
}

TEST(EpochAssembler, WrongEnderIsForgottenAndRelearnt) {
  Recorder r;
  EpochAssembler a(std::nullopt, r.sink());
  // The stream starts with GGA-only epochs, so GGA is learnt; then the receiver adds RMC after GGA.
  a.add(gga(1.0), 1.0);
  a.add(gga(2.0), 2.0);
  EXPECT_EQ(a.ender(), SentenceType::GGA);
  a.add(gga(3.0), 3.0);
  a.add(rmc(3.0), 3.0);  // RMC of an epoch that was already emitted on its GGA: late, ender forgotten
  EXPECT_EQ(a.late_sentences(), 1u);
  EXPECT_FALSE(a.ender());
  a.add(gga(4.0), 4.0);
  a.add(rmc(4.0), 4.0);
  a.add(gga(5.0), 5.0);
  EXPECT_EQ(a.ender(), SentenceType::RMC);
  a.add(rmc(5.0), 5.0);
  ASSERT_EQ(r.epochs.size(), 5u);
  EXPECT_TRUE(r.epochs.back().has(SentenceType::RMC));
  EXPECT_DOUBLE_EQ(*r.epochs.back().utc_s, 5.0);
}

TEST(EpochAssembler, ConfiguredEnderWithAnUntimedSentenceFirst) {
  // Hemisphere order: HDT, GGA, VTG each second. With VTG as ender every epoch keeps its own heading.
  Recorder r;
  EpochAssembler a(SentenceType::VTG, r.sink());
  for (int k = 0; k < 4; ++k) {
    a.add(hdt(100 + k), k);
    a.add(gga(k), k);
    a.add(vtg(), k);
  }
  ASSERT_EQ(r.epochs.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_DOUBLE_EQ(*r.epochs[k].utc_s, k);
    EXPECT_DOUBLE_EQ(*r.epochs[k].hdt->heading_deg, 100 + k);
  }
}

TEST(EpochAssembler, UntimedOnlyStreamClosesOnRepeatedType) {
  Recorder r;
  EpochAssembler a(std::nullopt, r.sink());
  for (int k = 0; k < 3; ++k) {
    a.add(hdt(k), k);
    a.add(vtg(), k);
  }
  ASSERT_EQ(r.epochs.size(), 2u);
  EXPECT_DOUBLE_EQ(*r.epochs[1].hdt->heading_deg, 1);
  EXPECT_FALSE(r.epochs[1].utc_s);
}

TEST(EpochAssembler, SecondTalkerOfTheSameEpochIsDropped) {
  Recorder r;
  EpochAssembler a(SentenceType::HDT, r.sink());
  GgaSentence first = gga(7.0);
  first.quality = 4;
  GgaSentence second = gga(7.0);
  second.quality = 1;
  a.add(first, 7.0);
  a.add(second, 7.0);
  a.add(hdt(1), 7.0);
  ASSERT_EQ(r.epochs.size(), 1u);
  EXPECT_EQ(r.epochs[0].gga->quality, 4);
  EXPECT_EQ(a.late_sentences(), 1u);
}

}  // namespace
}  // namespace fsd

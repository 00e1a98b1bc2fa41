#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "web/mpmc_ring.hpp"

namespace fsd::web {
namespace {

TEST(MpmcRing, FifoAndBounded) {
  MpmcRing<int> r(3);  // rounded up to 4
  EXPECT_EQ(r.capacity(), 4u);
  EXPECT_EQ(r.approx_size(), 0u);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(r.try_push(i));
  EXPECT_EQ(r.approx_size(), 4u);
  EXPECT_FALSE(r.try_push(99));  // full: refused, never waits
  EXPECT_EQ(r.approx_size(), 4u);
  int v = -1;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(r.try_pop(v));
    EXPECT_EQ(v, i);
  }
  EXPECT_FALSE(r.try_pop(v));
  EXPECT_EQ(r.approx_size(), 0u);
  EXPECT_TRUE(r.try_push(5));  // wraps around
  ASSERT_TRUE(r.try_pop(v));
  EXPECT_EQ(v, 5);
}

// Two producers and a consumer: every accepted item arrives exactly once, each producer's in its order.
TEST(MpmcRing, ConcurrentProducersLoseNothingTheyWereToldWasTaken) {
  MpmcRing<std::uint64_t> r(256);
  constexpr std::uint64_t kPerProducer = 200000;
  std::atomic<int> producers_done{0};
  std::vector<std::uint64_t> accepted(2, 0);
  auto produce = [&](std::uint64_t id) {
    for (std::uint64_t i = 0; i < kPerProducer; ++i)
      if (r.try_push((id << 32) | i)) ++accepted[id];
    ++producers_done;
  };
  std::thread a(produce, 0), b(produce, 1);
  std::vector<std::uint64_t> last(2, 0), received(2, 0);
  std::vector<bool> seen_any(2, false);
  bool ordered = true;
  std::uint64_t item;
  for (;;) {
    if (!r.try_pop(item)) {
      if (producers_done < 2) continue;
      if (!r.try_pop(item)) break;  // producers finished and the ring is empty
    }
    const auto id = item >> 32, seq = item & 0xffffffffu;
    if (seen_any[id] && seq <= last[id]) ordered = false;
    seen_any[id] = true;
    last[id] = seq;
    ++received[id];
  }
  a.join();
  b.join();
  EXPECT_TRUE(ordered);
  EXPECT_EQ(received[0], accepted[0]);
  EXPECT_EQ(received[1], accepted[1]);
  EXPECT_GT(accepted[0] + accepted[1], 0u);
}

}  // namespace
}  // namespace fsd::web

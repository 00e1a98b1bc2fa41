#include <gtest/gtest.h>

#include <thread>

#include "common/bounded_queue.hpp"
#include "common/clock.hpp"

namespace fsd {
namespace {

TEST(Clock, RealClockIsMonotonicAndSleeps) {
  RealClock c;
  const Stamp t0 = c.now();
  EXPECT_TRUE(c.sleep_for(0.02));
  const Stamp t1 = c.now();
  EXPECT_GE(t1 - t0, 0.02);
  EXPECT_LT(t1 - t0, 1.0);
}

TEST(Clock, RealClockStopWakesSleepers) {
  RealClock c;
  std::thread t([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    c.stop();
  });
  const Stamp t0 = c.now();
  EXPECT_FALSE(c.sleep_until(t0 + 30.0));  // would be 30 s without stop
  EXPECT_LT(c.now() - t0, 5.0);
  t.join();
  EXPECT_FALSE(c.sleep_for(1.0));
}

TEST(Clock, SimulatedClockRunsAtItsRate) {
  SimulatedClock c(10.0, 100.0);
  EXPECT_GE(c.now(), 100.0);
  const Stamp t0 = c.now();
  const auto w0 = std::chrono::steady_clock::now();
  EXPECT_TRUE(c.sleep_until(t0 + 0.5));  // 0.5 s simulated = 50 ms real
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  EXPECT_GE(c.now() - t0, 0.5);
  EXPECT_GE(wall, 0.045);
  EXPECT_LT(wall, 0.5);
}

TEST(Clock, LockstepMovesOnlyWhenAdvanced) {
  LockstepClock c(1.0);
  EXPECT_EQ(c.now(), 1.0);
  std::atomic<bool> woke{false};
  std::thread t([&] {
    c.sleep_until(2.0);
    woke = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_FALSE(woke.load());
  c.advance_to(1.5);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_FALSE(woke.load());
  c.advance_to(2.0);
  t.join();
  EXPECT_TRUE(woke.load());
  c.advance_to(0.5);  // never backwards
  EXPECT_EQ(c.now(), 2.0);
  c.stop();
  EXPECT_FALSE(c.sleep_until(100.0));
}

TEST(BoundedQueue, DropsOldestAndCounts) {
  BoundedQueue<int> q(2);
  EXPECT_TRUE(q.push(1));
  EXPECT_TRUE(q.push(2));
  EXPECT_FALSE(q.push(3));
  EXPECT_EQ(q.dropped(), 1u);
  EXPECT_EQ(q.try_pop(), 2);
  EXPECT_EQ(q.try_pop(), 3);
  EXPECT_EQ(q.try_pop(), std::nullopt);
  q.close();
  EXPECT_EQ(q.pop_for(std::chrono::seconds(5)), std::nullopt);  // returns at once when closed
}

TEST(LatestValue, ReportsOnlyNewValues) {
  LatestValue<int> v;
  std::uint64_t seen = 0;
  EXPECT_EQ(v.get_if_newer(seen), std::nullopt);
  v.set(4);
  EXPECT_EQ(v.get_if_newer(seen), 4);
  EXPECT_EQ(v.get_if_newer(seen), std::nullopt);
}

}  // namespace
}  // namespace fsd

// The loop closure's solve worker (LoopSolveThread, the Stack's in real time): a job runs on the worker's thread,
// not the caller's, and its result is taken once; one job at a time; a job that throws comes back unsolved; the
// destructor waits for a job under way. Paced by a run clock (a simulation faster than real time), a result comes
// once as much run time has passed as the job took, and a run clock ahead of the job waits for it.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <stdexcept>
#include <thread>

#include "daemon/stack/loop_solve_thread.hpp"
#include "tests/wait_until.hpp"

namespace fsd {
namespace {

SolvedLoop solved_at(double t) {
  SolvedLoop s;
  s.result.solved = true;
  s.result.closure.t = t;
  return s;
}

TEST(LoopSolveThread, AJobRunsOffTheCallingThreadAndItsResultIsTakenOnce) {
  LoopSolveThread worker;
  std::thread::id ran_on;
  ASSERT_TRUE(worker.submit([&ran_on] {
    ran_on = std::this_thread::get_id();
    return solved_at(12.5);
  }));
  std::optional<SolvedLoop> r;
  ASSERT_TRUE(test::wait_until([&] { return (r = worker.poll()).has_value(); }));
  EXPECT_NE(ran_on, std::thread::id{});
  EXPECT_NE(ran_on, std::this_thread::get_id());
  EXPECT_TRUE(r->result.solved);
  EXPECT_EQ(r->result.closure.t, 12.5);
  EXPECT_FALSE(worker.poll());  // taken once
}

TEST(LoopSolveThread, ASecondJobWhileOneIsOutIsRefusedUntilItsResultIsTaken) {
  LoopSolveThread worker;
  std::promise<void> release;
  std::shared_future<void> go = release.get_future().share();
  ASSERT_TRUE(worker.submit([go] {
    go.wait();
    return solved_at(1.0);
  }));
  std::atomic<int> second_ran{0};
  EXPECT_FALSE(worker.submit([&second_ran] {
    ++second_ran;
    return solved_at(2.0);
  }));  // still running
  EXPECT_FALSE(worker.poll());
  release.set_value();
  std::optional<SolvedLoop> r;
  ASSERT_TRUE(test::wait_until([&] { return (r = worker.poll()).has_value(); }));
  EXPECT_EQ(r->result.closure.t, 1.0);
  EXPECT_EQ(second_ran, 0);  // the refused job never ran
  // Its result taken, the worker takes the next.
  ASSERT_TRUE(worker.submit([] { return solved_at(3.0); }));
  ASSERT_TRUE(test::wait_until([&] { return (r = worker.poll()).has_value(); }));
  EXPECT_EQ(r->result.closure.t, 3.0);
}

TEST(LoopSolveThread, AJobThatThrowsComesBackUnsolved) {
  LoopSolveThread worker;
  ASSERT_TRUE(worker.submit([]() -> SolvedLoop { throw std::out_of_range("landmark"); }));
  std::optional<SolvedLoop> r;
  ASSERT_TRUE(test::wait_until([&] { return (r = worker.poll()).has_value(); }));
  EXPECT_FALSE(r->result.solved);
}

TEST(LoopSolveThread, DestroyedWithAJobUnderWayItWaitsForTheJob) {
  std::atomic<bool> started{false}, finished{false};
  {
    LoopSolveThread worker;
    ASSERT_TRUE(worker.submit([&] {
      started = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(150));  // a solve's time
      finished = true;
      return solved_at(1.0);
    }));
    ASSERT_TRUE(test::wait_until([&] { return started.load(); }));
    EXPECT_FALSE(finished);
  }  // joined here
  EXPECT_TRUE(finished);
}

TEST(LoopSolveThread, DestroyedIdleOrWithAnUntakenResultItJoins) {
  { LoopSolveThread idle; }
  std::atomic<bool> ran{false};
  {
    LoopSolveThread worker;
    ASSERT_TRUE(worker.submit([&ran] {
      ran = true;
      return solved_at(1.0);
    }));
    ASSERT_TRUE(test::wait_until([&] { return ran.load(); }));
  }
  EXPECT_TRUE(ran);
}

TEST(LoopSolveThread, PacedByARunClockAResultComesOnceAsMuchRunTimeHasPassedAsTheJobTook) {
  LoopSolveThread worker;
  std::atomic<double> run{100.0};
  worker.pace_by([&run] { return run.load(); });
  std::atomic<bool> done{false};
  ASSERT_TRUE(worker.submit([&done] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    done = true;
    return solved_at(1.0);
  }));
  ASSERT_TRUE(test::wait_until([&] { return done.load(); }));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  run = 100.05;  // the job is over on the wall clock, but only 50 ms of the run have passed: not yet
  EXPECT_FALSE(worker.poll());
  run = 110.0;  // its 100 ms (and more) have
  const auto r = worker.poll();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->result.closure.t, 1.0);
  EXPECT_FALSE(worker.poll());  // taken once
}

TEST(LoopSolveThread, PacedByARunClockAheadOfTheJobThePollWaitsForIt) {
  LoopSolveThread worker;
  std::atomic<double> run{0.0};
  worker.pace_by([&run] { return run.load(); });
  std::atomic<bool> done{false};
  ASSERT_TRUE(worker.submit([&done] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    done = true;
    return solved_at(2.0);
  }));
  run = 5.0;  // a fast simulation's 5 s since the job went out: the run must not drive on without its result
  const auto r = worker.poll();
  EXPECT_TRUE(done);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->result.closure.t, 2.0);
}

}  // namespace
}  // namespace fsd

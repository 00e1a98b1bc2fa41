// The Stack's processing thread (DESIGN.md §4) and what it stands on. FixedLatencyJobThread, the worker of the
// scans' processing and of lap 1's plans: unpaced (real time) poll() never waits for a job under way, so the
// control thread keeps its period; paced by a run clock (a simulation faster than real time) a result is taken
// exactly the given run time after its hand-over, waited for if need be, however long the job took on the wall
// clock. set_realtime: SCHED_FIFO or a message naming why not. And the whole daemon: a headless run with the
// workers (--workers: the scans processed on the processing thread, paced) drives clean and repeats itself.
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <future>
#include <optional>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "common/realtime.hpp"
#include "daemon/stack/job_thread.hpp"
#include "tests/daemon/sim_report.hpp"
#include "tests/wait_until.hpp"

namespace fsd {
namespace {

TEST(FixedLatencyJobThread, UnpacedAPollNeverWaitsForAJobUnderWay) {
  FixedLatencyJobThread<int> worker([](const std::exception&) { return -1; });
  std::promise<void> release;
  std::shared_future<void> go = release.get_future().share();
  std::atomic<bool> started{false};
  ASSERT_TRUE(worker.submit([go, &started] {
    started = true;
    go.wait();
    return 7;
  }));
  ASSERT_TRUE(test::wait_until([&] { return started.load(); }));
  // The job is blocked: were poll() to wait for it, this would never return.
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(worker.poll());
  EXPECT_FALSE(worker.submit([] { return 8; }));  // one job at a time
  release.set_value();
  std::optional<int> r;
  ASSERT_TRUE(test::wait_until([&] { return (r = worker.poll()).has_value(); }));
  EXPECT_EQ(*r, 7);
  EXPECT_FALSE(worker.poll());  // taken once
}

TEST(FixedLatencyJobThread, PacedAResultIsTakenTheLatencyAfterItsHandOverNotBeforeNorLater) {
  double run = 10.0;
  FixedLatencyJobThread<int> worker([](const std::exception&) { return -1; });
  worker.pace_by([&run] { return run; }, 0.02);
  std::atomic<bool> done{false};
  ASSERT_TRUE(worker.submit([&done] {
    done = true;
    return 3;
  }));
  ASSERT_TRUE(test::wait_until([&] { return done.load(); }));
  run = 10.01;
  EXPECT_FALSE(worker.poll());  // done on the wall clock, not yet due on the run's
  run = 10.02;
  const std::optional<int> r = worker.poll();
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, 3);
}

TEST(FixedLatencyJobThread, PacedADueResultIsWaitedFor) {
  double run = 0.0;
  FixedLatencyJobThread<int> worker([](const std::exception&) { return -1; });
  worker.pace_by([&run] { return run; }, 0.02);
  std::promise<void> release;
  std::shared_future<void> go = release.get_future().share();
  ASSERT_TRUE(worker.submit([go] {
    go.wait();
    return 5;
  }));
  run = 0.05;
  std::thread releaser([&release] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    release.set_value();
  });
  const std::optional<int> r = worker.poll();  // due: waits for the job, however long it takes
  releaser.join();
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, 5);
}

TEST(FixedLatencyJobThread, AJobThatThrowsComesBackAsTheFailureResult) {
  FixedLatencyJobThread<std::string> worker([](const std::exception& e) { return std::string("failed: ") + e.what(); });
  ASSERT_TRUE(worker.submit([]() -> std::string { throw std::runtime_error("no points"); }));
  std::optional<std::string> r;
  ASSERT_TRUE(test::wait_until([&] { return (r = worker.poll()).has_value(); }));
  EXPECT_EQ(*r, "failed: no points");
}

TEST(Realtime, AThreadIsPutUnderSchedFifoOrTheReasonIsNamed) {
  EXPECT_NE(set_realtime(0), std::nullopt);    // below SCHED_FIFO's range
  EXPECT_NE(set_realtime(100), std::nullopt);  // above it
  std::optional<std::string> failed;
  int policy = -1;
  sched_param p{};
  std::thread t([&] {
    failed = set_realtime(1);
    pthread_getschedparam(pthread_self(), &policy, &p);
  });
  t.join();
  if (failed) {
    // Without CAP_SYS_NICE or RLIMIT_RTPRIO: refused, said, and the thread left as it was.
    EXPECT_NE(failed->find("not permitted"), std::string::npos) << *failed;
    EXPECT_EQ(policy, SCHED_OTHER);
  } else {
    EXPECT_EQ(policy, SCHED_FIFO);
    EXPECT_EQ(p.sched_priority, 1);
  }
}

// The defaults (the perception stages, the fused pose with the LiDAR odometry), one lap of epfl_track_1 (no lap-2
// build, whose worker is paced by the wall time a build takes), twice with --workers: the scans processed on the
// processing thread, taken run.scan_latency after each hand-over, and lap 1's plans on theirs.
TEST(ProcessingThread, AHeadlessRunWithTheWorkersDrivesCleanAndRepeatsItself) {
  const std::string args = "--workers --laps 1 --track ../shared/tracks/epfl_track_1.csv";
  const nlohmann::json a = test::sim_report("processing_thread_a", nlohmann::json::object(), args);
  const nlohmann::json b = test::sim_report("processing_thread_b", nlohmann::json::object(), args);
  ASSERT_TRUE(a.is_object() && b.is_object());
  EXPECT_EQ(a["verdict"], "pass") << a["verdict_reasons"].dump();
  EXPECT_EQ(a["cones_hit"], 0);
  EXPECT_EQ(a["perception"]["source"], "lidar_camera");
  EXPECT_GT(a["perception"]["frames"].get<int>(), 300);  // every scan of the lap processed
  for (const char* key : {"laps", "map", "perception", "odometry", "sim_time_s"}) EXPECT_EQ(a[key], b[key]) << key;
}

}  // namespace
}  // namespace fsd

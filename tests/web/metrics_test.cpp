#include <gtest/gtest.h>

#include "web/metrics.hpp"

namespace fsd::web {
namespace {

TEST(Metrics, RendersCountersGaugesAndCallbacks) {
  Metrics m;
  m.counter("fsd_frames_total", "Frames", {{"sensor", "lidar"}}).inc(3);
  m.counter("fsd_frames_total", "Frames", {{"sensor", "lidar"}}).inc();  // same series
  m.gauge("fsd_queue_depth", "Depth\nwith newline").set(2.5);
  m.gauge_callback("fsd_answer", "Answer", [] { return 42.0; });
  const auto text = m.render();
  EXPECT_NE(
      text.find(
          "# HELP fsd_frames_total Frames\n# TYPE fsd_frames_total counter\nfsd_frames_total{sensor=\"lidar\"} 4\n"),
      std::string::npos);
  EXPECT_NE(text.find("# HELP fsd_queue_depth Depth\\nwith newline\n"), std::string::npos);
  EXPECT_NE(text.find("fsd_queue_depth 2.5\n"), std::string::npos);
  EXPECT_NE(text.find("fsd_answer 42\n"), std::string::npos);
}

TEST(Metrics, LabelValuesAreEscaped) {
  Metrics m;
  m.counter("c_total", "c", {{"what", "a\"b\\c"}}).inc();
  EXPECT_NE(m.render().find("c_total{what=\"a\\\"b\\\\c\"} 1\n"), std::string::npos);
}

TEST(Metrics, SummaryQuantilesByNearestRank) {
  Summary s(1000);
  for (int i = 1; i <= 200; ++i) s.observe(i);
  const auto snap = s.snapshot();
  EXPECT_EQ(snap.count, 200u);
  EXPECT_DOUBLE_EQ(snap.sum, 200.0 * 201.0 / 2.0);
  EXPECT_DOUBLE_EQ(snap.p50, 100.0);
  EXPECT_DOUBLE_EQ(snap.p90, 180.0);
  EXPECT_DOUBLE_EQ(snap.p99, 198.0);
  EXPECT_DOUBLE_EQ(snap.max, 200.0);
}

TEST(Metrics, SummaryWindowKeepsTheLatest) {
  Summary s(10);
  for (int i = 1; i <= 100; ++i) s.observe(i);
  const auto snap = s.snapshot();
  EXPECT_EQ(snap.count, 100u);
  EXPECT_DOUBLE_EQ(snap.max, 100.0);
  EXPECT_DOUBLE_EQ(snap.p50, 95.0);  // window 91..100
}

TEST(Metrics, RefusesBadNamesAndTypeClashes) {
  Metrics m;
  EXPECT_THROW(m.counter("9lives", "x"), std::logic_error);
  EXPECT_THROW(m.counter("has space", "x"), std::logic_error);
  EXPECT_THROW(m.counter("ok_total", "x", {{"bad-label", "v"}}), std::logic_error);
  m.counter("dup", "x");
  EXPECT_THROW(m.gauge("dup", "x"), std::logic_error);
}

}  // namespace
}  // namespace fsd::web

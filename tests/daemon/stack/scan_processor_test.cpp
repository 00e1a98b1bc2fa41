// ScanProcessor: a scan's perception and its scan match run side by side (perception on the caller's thread, the
// odometry on the processor's own), and what comes back is what each stage gives on its own: the same detections
// and the same odometry, scan after scan, as a detector and an odometry run one after the other on the same scans.
#include <gtest/gtest.h>

#include <memory>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "daemon/stack/scan_processor.hpp"
#include "localization/lidar_odometry/lidar_odometry.hpp"
#include "perception/lidar_cone_detector.hpp"
#include "tests/perception/sim_lidar_drive.hpp"

namespace fsd {
namespace {

TEST(ScanProcessor, BothStagesRunSideBySideAndGiveWhatEachGivesAlone) {
  test::SimLidarSetup setup;
  setup.speed = 10.0;
  test::SimLidarDrive drive(setup);
  const Pose3 mount = drive.mount();

  // The wall clock the processor is given tells which threads ran a stage.
  std::mutex m;
  std::set<std::thread::id> threads;
  const auto wall = [&] {
    std::lock_guard lock(m);
    threads.insert(std::this_thread::get_id());
    return 0.0;
  };
  auto odometry = std::make_unique<lidar_odometry::LidarOdometry>(lidar_odometry::LidarOdometryConfig{}, mount);
  odometry->start_at(drive.body_pose(0.0));
  ScanProcessor processor(std::make_unique<LidarCameraDetector>(LidarDetectorConfig{}, mount), std::move(odometry),
                          wall);

  // The reference: the cores' own classes, one stage after the other.
  LidarConeDetector detector(LidarDetectorConfig{}, mount);
  lidar_odometry::LidarOdometry reference(lidar_odometry::LidarOdometryConfig{}, mount);
  reference.start_at(drive.body_pose(0.0));

  int increments = 0, cones = 0;
  for (int i = 0; i < 12; ++i) {
    const auto scan = std::make_shared<const Scan>(drive.next());
    ScanJob job;
    job.scan = scan;
    job.odometry = true;
    job.detect = true;
    for (Stamp t = scan->stamp - 0.3; t <= scan->stamp + 0.15; t += 0.005) {
      const Pose3 p = drive.body_pose(std::max(0.0, t));
      job.poses.add(t, Pose2{p.translation().x(), p.translation().y(), std::atan2(p.linear()(1, 0), p.linear()(0, 0))});
    }
    const PoseHistory poses = job.poses;
    const ScanResult r = processor.process(std::move(job));
    ASSERT_TRUE(r.failure.empty()) << r.failure;

    const lidar_odometry::OdometryOutput o = reference.process(*scan);
    ASSERT_TRUE(r.odometry);
    EXPECT_EQ(r.odometry->has_increment, o.has_increment);
    EXPECT_TRUE(r.odometry->pose.isApprox(o.pose, 1e-12)) << "scan " << i;
    increments += o.has_increment;

    const LidarDetection d = detector.detect(*scan, [&poses](Stamp t) { return poses.at(t)->to_pose3(); });
    ASSERT_TRUE(r.detection);
    ASSERT_EQ(r.detection->detections.cones.size(), d.detections.cones.size()) << "scan " << i;
    for (std::size_t k = 0; k < d.detections.cones.size(); ++k)
      EXPECT_TRUE(r.detection->detections.cones[k].position.isApprox(d.detections.cones[k].position, 1e-12));
    cones += static_cast<int>(d.detections.cones.size());
  }
  EXPECT_GE(increments, 11);      // every scan after the first matched
  EXPECT_GT(cones, 12 * 5);       // cones seen in every scan: the comparison is not of empty lists
  EXPECT_EQ(threads.size(), 2u);  // this thread (perception) and the processor's (the scan match)
}

TEST(ScanProcessor, AScanWithOneStageRunsItOnTheCallersThread) {
  test::SimLidarDrive drive(test::SimLidarSetup{});
  std::set<std::thread::id> threads;
  ScanProcessor processor(
      nullptr, std::make_unique<lidar_odometry::LidarOdometry>(lidar_odometry::LidarOdometryConfig{}, drive.mount()),
      [&threads] {
        threads.insert(std::this_thread::get_id());
        return 0.0;
      });
  ScanJob job;
  job.scan = std::make_shared<const Scan>(drive.next());
  job.odometry = true;
  const ScanResult r = processor.process(std::move(job));
  EXPECT_TRUE(r.failure.empty());
  EXPECT_TRUE(r.odometry);
  EXPECT_FALSE(r.detection);
  EXPECT_EQ(threads, std::set<std::thread::id>{std::this_thread::get_id()});
}

}  // namespace
}  // namespace fsd

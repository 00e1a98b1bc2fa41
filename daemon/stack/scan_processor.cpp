#include "daemon/stack/scan_processor.hpp"

#include <opencv2/imgcodecs.hpp>

namespace fsd {

ScanProcessor::ScanProcessor(std::unique_ptr<LidarCameraDetector> detector,
                             std::unique_ptr<lidar_odometry::LidarOdometry> odometry, std::function<double()> wall)
    : detector_(std::move(detector)), odometry_(std::move(odometry)), wall_(std::move(wall)) {
  if (detector_ && odometry_)
    odometry_thread_ = std::make_unique<JobThread<OdometryRun>>([](const std::exception& e) {
      OdometryRun r;
      r.failure = e.what();
      return r;
    });
}

ScanProcessor::~ScanProcessor() = default;

std::optional<std::string> ScanProcessor::set_realtime(int priority) {
  return odometry_thread_ ? odometry_thread_->set_realtime(priority) : std::nullopt;
}

ScanProcessor::OdometryRun ScanProcessor::run_odometry(const Scan& scan,
                                                       const std::optional<lidar_odometry::Vec6>& measured) {
  OdometryRun r;
  const double w0 = wall_();
  r.output = odometry_->process(scan, measured);
  r.seconds = wall_() - w0;
  return r;
}

ScanResult ScanProcessor::process(ScanJob job) {
  ScanResult r;
  r.scan = job.scan;
  if (!job.scan) return r;
  const bool odometry = job.odometry && odometry_;
  const bool detect_here = job.detect && detector_ && !job.poses.empty();
  // The scan match beside perception when both run (the job holds the scan alive until it is joined below).
  const bool beside = odometry && detect_here && odometry_thread_ &&
                      odometry_thread_->submit(
                          [this, scan = job.scan, measured = job.measured] { return run_odometry(*scan, measured); });
  OdometryRun o;
  if (odometry && !beside) o = run_odometry(*job.scan, job.measured);
  std::string detect_failure;
  if (detect_here) {
    try {
      detect(job, r);
    } catch (const std::exception& e) {
      detect_failure = e.what();
    }
  }
  if (beside) o = std::move(*odometry_thread_->wait());  // bounded: the scan match takes milliseconds
  if (!detect_failure.empty() || !o.failure.empty()) {
    ScanResult failed;
    failed.failure = !detect_failure.empty() ? detect_failure : o.failure;
    return failed;
  }
  r.odometry = std::move(o.output);
  r.odometry_s = o.seconds;
  return r;
}

void ScanProcessor::detect(const ScanJob& job, ScanResult& r) {
  const double w0 = wall_();
  std::optional<CameraImage> image;
  if (job.camera_jpeg) {
    CameraImage img;
    img.capture = job.camera_capture;
    try {
      img.bgr = cv::imdecode(*job.camera_jpeg, cv::IMREAD_COLOR);
    } catch (const cv::Exception&) {
      img.bgr.release();
    }
    if (img.bgr.empty())
      r.camera_decode_failed = true;
    else
      image = std::move(img);
  }
  const PoseHistory& poses = job.poses;
  const BodyPoseAt pose_at = [&poses](Stamp t) { return poses.at(t)->to_pose3(); };
  r.detection = detector_->detect(*job.scan, pose_at, image ? &*image : nullptr);
  r.detector_counters = detector_->counters();
  r.perception_s = wall_() - w0;
}

}  // namespace fsd

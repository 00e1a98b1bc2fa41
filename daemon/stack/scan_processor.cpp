#include "daemon/stack/scan_processor.hpp"

#include <opencv2/imgcodecs.hpp>

namespace fsd {

ScanProcessor::ScanProcessor(std::unique_ptr<LidarCameraDetector> detector,
                             std::unique_ptr<lidar_odometry::LidarOdometry> odometry, std::function<double()> wall)
    : detector_(std::move(detector)), odometry_(std::move(odometry)), wall_(std::move(wall)) {}

ScanProcessor::~ScanProcessor() = default;

ScanResult ScanProcessor::process(ScanJob job) {
  ScanResult r;
  r.scan = job.scan;
  if (!job.scan) return r;
  if (job.odometry && odometry_) {
    const double w0 = wall_();
    r.odometry = odometry_->process(*job.scan, job.measured);
    r.odometry_s = wall_() - w0;
  }
  if (job.detect && detector_ && !job.poses.empty()) {
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
  return r;
}

}  // namespace fsd

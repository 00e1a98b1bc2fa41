#include "daemon/dds/perception_role.hpp"

#include <chrono>
#include <deque>
#include <thread>

#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/bounded_queue.hpp"
#include "common/clock.hpp"
#include "common/logging.hpp"
#include "daemon/dds/checked_type.hpp"
#include "daemon/dds/dds_participant.hpp"
#include "daemon/dds/outbox.hpp"
#include "daemon/dds/ros_messages.hpp"
#include "daemon/dds/topics.hpp"
#include "daemon/stack/cone_classifier_file.hpp"
#include "daemon/stack/settings.hpp"
#include "drivers/camera/camera_calibration.hpp"
#include "drivers/camera/camera_source.hpp"
#include "drivers/sim/sensors/camera_model_config.hpp"
#include "drivers/sim/virtual_car.hpp"
#include "drivers/vlp16/config.hpp"
#include "drivers/vlp16/scan_builder.hpp"
#include "drivers/vlp16/udp_receiver.hpp"
#include "eufs_msgs/msg/ConeArrayWithCovariancePubSubTypes.h"
#include "fsd_msgs/msg/ConeDetectionsPubSubTypes.h"
#include "localization/pose_history.hpp"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "perception/camera/camera_stage.hpp"
#include "perception/lidar_camera_detector.hpp"
#include "sensor_msgs/msg/CompressedImagePubSubTypes.h"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"
#include "visualization_msgs/msg/MarkerArrayPubSubTypes.h"

namespace fsd::dds {

namespace fdds = eprosima::fastdds::dds;

namespace {

constexpr double kPoseWait = 0.15;            // s a scan waits for a pose past its last firing
constexpr std::size_t kPacketsQueued = 4096;  // VLP-16 packets: over 5 s at 754/s
constexpr std::size_t kPosesQueued = 256;     // poses between two passes (100 Hz: one)
constexpr std::size_t kPosesKept = 512;       // over 2 s at 100 Hz + margin: deskew and accumulation
constexpr std::size_t kImagesKept = 4;        // the newest camera frames (20 Hz), for the one nearest each scan
constexpr std::size_t kScansWaiting = 4;
constexpr int kCameraJpegQuality = 85;

struct Packet {
  Stamp t;
  std::vector<std::uint8_t> bytes;
};

// A reader's listener: each sample checked (ros_messages.hpp) and queued, refusals counted and logged once a second.
template <class Msg, class Value>
struct CheckedListener final : fdds::DataReaderListener {
  using Convert = std::function<Checked<Value>(Msg&&)>;
  CheckedListener(std::size_t capacity, std::string what, Convert convert)
      : queue(capacity), what(std::move(what)), convert(std::move(convert)) {}
  BoundedQueue<Value> queue;
  std::string what;
  Convert convert;
  std::atomic<std::uint64_t> received{0}, refused{0};
  std::atomic<std::int64_t> last_log_ns{0};  // Fast DDS may call from more than one thread

  void on_data_available(fdds::DataReader* reader) override {
    Msg m;
    fdds::SampleInfo info;
    while (reader->take_next_sample(&m, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      received.fetch_add(1, std::memory_order_relaxed);
      auto checked = convert(std::move(m));
      if (auto* why = std::get_if<std::string>(&checked)) {
        refused.fetch_add(1, std::memory_order_relaxed);
        const std::int64_t now = std::chrono::steady_clock::now().time_since_epoch().count();
        std::int64_t last = last_log_ns.load();
        if (now - last > std::chrono::nanoseconds(std::chrono::seconds(1)).count() &&
            last_log_ns.compare_exchange_strong(last, now)) {
          logger("dds")->warn("refused {}: {} ({} refused so far)", what, *why, refused.load());
        }
        continue;
      }
      queue.push(std::move(std::get<Value>(checked)));
    }
  }
};

}  // namespace

struct PerceptionRole::Impl {
  RealClock clock;
  double epoch = 0;
  std::shared_ptr<spdlog::logger> log = logger("perception");
  Vlp16Config vlp_cfg;
  CameraDriverConfig cam_cfg;
  std::unique_ptr<LidarCameraDetector> detector;
  std::string stages;
  std::optional<double> camera_latency;  // the camera driver's frames: stamped at capture already (0)

  BoundedQueue<Packet> packets{kPacketsQueued};
  std::unique_ptr<UdpReceiver> lidar_rx;
  std::unique_ptr<CameraSource> camera;
  std::thread camera_thread;
  struct Jpeg {
    Stamp capture;
    std::vector<std::uint8_t> bytes;
  };
  BoundedQueue<Jpeg> camera_frames{kImagesKept};  // the camera driver's, JPEG-encoded on its thread

  using PoseListener = CheckedListener<nav_msgs::msg::dds_::Odometry_, RemotePose>;
  using ImageListener = CheckedListener<sensor_msgs::msg::dds_::CompressedImage_, RemoteImage>;
  std::unique_ptr<PoseListener> poses_in;
  std::unique_ptr<ImageListener> images_in;
  // Declared after the listeners: the participant (and its readers) go first.
  std::unique_ptr<Participant> participant;
  fdds::DataWriter *detections = nullptr, *cones = nullptr, *markers = nullptr, *cloud = nullptr;
  std::unique_ptr<Outbox> outbox;

  // The perception thread's.
  std::unique_ptr<Vlp16ScanBuilder> scans;
  std::deque<std::shared_ptr<const Scan>> waiting;  // complete scans waiting for their pose
  PoseHistory poses{kPosesKept};
  std::deque<Jpeg> images;
  std::uint64_t frames_out = 0, scans_without_pose = 0, scans_dropped = 0, published = 0;
  std::function<void()> loop_hook;

  Impl(const Config& cfg, const RunOptions&)
      : vlp_cfg(read_vlp16_config(cfg)), cam_cfg(camera_driver_section().read(cfg)) {
    const RunSettings run = run_section().read(cfg);
    std::unique_ptr<CameraStage> stage;
    if (run.perception_source != "lidar") {
      const CameraCalibration calibration = cam_cfg.calibration.empty()
                                                ? sim::calibration_of(sim::read_virtual_car_settings(cfg).camera)
                                                : load_camera_calibration(cam_cfg.calibration);
      const CameraStageConfig cc = read_camera_stage_config(cfg);
      stage = std::make_unique<CameraStage>(calibration, load_cone_classifier_model(cc.classifier.model), cc);
      log->info("camera stage on {} frames, calibration {}", cam_cfg.enabled ? "the camera driver's" : "DDS",
                cam_cfg.calibration.empty() ? "of the virtual camera (sim.camera.*)" : cam_cfg.calibration);
    }
    stages = stage ? "lidar_camera" : "lidar";
    detector = std::make_unique<LidarCameraDetector>(read_lidar_detector_config(cfg), vlp_cfg.body_from_sensor(),
                                                     std::move(stage));
    scans = std::make_unique<Vlp16ScanBuilder>(vlp_cfg, [this](Scan&& s) {
      if (waiting.size() == kScansWaiting) {
        waiting.pop_front();
        ++scans_dropped;
      }
      waiting.push_back(std::make_shared<const Scan>(std::move(s)));
    });
    try {
      lidar_rx = std::make_unique<UdpReceiver>(
          UdpReceiver::Options{vlp_cfg.address, static_cast<std::uint16_t>(vlp_cfg.data_port),
                               vlp_cfg.receive_buffer_bytes, "vlp16 data"},
          clock, [this](Stamp t, std::span<const std::uint8_t> b) {
            packets.push({t, {b.begin(), b.end()}});
          });
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(std::string("drivers.vlp16: ") + e.what());
    }
    if (cam_cfg.enabled && detector->has_camera()) camera = std::make_unique<CameraSource>(cam_cfg, clock);

    DdsSettings ds = dds_section().read(cfg);
    poses_in = std::make_unique<PoseListener>(
        kPosesQueued, "a pose", [this](nav_msgs::msg::dds_::Odometry_&& m) { return from_odometry(m, epoch); });
    images_in = std::make_unique<ImageListener>(
        kImagesKept, "a camera frame",
        [this](sensor_msgs::msg::dds_::CompressedImage_&& m) { return from_compressed_image(std::move(m), epoch); });
    epoch = run_epoch(clock.now());
    participant = std::make_unique<Participant>(ds, "fsd-perception");
    auto& p = *participant;
    p.reader(kOdomTopic, fdds::TypeSupport(new CheckedType<nav_msgs::msg::dds_::Odometry_PubSubType>), TopicKind::State,
             poses_in.get());
    if (detector->has_camera() && !camera)
      p.reader(kCameraTopic, fdds::TypeSupport(new CheckedType<sensor_msgs::msg::dds_::CompressedImage_PubSubType>),
               TopicKind::Stream, images_in.get());
    detections = p.writer(kDetectionsTopic, fdds::TypeSupport(new fsd_msgs::msg::dds_::ConeDetections_PubSubType),
                          TopicKind::State);
    cones = p.writer(kPerceptionConesTopic,
                     fdds::TypeSupport(new eufs_msgs::msg::dds_::ConeArrayWithCovariance_PubSubType), TopicKind::State);
    markers = p.writer(kPerceptionMarkersTopic,
                       fdds::TypeSupport(new visualization_msgs::msg::dds_::MarkerArray_PubSubType), TopicKind::State);
    cloud =
        p.writer(kCloudTopic, fdds::TypeSupport(new sensor_msgs::msg::dds_::PointCloud2_PubSubType), TopicKind::Stream);
    outbox = std::make_unique<Outbox>(64);
  }

  ~Impl() {
    if (outbox) outbox->stop();
    participant.reset();  // its readers call the listeners: gone before them
  }

  // The camera frame taken nearest `t`, decoded; empty without one that decodes.
  std::optional<CameraImage> image_near(Stamp t) {
    if (images.empty()) return std::nullopt;
    const Jpeg* best = &images.front();
    for (const auto& j : images)
      if (std::abs(j.capture - t) < std::abs(best->capture - t)) best = &j;
    CameraImage img;
    img.capture = best->capture;
    try {
      img.bgr = cv::imdecode(best->bytes, cv::IMREAD_COLOR);
    } catch (const cv::Exception&) {
      img.bgr.release();
    }
    if (img.bgr.empty()) return std::nullopt;
    return img;
  }

  void keep_image(Jpeg j) {
    if (images.size() == kImagesKept) images.pop_front();
    images.push_back(std::move(j));
  }

  // The oldest waiting scan, once a pose past its last firing came (or it waited kPoseWait).
  void detect_ready(Stamp now) {
    while (!waiting.empty()) {
      const auto scan = waiting.front();
      const Stamp end = firing_span(*scan).last;
      const bool posed = !poses.empty() && *poses.newest() >= end;
      if (!posed && now - end < kPoseWait) return;
      waiting.pop_front();
      if (poses.empty()) {
        ++scans_without_pose;
        continue;
      }
      const BodyPoseAt pose_at = [this](Stamp t) { return poses.at(t)->to_pose3(); };
      std::optional<CameraImage> image = image_near(end);
      LidarDetection d = detector->detect(*scan, pose_at, image ? &*image : nullptr);
      ++frames_out;
      outbox->post([this, d = std::make_shared<LidarDetection>(std::move(d)), scan] {
        auto m = to_detections(d->detections, d->camera_rejected, epoch);
        published += detections->write(&m);
        auto c = to_cone_array(d->detections.cones, d->detections.stamp, kBodyFrame, epoch);
        published += cones->write(&c);
        auto k = to_markers(d->detections.cones, d->detections.stamp, kBodyFrame, "detections", epoch);
        published += markers->write(&k);
        auto pc = to_point_cloud(*scan, epoch);
        published += cloud->write(&pc);
      });
    }
  }

  // The camera driver's frames as an MJPEG camera sends them, encoded on this thread (as on the car's).
  void camera_loop() {
    while (!stopping.load())
      if (auto f = camera->next_frame(std::chrono::milliseconds(100))) {
        if (f->bgr.empty()) continue;
        std::vector<std::uint8_t> jpeg;
        if (cv::imencode(".jpg", f->bgr, jpeg, {cv::IMWRITE_JPEG_QUALITY, kCameraJpegQuality}))
          camera_frames.push({f->stamp, std::move(jpeg)});
      }
  }
  std::atomic<bool> stopping{false};

  int run(const std::atomic<bool>& stop) {
    lidar_rx->start();
    if (camera) {
      camera->start();
      camera_thread = std::thread([this] { camera_loop(); });
    }
    log->info("perception role: {} stages, VLP-16 on udp {}:{}, poses from /fsd/odom, frames to {}", stages,
              vlp_cfg.address, lidar_rx->port(), kDetectionsTopic);
    Stamp next = clock.now();
    Stamp next_stats = next + 5.0;
    while (!stop.load()) {
      next += 0.01;
      clock.sleep_until(next);
      const Stamp now = clock.now();
      if (now - next > 0.01) next = now;
      while (auto p = poses_in->queue.try_pop()) poses.add(p->t, p->pose);
      while (auto i = images_in->queue.try_pop()) keep_image({i->capture, std::move(i->jpeg)});
      while (auto j = camera_frames.try_pop()) keep_image(std::move(*j));
      while (auto p = packets.try_pop()) scans->on_data_packet(p->t, p->bytes);
      detect_ready(now);
      if (loop_hook) loop_hook();
      if (now >= next_stats) {
        next_stats += 5.0;
        log->info(
            "{} frames out, {} scans without a pose, {} dropped; poses {} in ({} refused), images {} in ({} "
            "refused), packets dropped {}",
            frames_out, scans_without_pose, scans_dropped, poses_in->received.load(), poses_in->refused.load(),
            images_in->received.load(), images_in->refused.load(), packets.dropped());
      }
    }
    stopping = true;
    lidar_rx->stop();
    if (camera) {
      camera->stop();
      camera_thread.join();
    }
    outbox->stop();
    log->info("perception role stopped: {} frames out, {} messages published", frames_out, published);
    return 0;
  }
};

PerceptionRole::PerceptionRole(const Config& config, const RunOptions& options)
    : impl_(std::make_unique<Impl>(config, options)) {}
PerceptionRole::~PerceptionRole() = default;
int PerceptionRole::run(const std::atomic<bool>& stop) { return impl_->run(stop); }
void PerceptionRole::on_loop(std::function<void()> loop) { impl_->loop_hook = std::move(loop); }

}  // namespace fsd::dds

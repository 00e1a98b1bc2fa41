#include "daemon/dds/dds_bridge.hpp"

#include <atomic>

#include "ackermann_msgs/msg/AckermannDriveStampedPubSubTypes.h"
#include "common/logging.hpp"
#include "daemon/dds/dds_participant.hpp"
#include "daemon/dds/outbox.hpp"
#include "daemon/dds/ros_messages.hpp"
#include "daemon/dds/topics.hpp"
#include "daemon/stack/stack.hpp"
#include "daemon/telemetry/telemetry.hpp"
#include "eufs_msgs/msg/ConeArrayWithCovariancePubSubTypes.h"
#include "fsd_msgs/msg/ConeDetectionsPubSubTypes.h"
#include "fsd_msgs/msg/StatusPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/CompressedImagePubSubTypes.h"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"
#include "visualization_msgs/msg/MarkerArrayPubSubTypes.h"

namespace fsd::dds {

namespace fdds = eprosima::fastdds::dds;

namespace {

constexpr std::size_t kOutboxJobs = 256;  // over 1 s of every topic at its rate
constexpr double kMapPeriod = 0.5;        // s between two cone-map messages

void stamp(std_msgs::msg::dds_::Header_& h, Stamp t, const char* frame, double epoch) {
  const RosTime r = to_ros_time(epoch + t);
  h.stamp().sec(r.sec);
  h.stamp().nanosec(r.nanosec);
  h.frame_id(frame);
}

}  // namespace

struct DdsBridge::Impl {
  std::set<std::string> topics;
  std::unique_ptr<Participant> participant;
  fdds::DataWriter *cloud = nullptr, *detections = nullptr, *perception_cones = nullptr, *perception_markers = nullptr,
                   *map_cones = nullptr, *map_markers = nullptr, *odom = nullptr, *command = nullptr, *status = nullptr,
                   *laps = nullptr, *faults = nullptr, *camera = nullptr;
  Stack* stack = nullptr;
  double epoch = 0;
  std::atomic<std::uint64_t> published{0};
  // The control thread's bookkeeping of what went out already.
  Stamp last_state = -1e300;
  Stamp last_scan = -1e300, last_detections = -1e300;  // stamps of the newest sent
  Stamp last_map = -1e300;
  std::size_t laps_sent = 0;
  Stamp last_fault_t = -1e300;
  std::size_t faults_at_last_t = 0;
  std::string mission;
  std::unique_ptr<Outbox> outbox;  // last: its thread stops first

  bool on(const char* name) const { return topics.count(name) > 0; }

  template <class Msg>
  void write(fdds::DataWriter* w, Msg& m) {
    if (w->write(&m)) published.fetch_add(1, std::memory_order_relaxed);
  }

  void post_faults(const TelemetrySnapshot& s) {
    // The snapshot holds the recent faults, newest last; those after the last one sent go out.
    std::vector<web::FaultEvent> fresh;
    std::size_t at_t = 0;
    for (const auto& f : s.faults) {
      if (f.t < last_fault_t) continue;
      if (f.t == last_fault_t && at_t++ < faults_at_last_t) continue;
      fresh.push_back(f);
    }
    if (fresh.empty()) return;
    const Stamp newest = fresh.back().t;
    std::size_t same = 0;
    for (const auto& f : s.faults) same += f.t == newest;
    last_fault_t = newest;
    faults_at_last_t = same;
    outbox->post([this, fresh = std::move(fresh)] {
      for (const auto& f : fresh) {
        fsd_msgs::msg::dds_::Fault_ m;
        stamp(m.header(), f.t, kBodyFrame, epoch);
        m.source(f.source);
        m.what(f.what);
        m.action(f.action);
        write(faults, m);
      }
    });
  }

  void on_snapshot(const std::shared_ptr<const TelemetrySnapshot>& s) {
    if (status) {
      outbox->post([this, s] {
        fsd_msgs::msg::dds_::AsStatus_ m;
        stamp(m.header(), s->t, kBodyFrame, epoch);
        m.as_state(static_cast<std::uint8_t>(s->as.as_state));
        m.as_state_name(std::string(to_string(s->as.as_state)));
        m.mission(std::string(to_string(s->as.mission)));
        m.laps_completed(static_cast<std::uint32_t>(s->as.laps_completed));
        m.laps_total(static_cast<std::uint32_t>(s->as.laps_total));
        write(status, m);
      });
    }
    if (cloud && s->scan && s->scan->stamp > last_scan) {
      last_scan = s->scan->stamp;
      outbox->post([this, scan = s->scan] {
        auto m = to_point_cloud(*scan, epoch);
        write(cloud, m);
      });
    }
    if (s->detections && s->detections->stamp > last_detections) {
      last_detections = s->detections->stamp;
      outbox->post([this, d = s->detections] {
        if (detections) {
          auto m = to_detections(*d, {}, epoch);
          write(detections, m);
        }
        if (perception_cones) {
          auto m = to_cone_array(d->cones, d->stamp, kBodyFrame, epoch);
          write(perception_cones, m);
        }
        if (perception_markers) {
          auto m = to_markers(d->cones, d->stamp, kBodyFrame, "detections", epoch);
          write(perception_markers, m);
        }
      });
    }
    if ((map_cones || map_markers) && s->cone_map && s->t - last_map >= kMapPeriod) {
      last_map = s->t;
      outbox->post([this, map = s->cone_map, t = s->t] {
        if (map_cones) {
          auto m = to_cone_array(*map, t, kMapFrame, epoch);
          write(map_cones, m);
        }
        if (map_markers) {
          auto m = to_markers(*map, t, kMapFrame, "map", epoch);
          write(map_markers, m);
        }
      });
    }
    if (laps && s->as.lap_times.size() > laps_sent) {
      for (std::size_t k = laps_sent; k < s->as.lap_times.size(); ++k)
        outbox->post([this, t = s->t, lap = k + 1, time = s->as.lap_times[k]] {
          fsd_msgs::msg::dds_::LapEvent_ m;
          stamp(m.header(), t, kBodyFrame, epoch);
          m.lap(static_cast<std::uint32_t>(lap));
          m.time_s(time);
          write(laps, m);
        });
      laps_sent = s->as.lap_times.size();
    }
    if (faults) post_faults(*s);
  }

  void on_output(const ControlCommand& c) {
    if (command)
      outbox->post([this, c] {
        auto m = to_drive(c, epoch);
        write(command, m);
      });
    if (!odom || !stack) return;
    const auto& st = stack->state();
    if (!st || st->stamp <= last_state) return;
    last_state = st->stamp;
    outbox->post([this, s = *st] {
      auto m = to_odometry(s, epoch);
      write(odom, m);
    });
  }
};

DdsBridge::DdsBridge(const DdsSettings& settings, const std::set<std::string>& without)
    : impl_(std::make_unique<Impl>()) {
  auto& m = *impl_;
  m.topics = parse_topics(settings.topics);
  for (const auto& t : without) m.topics.erase(t);
  m.participant = std::make_unique<Participant>(settings, "fsd");
  auto& p = *m.participant;
  using TK = TopicKind;
  if (m.on("cloud"))
    m.cloud = p.writer(kCloudTopic, fdds::TypeSupport(new sensor_msgs::msg::dds_::PointCloud2_PubSubType), TK::Stream);
  if (m.on("detections")) {
    m.detections =
        p.writer(kDetectionsTopic, fdds::TypeSupport(new fsd_msgs::msg::dds_::ConeDetections_PubSubType), TK::State);
    m.perception_cones =
        p.writer(kPerceptionConesTopic, fdds::TypeSupport(new eufs_msgs::msg::dds_::ConeArrayWithCovariance_PubSubType),
                 TK::State);
    m.perception_markers =
        p.writer(kPerceptionMarkersTopic, fdds::TypeSupport(new visualization_msgs::msg::dds_::MarkerArray_PubSubType),
                 TK::State);
  }
  if (m.on("map")) {
    m.map_cones = p.writer(kMapConesTopic,
                           fdds::TypeSupport(new eufs_msgs::msg::dds_::ConeArrayWithCovariance_PubSubType), TK::State);
    m.map_markers = p.writer(kMapMarkersTopic,
                             fdds::TypeSupport(new visualization_msgs::msg::dds_::MarkerArray_PubSubType), TK::State);
  }
  if (m.on("odom"))
    m.odom = p.writer(kOdomTopic, fdds::TypeSupport(new nav_msgs::msg::dds_::Odometry_PubSubType), TK::State);
  if (m.on("command"))
    m.command = p.writer(kCommandTopic,
                         fdds::TypeSupport(new ackermann_msgs::msg::dds_::AckermannDriveStamped_PubSubType), TK::State);
  if (m.on("status"))
    m.status = p.writer(kStatusTopic, fdds::TypeSupport(new fsd_msgs::msg::dds_::AsStatus_PubSubType), TK::State);
  if (m.on("laps"))
    m.laps = p.writer(kLapsTopic, fdds::TypeSupport(new fsd_msgs::msg::dds_::LapEvent_PubSubType), TK::Events);
  if (m.on("faults"))
    m.faults = p.writer(kFaultsTopic, fdds::TypeSupport(new fsd_msgs::msg::dds_::Fault_PubSubType), TK::Events);
  m.outbox = std::make_unique<Outbox>(kOutboxJobs);
  std::string list;
  for (const auto& t : m.topics) list += (list.empty() ? "" : ", ") + t;
  logger("dds")->info("publishing on domain {}: {}{}", settings.domain, list.empty() ? "nothing" : list,
                      settings.initial_peers.empty() ? "" : " (initial peers " + settings.initial_peers + ")");
}

DdsBridge::~DdsBridge() { stop(); }

void DdsBridge::attach(Stack& stack, double epoch) {
  impl_->stack = &stack;
  impl_->epoch = epoch;
  stack.add_tap(this);
}

void DdsBridge::open_camera_topic() {
  auto& m = *impl_;
  if (!m.camera)
    m.camera = m.participant->writer(
        kCameraTopic, fdds::TypeSupport(new sensor_msgs::msg::dds_::CompressedImage_PubSubType), TopicKind::Stream);
}

void DdsBridge::publish_camera(std::shared_ptr<const std::vector<std::uint8_t>> jpeg, Stamp capture) {
  auto& m = *impl_;
  if (!m.camera) return;
  m.outbox->post([&m, jpeg = std::move(jpeg), capture] {
    auto msg = to_compressed_image(*jpeg, capture, m.epoch);
    m.write(m.camera, msg);
  });
}

Participant& DdsBridge::participant() { return *impl_->participant; }

BridgeCounters DdsBridge::counters() const { return {impl_->published.load(), impl_->outbox->dropped()}; }

void DdsBridge::stop() { impl_->outbox->stop(); }

void DdsBridge::on_output(Stamp, const ControlCommand& command, wire::vcu::AsRequest) { impl_->on_output(command); }

void DdsBridge::on_snapshot(const std::shared_ptr<const TelemetrySnapshot>& snapshot) { impl_->on_snapshot(snapshot); }

}  // namespace fsd::dds

#include "daemon/dds/ros_messages.hpp"

#include <cmath>
#include <cstring>

namespace fsd::dds {

namespace msg_std = std_msgs::msg::dds_;
namespace msg_geo = geometry_msgs::msg::dds_;

namespace {

constexpr std::uint8_t kFloat32 = 7, kUint16 = 4;  // sensor_msgs/PointField datatypes

void stamp_header(msg_std::Header_& h, Stamp t, const char* frame, double epoch) {
  const RosTime r = to_ros_time(epoch + t);
  h.stamp().sec(r.sec);
  h.stamp().nanosec(r.nanosec);
  h.frame_id(frame);
}

sensor_msgs::msg::dds_::PointField_ field(const char* name, std::uint32_t offset, std::uint8_t type) {
  sensor_msgs::msg::dds_::PointField_ f;
  f.name(name);
  f.offset(offset);
  f.datatype(type);
  f.count(1);
  return f;
}

template <class T>
void put(std::uint8_t* at, T v) {
  std::memcpy(at, &v, sizeof v);
}

msg_geo::Quaternion_ yaw_quaternion(double yaw) {
  msg_geo::Quaternion_ q;
  q.z(std::sin(yaw / 2));
  q.w(std::cos(yaw / 2));
  return q;
}

// The cone's colour on the dashboard's palette, as RViz draws it.
std_msgs::msg::dds_::ColorRGBA_ rgba(ConeColour c) {
  std_msgs::msg::dds_::ColorRGBA_ out;
  float r = 0.6f, g = 0.6f, b = 0.6f;
  switch (c) {
    case ConeColour::Blue:
      r = 0.1f, g = 0.3f, b = 1.0f;
      break;
    case ConeColour::Yellow:
      r = 1.0f, g = 0.85f, b = 0.0f;
      break;
    case ConeColour::Orange:
    case ConeColour::BigOrange:
      r = 1.0f, g = 0.45f, b = 0.0f;
      break;
    case ConeColour::Red:
      r = 0.9f, g = 0.1f, b = 0.1f;
      break;
    case ConeColour::Unknown:
      break;
  }
  out.r(r);
  out.g(g);
  out.b(b);
  out.a(1.0f);
  return out;
}

fsd_msgs::msg::dds_::DetectedCone_ detected(const Cone& c) {
  fsd_msgs::msg::dds_::DetectedCone_ m;
  m.position().x(c.position.x());
  m.position().y(c.position.y());
  m.position().z(c.position.z());
  m.covariance() = {c.covariance(0, 0), c.covariance(0, 1), c.covariance(1, 0), c.covariance(1, 1)};
  m.colour(static_cast<std::uint8_t>(c.colour));
  m.confidence(c.confidence);
  m.colour_confidence(c.colour_confidence);
  m.colour_source(static_cast<std::uint8_t>(c.colour_source));
  m.stage(static_cast<std::uint8_t>(c.stage));
  m.points(c.points);
  return m;
}

bool finite_within(double v, double bound) { return std::isfinite(v) && std::abs(v) <= bound; }

std::optional<std::string> bad_stamp(const msg_std::Header_& h) {
  if (h.stamp().nanosec() >= 1000000000u) return "header.stamp.nanosec " + std::to_string(h.stamp().nanosec());
  if (h.stamp().sec() < 0) return "header.stamp.sec negative";
  return std::nullopt;
}

Checked<Cone> from_detected(const fsd_msgs::msg::dds_::DetectedCone_& m) {
  const auto& p = m.position();
  if (!finite_within(p.x(), kMaxCoordinate) || !finite_within(p.y(), kMaxCoordinate) ||
      !finite_within(p.z(), kMaxCoordinate))
    return std::string("a cone's position is not finite or out of range");
  for (double v : m.covariance())
    if (!finite_within(v, 1e6)) return std::string("a cone's covariance is not finite or out of range");
  if (m.colour() > static_cast<std::uint8_t>(ConeColour::Red))
    return "a cone's colour " + std::to_string(m.colour()) + " is unknown";
  if (m.colour_source() > static_cast<std::uint8_t>(ColourSource::LidarIntensity))
    return "a cone's colour_source " + std::to_string(m.colour_source()) + " is unknown";
  if (m.stage() > static_cast<std::uint8_t>(DetectionStage::Camera))
    return "a cone's stage " + std::to_string(m.stage()) + " is unknown";
  if (!(m.confidence() >= 0 && m.confidence() <= 1) || !(m.colour_confidence() >= 0 && m.colour_confidence() <= 1))
    return std::string("a cone's confidence is outside 0..1");
  Cone c;
  c.position = Vec3(p.x(), p.y(), p.z());
  c.covariance << m.covariance()[0], m.covariance()[1], m.covariance()[2], m.covariance()[3];
  c.colour = static_cast<ConeColour>(m.colour());
  c.confidence = m.confidence();
  c.colour_confidence = m.colour_confidence();
  c.colour_source = static_cast<ColourSource>(m.colour_source());
  c.stage = static_cast<DetectionStage>(m.stage());
  c.points = m.points();
  return c;
}

}  // namespace

sensor_msgs::msg::dds_::PointCloud2_ to_point_cloud(const Scan& scan, double epoch) {
  // x, y, z, intensity (float32), t (float32, s after the header's stamp: the first firing), ring (uint16).
  constexpr std::uint32_t kStep = 24;
  sensor_msgs::msg::dds_::PointCloud2_ m;
  stamp_header(m.header(), scan.stamp, kLidarFrame, epoch);
  m.height(1);
  m.width(static_cast<std::uint32_t>(scan.points.size()));
  m.fields({field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32), field("intensity", 12, kFloat32),
            field("t", 16, kFloat32), field("ring", 20, kUint16)});
  m.is_bigendian(false);
  m.point_step(kStep);
  m.row_step(kStep * m.width());
  m.is_dense(true);
  auto& data = m.data();
  data.assign(static_cast<std::size_t>(kStep) * scan.points.size(), 0);
  std::uint8_t* at = data.data();
  for (const Point& p : scan.points) {
    put(at + 0, p.x);
    put(at + 4, p.y);
    put(at + 8, p.z);
    put(at + 12, p.intensity);
    put(at + 16, static_cast<float>(p.t - scan.stamp));
    put(at + 20, p.ring);
    at += kStep;
  }
  return m;
}

fsd_msgs::msg::dds_::ConeDetections_ to_detections(const ConeDetections& d, const std::vector<Cone>& camera_rejected,
                                                   double epoch) {
  fsd_msgs::msg::dds_::ConeDetections_ m;
  stamp_header(m.header(), d.stamp, kBodyFrame, epoch);
  for (const Cone& c : d.cones) m.cones().push_back(detected(c));
  for (const Cone& c : camera_rejected) m.camera_rejected().push_back(detected(c));
  return m;
}

eufs_msgs::msg::dds_::ConeArrayWithCovariance_ to_cone_array(const std::vector<Cone>& cones, Stamp t, const char* frame,
                                                             double epoch) {
  eufs_msgs::msg::dds_::ConeArrayWithCovariance_ m;
  stamp_header(m.header(), t, frame, epoch);
  for (const Cone& c : cones) {
    eufs_msgs::msg::dds_::ConeWithCovariance_ e;
    e.point().x(c.position.x());
    e.point().y(c.position.y());
    e.point().z(c.position.z());
    e.covariance() = {c.covariance(0, 0), c.covariance(0, 1), c.covariance(1, 0), c.covariance(1, 1)};
    switch (c.colour) {
      case ConeColour::Blue:
        m.blue_cones().push_back(e);
        break;
      case ConeColour::Yellow:
        m.yellow_cones().push_back(e);
        break;
      case ConeColour::Orange:
        m.orange_cones().push_back(e);
        break;
      case ConeColour::BigOrange:
        m.big_orange_cones().push_back(e);
        break;
      case ConeColour::Red:  // no red list in eufs_msgs (FSAC's red boundary): unknown to its readers
      case ConeColour::Unknown:
        m.unknown_color_cones().push_back(e);
        break;
    }
  }
  return m;
}

visualization_msgs::msg::dds_::MarkerArray_ to_markers(const std::vector<Cone>& cones, Stamp t, const char* frame,
                                                       const std::string& ns, double epoch) {
  visualization_msgs::msg::dds_::MarkerArray_ m;
  visualization_msgs::msg::dds_::Marker_ clear;  // DELETEALL: the previous frame's cones go
  stamp_header(clear.header(), t, frame, epoch);
  clear.ns(ns);
  clear.action(3);
  m.markers().push_back(clear);
  std::int32_t id = 0;
  for (const Cone& c : cones) {
    const bool big = c.colour == ConeColour::BigOrange;
    const double w = big ? 0.285 : 0.228, h = big ? 0.505 : 0.325;  // the rules' cones
    visualization_msgs::msg::dds_::Marker_ k;
    stamp_header(k.header(), t, frame, epoch);
    k.ns(ns);
    k.id(id++);
    k.type(3);  // CYLINDER
    k.action(0);
    k.pose().position().x(c.position.x());
    k.pose().position().y(c.position.y());
    k.pose().position().z(h / 2);
    k.pose().orientation().w(1.0);
    k.scale().x(w);
    k.scale().y(w);
    k.scale().z(h);
    k.color(rgba(c.colour));
    m.markers().push_back(std::move(k));
  }
  return m;
}

nav_msgs::msg::dds_::Odometry_ to_odometry(const VehicleState& s, double epoch) {
  nav_msgs::msg::dds_::Odometry_ m;
  stamp_header(m.header(), s.stamp, kMapFrame, epoch);
  m.child_frame_id(kBodyFrame);
  m.pose().pose().position().x(s.pose.x);
  m.pose().pose().position().y(s.pose.y);
  m.pose().pose().orientation(yaw_quaternion(s.pose.yaw));
  m.twist().twist().linear().x(s.vx);
  m.twist().twist().linear().y(s.vy);
  m.twist().twist().angular().z(s.yaw_rate);
  return m;
}

ackermann_msgs::msg::dds_::AckermannDriveStamped_ to_drive(const ControlCommand& c, double epoch) {
  ackermann_msgs::msg::dds_::AckermannDriveStamped_ m;
  stamp_header(m.header(), c.stamp, kBodyFrame, epoch);
  m.drive().steering_angle(static_cast<float>(c.steering));
  m.drive().speed(static_cast<float>(c.target_speed));
  return m;
}

sensor_msgs::msg::dds_::CompressedImage_ to_compressed_image(const std::vector<std::uint8_t>& jpeg, Stamp capture,
                                                             double epoch) {
  sensor_msgs::msg::dds_::CompressedImage_ m;
  stamp_header(m.header(), capture, "camera", epoch);
  m.format("jpeg");
  m.data(jpeg);
  return m;
}

Checked<RemoteDetections> from_detections(const fsd_msgs::msg::dds_::ConeDetections_& m, double epoch) {
  if (auto bad = bad_stamp(m.header())) return *bad;
  if (m.header().frame_id() != kBodyFrame)
    return "header.frame_id '" + m.header().frame_id().substr(0, 64) + "', not " + kBodyFrame;
  if (m.cones().size() > kMaxRemoteCones || m.camera_rejected().size() > kMaxRemoteCones)
    return "more than " + std::to_string(kMaxRemoteCones) + " cones";
  RemoteDetections out;
  out.detections.stamp = from_ros_time({m.header().stamp().sec(), m.header().stamp().nanosec()}) - epoch;
  for (const auto& c : m.cones()) {
    auto cone = from_detected(c);
    if (auto* why = std::get_if<std::string>(&cone)) return *why;
    out.detections.cones.push_back(std::get<Cone>(cone));
  }
  for (const auto& c : m.camera_rejected()) {
    auto cone = from_detected(c);
    if (auto* why = std::get_if<std::string>(&cone)) return *why;
    out.camera_rejected.push_back(std::get<Cone>(cone));
  }
  return out;
}

Checked<RemotePose> from_odometry(const nav_msgs::msg::dds_::Odometry_& m, double epoch) {
  if (auto bad = bad_stamp(m.header())) return *bad;
  if (m.header().frame_id() != kMapFrame)
    return "header.frame_id '" + m.header().frame_id().substr(0, 64) + "', not " + kMapFrame;
  const auto& p = m.pose().pose().position();
  const auto& q = m.pose().pose().orientation();
  if (!finite_within(p.x(), kMaxCoordinate) || !finite_within(p.y(), kMaxCoordinate))
    return std::string("the position is not finite or out of range");
  const double n = q.x() * q.x() + q.y() * q.y() + q.z() * q.z() + q.w() * q.w();
  if (!std::isfinite(n) || std::abs(n - 1.0) > 1e-3) return std::string("the orientation is not a unit quaternion");
  RemotePose out;
  out.t = from_ros_time({m.header().stamp().sec(), m.header().stamp().nanosec()}) - epoch;
  const double yaw = std::atan2(2 * (q.w() * q.z() + q.x() * q.y()), 1 - 2 * (q.y() * q.y() + q.z() * q.z()));
  out.pose = Pose2{p.x(), p.y(), yaw};
  return out;
}

Checked<RemoteImage> from_compressed_image(sensor_msgs::msg::dds_::CompressedImage_&& m, double epoch) {
  if (auto bad = bad_stamp(m.header())) return *bad;
  if (m.format().rfind("jpeg", 0) != 0 && m.format().find("jpeg compressed") == std::string::npos)
    return "format '" + m.format().substr(0, 64) + "', not jpeg";
  const auto& d = m.data();
  if (d.size() < 4 || d.size() > kMaxJpegBytes) return "a JPEG of " + std::to_string(d.size()) + " bytes";
  if (d[0] != 0xFF || d[1] != 0xD8) return std::string("no JPEG start-of-image marker");
  RemoteImage out;
  out.capture = from_ros_time({m.header().stamp().sec(), m.header().stamp().nanosec()}) - epoch;
  out.jpeg = std::move(m.data());
  return out;
}

}  // namespace fsd::dds

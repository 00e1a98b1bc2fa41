#include "daemon/dds/run_dds.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <stdexcept>

#include "common/logging.hpp"
#include "daemon/dds/dds_bridge.hpp"
#include "daemon/dds/remote_perception.hpp"
#include "daemon/stack/settings.hpp"
#include "daemon/stack/stack.hpp"

namespace fsd::dds {

struct RunDds::Impl {
  DdsSettings settings;
  bool remote = false;  // run.perception_source = dds
  bool simulator = false;
  // Declared before the bridge: the bridge's participant holds the reader whose listener this is, and goes first.
  std::unique_ptr<RemotePerception> perception;
  std::unique_ptr<DdsBridge> bridge;
  int udp = -1;  // the virtual car's VLP-16 packets to the perception process
  sockaddr_in lidar_to{};
  std::uint64_t udp_sent = 0, udp_failed = 0, frames_used = 0;

  ~Impl() {
    if (bridge) bridge->stop();
    bridge.reset();
    if (udp >= 0) ::close(udp);
  }
};

std::unique_ptr<RunDds> RunDds::make(const Config& cfg, bool simulator) {
  auto m = std::make_unique<Impl>();
  m->settings = dds_section().read(cfg);
  m->remote = run_section().read(cfg).perception_source == "dds";
  m->simulator = simulator;
  if (!m->settings.enabled && !m->remote) return nullptr;
  // Split mode needs the participant even with the publishing off: the perception process's frames come over it,
  // and the pose it places its scans by goes out on /fsd/odom.
  DdsSettings s = m->settings;
  if (!s.enabled) s.topics = m->remote ? "odom" : "";
  std::set<std::string> without;
  if (m->remote) without = {"cloud", "detections"};  // the perception process publishes them
  m->bridge = std::make_unique<DdsBridge>(s, without);
  if (m->remote) m->perception = std::make_unique<RemotePerception>(m->bridge->participant());
  if (m->remote && simulator) {
    m->udp = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (m->udp < 0) throw std::invalid_argument("dds.sim_lidar_address: cannot open a UDP socket");
    m->lidar_to.sin_family = AF_INET;
    m->lidar_to.sin_port = htons(static_cast<std::uint16_t>(m->settings.sim_lidar_port));
    if (inet_pton(AF_INET, m->settings.sim_lidar_address.c_str(), &m->lidar_to.sin_addr) != 1)
      throw std::invalid_argument("dds.sim_lidar_address: '" + m->settings.sim_lidar_address +
                                  "' is not an IPv4 address");
    if (m->settings.sim_camera) m->bridge->open_camera_topic();
    logger("dds")->info("split mode: the virtual car's VLP-16 to udp {}:{}, its camera on DDS{}",
                        m->settings.sim_lidar_address, m->settings.sim_lidar_port,
                        m->settings.sim_camera ? "" : " (off: dds.sim_camera)");
  }
  return std::unique_ptr<RunDds>(new RunDds(std::move(m)));
}

RunDds::RunDds(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
RunDds::~RunDds() = default;

void RunDds::start(Stack& stack, double epoch) {
  impl_->bridge->attach(stack, epoch);
  if (impl_->perception) impl_->perception->set_epoch(epoch);
}

void RunDds::before_step(Stack& stack) {
  if (!impl_->perception) return;
  while (auto f = impl_->perception->poll()) {
    stack.feed_remote_detections(std::move(f->detections), std::move(f->camera_rejected));
    ++impl_->frames_used;
  }
}

void RunDds::lidar_packet(std::span<const std::uint8_t> bytes) {
  if (impl_->udp < 0) return;
  const auto n = ::sendto(impl_->udp, bytes.data(), bytes.size(), 0,
                          reinterpret_cast<const sockaddr*>(&impl_->lidar_to), sizeof impl_->lidar_to);
  ++(n == static_cast<ssize_t>(bytes.size()) ? impl_->udp_sent : impl_->udp_failed);
}

void RunDds::camera_frame(Stamp capture, std::span<const std::uint8_t> jpeg) {
  if (!impl_->remote || !impl_->simulator || !impl_->settings.sim_camera) return;
  impl_->bridge->publish_camera(std::make_shared<const std::vector<std::uint8_t>>(jpeg.begin(), jpeg.end()), capture);
}

void RunDds::stop() {
  if (impl_->bridge) impl_->bridge->stop();
}

std::string RunDds::summary() const {
  const auto b = impl_->bridge->counters();
  std::string s = "dds: " + std::to_string(b.published) + " messages published, " + std::to_string(b.dropped) +
                  " dropped by the outbox";
  if (impl_->perception) {
    const auto p = impl_->perception->counters();
    s += "; perception frames " + std::to_string(p.received) + " received, " + std::to_string(p.refused) +
         " refused, " + std::to_string(p.dropped) + " dropped, " + std::to_string(impl_->frames_used) + " used";
  }
  if (impl_->udp >= 0)
    s += "; VLP-16 packets " + std::to_string(impl_->udp_sent) + " sent, " + std::to_string(impl_->udp_failed) + " not";
  return s;
}

}  // namespace fsd::dds

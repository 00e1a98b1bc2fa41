#include "daemon/dds/remote_perception.hpp"

#include <chrono>

#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "common/logging.hpp"
#include "daemon/dds/checked_type.hpp"
#include "daemon/dds/dds_participant.hpp"
#include "daemon/dds/topics.hpp"
#include "fsd_msgs/msg/ConeDetectionsPubSubTypes.h"

namespace fsd::dds {

namespace fdds = eprosima::fastdds::dds;

namespace {
constexpr std::size_t kFramesQueued = 16;  // 1.6 s of 10 Hz frames: the control thread takes them every 10 ms
}

struct RemotePerception::Listener final : fdds::DataReaderListener {
  BoundedQueue<RemoteDetections> frames{kFramesQueued};
  std::atomic<double> epoch{0};
  std::atomic<std::uint64_t> received{0}, refused{0};
  std::atomic<std::int64_t> last_log_ns{0};  // Fast DDS may call from more than one thread

  void on_data_available(fdds::DataReader* reader) override {
    fsd_msgs::msg::dds_::ConeDetections_ m;
    fdds::SampleInfo info;
    while (reader->take_next_sample(&m, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      received.fetch_add(1, std::memory_order_relaxed);
      auto checked = from_detections(m, epoch.load());
      if (auto* why = std::get_if<std::string>(&checked)) {
        refused.fetch_add(1, std::memory_order_relaxed);
        const std::int64_t now = std::chrono::steady_clock::now().time_since_epoch().count();
        std::int64_t last = last_log_ns.load();
        if (now - last > std::chrono::nanoseconds(std::chrono::seconds(1)).count() &&
            last_log_ns.compare_exchange_strong(last, now)) {
          logger("dds")->warn("refused a perception frame: {} ({} refused so far)", *why, refused.load());
        }
        continue;
      }
      frames.push(std::move(std::get<RemoteDetections>(checked)));
    }
  }
};

RemotePerception::RemotePerception(Participant& participant) : listener_(std::make_unique<Listener>()) {
  participant.reader(kDetectionsTopic,
                     fdds::TypeSupport(new CheckedType<fsd_msgs::msg::dds_::ConeDetections_PubSubType>),
                     TopicKind::State, listener_.get());
}

// The participant (which the caller destroys after this) still holds the reader: its listener must stay valid
// until then, so the caller keeps this object alive longer than the participant's readers run. The bridge's
// participant is destroyed first in every feeder (it is declared after this object).
RemotePerception::~RemotePerception() = default;

void RemotePerception::set_epoch(double epoch) { listener_->epoch.store(epoch); }

std::optional<RemoteDetections> RemotePerception::poll() { return listener_->frames.try_pop(); }

RemotePerceptionCounters RemotePerception::counters() const {
  return {listener_->received.load(), listener_->refused.load(), listener_->frames.dropped()};
}

}  // namespace fsd::dds

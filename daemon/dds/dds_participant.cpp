#include "daemon/dds/dds_participant.hpp"

#include <stdexcept>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

namespace fsd::dds {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

namespace {

constexpr int kStateDepth = 10, kStreamDepth = 2, kEventsDepth = 100;
// A cloud is ~0.7 MB: shared memory segments and socket buffers that hold several, so that a best-effort cloud is not
// lost to a full buffer (Fast DDS's defaults, 512 kB and the kernel's ~200 kB, lost 5 % of them between two
// processes on one computer; bench/dds_bench.cpp).
constexpr std::uint32_t kShmSegmentBytes = 8u << 20;
constexpr std::uint32_t kSocketBufferBytes = 4u << 20;

fdds::DataWriterQos writer_qos(TopicKind kind) {
  fdds::DataWriterQos q = fdds::DATAWRITER_QOS_DEFAULT;
  q.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
  switch (kind) {
    case TopicKind::State:
      q.reliability().kind = fdds::RELIABLE_RELIABILITY_QOS;
      q.durability().kind = fdds::VOLATILE_DURABILITY_QOS;
      q.history().depth = kStateDepth;
      break;
    case TopicKind::Stream:
      q.reliability().kind = fdds::BEST_EFFORT_RELIABILITY_QOS;
      q.durability().kind = fdds::VOLATILE_DURABILITY_QOS;
      q.history().depth = kStreamDepth;
      break;
    case TopicKind::Events:
      q.reliability().kind = fdds::RELIABLE_RELIABILITY_QOS;
      q.durability().kind = fdds::TRANSIENT_LOCAL_DURABILITY_QOS;
      q.history().depth = kEventsDepth;
      break;
  }
  // Large samples (a cloud is 100s of kB) are fragmented; the writer's history grows as they need.
  q.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  return q;
}

fdds::DataReaderQos reader_qos(TopicKind kind) {
  fdds::DataReaderQos q = fdds::DATAREADER_QOS_DEFAULT;
  q.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
  q.reliability().kind = kind == TopicKind::Stream ? fdds::BEST_EFFORT_RELIABILITY_QOS : fdds::RELIABLE_RELIABILITY_QOS;
  q.durability().kind = fdds::VOLATILE_DURABILITY_QOS;
  q.history().depth = kind == TopicKind::Stream ? kStreamDepth : kStateDepth;
  q.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  return q;
}

}  // namespace

std::string wire_topic(const std::string& ros_topic) { return "rt" + ros_topic; }

Participant::Participant(const DdsSettings& s, const std::string& name) {
  fdds::DomainParticipantQos pq = fdds::PARTICIPANT_QOS_DEFAULT;
  pq.name(name);
  auto& builtin = pq.wire_protocol().builtin;
  const auto peers = parse_peers(s.initial_peers);
  if (!peers.empty()) {
    // Given peers replace Fast DDS's default (multicast); it is put back when multicast is wanted.
    for (const auto& p : peers) {
      Locator_t l;
      IPLocator::setIPv4(l, p);
      builtin.initialPeersList.push_back(l);  // port 0: each participant id's discovery port is tried
    }
    if (s.multicast) {
      Locator_t m;
      IPLocator::setIPv4(m, "239.255.0.1");
      m.port = static_cast<std::uint32_t>(7400 + 250 * s.domain);
      builtin.initialPeersList.push_back(m);
    }
  }
  pq.transport().use_builtin_transports = false;
  auto shm = std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>();
  shm->segment_size(kShmSegmentBytes);
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->sendBufferSize = kSocketBufferBytes;
  udp->receiveBufferSize = kSocketBufferBytes;
  pq.transport().user_transports = {shm, udp};
  participant_ = fdds::DomainParticipantFactory::get_instance()->create_participant(s.domain, pq);
  if (!participant_)
    throw std::invalid_argument("dds.domain " + std::to_string(s.domain) +
                                ": Fast DDS could not create a participant (see its log above)");
  publisher_ = participant_->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  if (!publisher_ || !subscriber_) throw std::invalid_argument("dds: Fast DDS could not create a publisher");
}

Participant::~Participant() {
  if (!participant_) return;
  participant_->delete_contained_entities();
  fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

fdds::Topic* Participant::topic(const std::string& ros_topic, fdds::TypeSupport& type) {
  if (auto it = topics_.find(ros_topic); it != topics_.end()) return it->second;
  if (participant_->find_type(type.get_type_name()).empty() &&
      type.register_type(participant_) != ReturnCode_t::RETCODE_OK)
    throw std::runtime_error("dds: cannot register type " + type.get_type_name());
  fdds::Topic* t = participant_->create_topic(wire_topic(ros_topic), type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  if (!t) throw std::runtime_error("dds: cannot create topic " + wire_topic(ros_topic));
  topics_[ros_topic] = t;
  return t;
}

fdds::DataWriter* Participant::writer(const std::string& ros_topic, fdds::TypeSupport type, TopicKind kind) {
  fdds::DataWriter* w = publisher_->create_datawriter(topic(ros_topic, type), writer_qos(kind));
  if (!w) throw std::runtime_error("dds: cannot create a writer on " + ros_topic);
  return w;
}

fdds::DataReader* Participant::reader(const std::string& ros_topic, fdds::TypeSupport type, TopicKind kind,
                                      fdds::DataReaderListener* listener) {
  fdds::DataReader* r = subscriber_->create_datareader(topic(ros_topic, type), reader_qos(kind), listener);
  if (!r) throw std::runtime_error("dds: cannot create a reader on " + ros_topic);
  return r;
}

}  // namespace fsd::dds

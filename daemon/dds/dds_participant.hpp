#pragma once
// One Fast DDS participant with the daemon's conventions (docs/dds.md): ROS 2's names (a topic /fsd/x is
// "rt/fsd/x" on the wire; types pkg::msg::dds_::T_), the QoS of each kind of topic, discovery by multicast and/or
// the configured initial peers. It owns every entity it made and deletes them in its destructor; readers' listeners
// are called on Fast DDS's own threads and must outlive the participant.
#include <map>
#include <memory>
#include <string>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "daemon/dds/dds_settings.hpp"

namespace fsd::dds {

// The QoS kinds (docs/dds.md): state and commands reliable (keep the last 10); clouds and images best effort
// (keep the last 2: a late one is worth less than the next); events (laps, faults) reliable and transient-local,
// so a tool that joins late still reads the run's last 100.
enum class TopicKind { State, Stream, Events };

class Participant {
 public:
  // Throws std::invalid_argument naming dds.domain / dds.initial_peers when Fast DDS refuses the participant.
  Participant(const DdsSettings& settings, const std::string& name);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  // `ros_topic`: the ROS 2 name ("/fsd/odom"). The type is registered once per name.
  eprosima::fastdds::dds::DataWriter* writer(const std::string& ros_topic, eprosima::fastdds::dds::TypeSupport type,
                                             TopicKind kind);
  eprosima::fastdds::dds::DataReader* reader(const std::string& ros_topic, eprosima::fastdds::dds::TypeSupport type,
                                             TopicKind kind, eprosima::fastdds::dds::DataReaderListener* listener);

 private:
  eprosima::fastdds::dds::Topic* topic(const std::string& ros_topic, eprosima::fastdds::dds::TypeSupport& type);
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
};

// "/fsd/odom" -> "rt/fsd/odom", as rmw_fastrtps and rmw_cyclonedds name ROS 2 topics in DDS.
std::string wire_topic(const std::string& ros_topic);

}  // namespace fsd::dds

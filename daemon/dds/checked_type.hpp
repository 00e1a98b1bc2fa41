#pragma once
// A fastddsgen type (T_PubSubType) whose deserializer refuses bytes it cannot decode instead of throwing. The
// generated deserialize() (fastddsgen 2.3) catches Fast CDR's NotEnoughMemoryException only: a payload with a bad
// encapsulation header or a boolean byte other than 0 or 1 throws BadParamException through the DataReader's
// take() and out of the listener on Fast DDS's thread, which ends the process (found by dds_messages_fuzz). Every
// reader of the network's samples registers its type through this.
#include <fastcdr/exceptions/Exception.h>
#include <fastdds/rtps/common/SerializedPayload.h>

namespace fsd::dds {

template <class Generated>
class CheckedType final : public Generated {
 public:
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    try {
      return Generated::deserialize(payload, data);
    } catch (const eprosima::fastcdr::exception::Exception&) {
      return false;
    }
  }
};

}  // namespace fsd::dds

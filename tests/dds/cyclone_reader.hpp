#pragma once
// The independent reader of the daemon's DDS topics: Cyclone DDS (ROS 2's other tier-1 middleware), through its C
// API, with the types its own idlc generated from daemon/dds/idl. A Cyclone reader matches a writer only on the
// same topic name and type name, so data arriving here is data under the ROS 2 names; DCPSPublication says what
// each remote writer declared.
#include <dds/dds.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <string>
#include <thread>

#include <unistd.h>

namespace fsd::test {

// A domain of the test's own (no cross-talk with another test process), discovered by unicast on loopback only:
// multicast is not needed (the daemon is given dds.initial_peers = 127.0.0.1).
inline int test_domain() { return 100 + static_cast<int>(::getpid() % 100); }

inline void configure_cyclone_for_loopback() {
  static const char* xml =
      "<CycloneDDS><Domain id=\"any\"><General><AllowMulticast>false</AllowMulticast></General>"
      "<Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>30</MaxAutoParticipantIndex>"
      "<Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery>"
      "<Internal><SocketReceiveBufferSize min=\"default\"/></Internal></Domain></CycloneDDS>";
  ::setenv("CYCLONEDDS_URI", xml, 1);
}

class CycloneParticipant {
 public:
  explicit CycloneParticipant(int domain) {
    configure_cyclone_for_loopback();
    pp_ = dds_create_participant(static_cast<dds_domainid_t>(domain), nullptr, nullptr);
  }
  ~CycloneParticipant() {
    if (pp_ > 0) dds_delete(pp_);
  }
  dds_entity_t handle() const { return pp_; }
  bool ok() const { return pp_ > 0; }

 private:
  dds_entity_t pp_ = 0;
};

// One topic's reader. `reliable`: the QoS the daemon documents for it (a best-effort reader of a reliable writer
// matches too; a reliable reader of a best-effort writer does not, which the cloud's reader checks).
class CycloneReader {
 public:
  CycloneReader(const CycloneParticipant& p, const std::string& wire_topic, const dds_topic_descriptor_t* desc,
                bool reliable, int depth = 64) {
    topic_ = dds_create_topic(p.handle(), desc, wire_topic.c_str(), nullptr, nullptr);
    dds_qos_t* q = dds_create_qos();
    dds_qset_reliability(q, reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT, DDS_SECS(1));
    dds_qset_history(q, DDS_HISTORY_KEEP_LAST, depth);
    reader_ = dds_create_reader(p.handle(), topic_, q, nullptr);
    dds_delete_qos(q);
  }
  bool ok() const { return topic_ > 0 && reader_ > 0; }
  // Hands each valid sample taken to `f` (as the generated C struct); returns how many.
  int take(const std::function<void(const void*)>& f) {
    int n = 0;
    for (;;) {
      void* samples[16] = {nullptr};
      dds_sample_info_t infos[16];
      const dds_return_t got = dds_take(reader_, samples, infos, 16, 16);
      if (got <= 0) break;
      for (int k = 0; k < got; ++k)
        if (infos[k].valid_data) {
          f(samples[k]);
          ++n;
        }
      dds_return_loan(reader_, samples, got);
    }
    return n;
  }

 private:
  dds_entity_t topic_ = 0, reader_ = 0;
};

}  // namespace fsd::test

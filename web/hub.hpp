#pragma once
// The socket-free heart of the server: the advertised channels, the connected clients, the fan-out of published
// telemetry into each client's bounded queue, and the Foxglove protocol's replies to what a client sends
// (subscriptions, parameters with authorisation). The Beast sessions only move bytes in and out of it.
//
// Publishing is wait-free: publish() puts the message in a lock-free ring (the outbox) and returns; the server's
// I/O thread drains the ring every couple of milliseconds (drain()) and does the fan-out, the latching and the
// wake-ups. So the cost on the control thread does not depend on the number of clients, and no client, lock or
// system call can make it wait.
#include <array>
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/params.hpp"
#include "common/time.hpp"
#include "web/client_state.hpp"
#include "web/metrics.hpp"
#include "web/mpmc_ring.hpp"
#include "web/protocol.hpp"

namespace fsd::web {

struct ChannelOptions {
  // The last message is kept and sent to each new subscriber at once (maps, paths, AS state: things that
  // change rarely but that a client connecting late must see).
  bool latched = false;
  // The last `backlog` messages are kept and sent to each new subscriber (the log: a page opened after an
  // event shows the lines before it). Bounded by the client's telemetry queue; latched is a backlog of 1.
  std::size_t backlog = 0;
  // The messages are changes to a state (a SceneUpdate sent by entity, web/scene_delta.hpp) and publish() hands the
  // whole state beside each: the hub keeps that state (not the change) for each new subscriber, and a client
  // whose queue dropped one of the changes gets the whole state again, so no client keeps a stale entity.
  bool delta = false;
};

// One connected WebSocket client as the hub sees it.
struct Peer {
  std::shared_ptr<ClientState> state;
  std::function<void()> wake;             // schedules the client's writer; called when a push reports the writer idle
  std::atomic<bool> wake_pending{false};  // set during a drain pass; the pass then calls wake once
  std::string address;                    // "ip:port", for logs and the attribution of parameter changes
  bool token_ok = false;                  // the WebSocket URL carried the right ?token=
};

struct HubLimits {
  int max_clients = 32;
  std::size_t telemetry_queue = 256;
  std::size_t control_queue = 1024;
  std::size_t outbox = 4096;  // messages published and not yet drained
};

class Hub : public std::enable_shared_from_this<Hub> {
 public:
  Hub(ParamRegistry& params, std::string token, Metrics& metrics, HubLimits limits, std::string server_name);
  // Registers for parameter changes (call once after construction; the listener holds a weak reference).
  void listen_to_params();

  ChannelId add_channel(const std::string& topic, const std::string& schema_name, const std::string& json_schema,
                        ChannelOptions options = {});
  std::vector<foxglove::ChannelInfo> channels() const;
  // Any thread, wait-free: hands the message to the outbox (a full outbox drops it, counted). `state`: on a delta
  // channel, the whole state after this change (kept for new subscribers and resyncs in place of the message).
  void publish(ChannelId channel, Stamp t, std::string payload, std::string state = {});
  // On an I/O thread: moves the outbox into the subscribers' queues (a slow client loses its oldest messages),
  // keeps latched channels' last message and wakes the clients' writers.
  void drain();
  // On an I/O thread: a Foxglove time message to every client.
  void publish_time(Stamp t);

  // The state of a new client, with the configured queue sizes.
  std::shared_ptr<ClientState> make_client_state();

  // Admission: try_admit() takes a client slot (false when all max_clients are taken); release() gives it back.
  bool try_admit();
  void release();
  void add_peer(const std::shared_ptr<Peer>& peer);  // sends serverInfo and advertise
  void remove_peer(const Peer* peer);
  std::size_t peer_count() const;

  // Handles one text message of `peer`. Returns false when it was a protocol violation (malformed, unknown op,
  // refused parameter change); the session counts those and disconnects an abusive client.
  bool on_text(Peer& peer, std::string_view text);
  void send_status(Peer& peer, foxglove::StatusLevel level, const std::string& message);

  bool tuning_enabled() const { return !token_.empty(); }
  bool authorised(std::string_view given) const;
  void note_protocol_error() { protocol_errors_.inc(); }
  void note_param_refusal() { param_refusals_.inc(); }
  void note_param_changes(std::size_t n) { param_changes_.inc(n); }
  ParamRegistry& params() { return params_; }
  Metrics& metrics() { return metrics_; }

 private:
  static constexpr std::size_t kMaxChannels = ClientState::kMaxChannels;
  struct Latched {
    std::shared_ptr<const std::string> payload;
    std::uint64_t ns = 0;
  };
  struct Channel {
    foxglove::ChannelInfo info;
    ChannelOptions options;
    std::size_t keep = 0;                                           // messages kept: 1 latched or delta, or the backlog
    std::atomic<std::shared_ptr<const std::vector<Latched>>> kept;  // oldest first; only the drain writes it
  };
  using PeerList = std::vector<std::shared_ptr<Peer>>;

  Channel* channel(ChannelId id) const;     // nullptr for an unknown id; lock-free
  static void keep(Channel& c, Latched m);  // on the drain: appends to the kept messages, oldest out
  std::shared_ptr<const PeerList> peers() const;
  void push(Peer& peer, std::string text);
  void resync(Peer& peer);  // on the drain: the whole state of each delta channel the client lost a change of
  void on_param_change(const ParamChange& change);
  void handle(Peer& peer, const foxglove::SubscribeOp& op);
  void handle(Peer& peer, const foxglove::UnsubscribeOp& op);
  void handle(Peer& peer, const foxglove::GetParametersOp& op);
  bool handle(Peer& peer, const foxglove::SetParametersOp& op);
  void handle(Peer& peer, const foxglove::SubscribeParameterUpdatesOp& op);
  void handle(Peer& peer, const foxglove::UnsubscribeParameterUpdatesOp& op);

  ParamRegistry& params_;
  const std::string token_;
  Metrics& metrics_;
  const HubLimits limits_;
  const std::string name_;
  const std::string session_id_;

  // Channels are only ever appended: publishers index the array below the published count without a lock.
  std::mutex add_channel_m_;
  std::array<std::unique_ptr<Channel>, kMaxChannels> channels_;
  std::atomic<std::size_t> channel_count_{0};

  // Copy-on-write list of peers: writers (connect, disconnect) serialise on peers_write_m_ and swap the
  // pointer; publishers load it atomically.
  std::mutex peers_write_m_;
  std::atomic<std::shared_ptr<const PeerList>> peers_;
  std::atomic<int> admitted_{0};

  struct Outgoing {
    ChannelId channel = 0;
    std::uint64_t ns = 0;
    std::shared_ptr<const std::string> payload;
    std::shared_ptr<const std::string> state;  // delta channels: the whole state after this change
  };
  MpmcRing<Outgoing> outbox_;
  // Held by the drain and by a subscription's start (I/O threads only, never a publisher): a new subscriber gets
  // the kept state and then exactly the changes after it, also with two I/O threads.
  std::mutex fanout_m_;
  std::vector<ChannelId> delta_channels_;  // appended under add_channel_m_, read under fanout_m_

  Counter& published_;
  Counter& outbox_full_;
  Counter& dropped_;
  Counter& dropped_unknown_;
  Counter& protocol_errors_;
  Counter& param_changes_;
  Counter& param_refusals_;
  Counter& refused_clients_;
};

}  // namespace fsd::web

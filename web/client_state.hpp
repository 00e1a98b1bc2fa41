#pragma once
// What the server keeps for one WebSocket client, shared by the server's I/O threads (the hub's fan-out, the
// client's strand) and the parameter listener: its channel and parameter subscriptions and its outgoing queues.
// This is where back-pressure lives (as in foxglove_bridge): telemetry goes to a bounded queue that drops its
// oldest message when the client reads too slowly; protocol replies go to a separate queue that is never
// dropped from (a client that lets it overflow is disconnected). Every operation takes one short lock, never
// held across I/O. Publishers (the control thread) never come here: they hand over to the hub's ring.
#include <array>
#include <atomic>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "web/metrics.hpp"
#include "web/protocol.hpp"

namespace fsd::web {

using ChannelId = std::uint32_t;

struct OutMessage {
  bool binary = false;
  foxglove::MessageDataHeader header{};  // sent before `body` when header_size > 0
  std::size_t header_size = 0;
  std::shared_ptr<const std::string> body;  // shared by every client receiving the same message
  std::uint32_t subscription_id = 0;
  bool telemetry = false;

  std::size_t size() const { return header_size + (body ? body->size() : 0); }
};

class ClientState {
 public:
  static constexpr std::size_t kMaxChannels = 256;  // channel ids 1..kMaxChannels

  // `drops`, when given, counts the dropped telemetry of every client together (for /metrics).
  ClientState(std::size_t telemetry_capacity, std::size_t control_capacity, Counter* drops = nullptr);

  enum class SubscribeResult { Ok, IdInUse, ChannelAlreadySubscribed };
  SubscribeResult subscribe(std::uint32_t subscription_id, ChannelId channel);
  // Ends a subscription and drops its queued messages; nullopt for an unknown id.
  std::optional<ChannelId> unsubscribe(std::uint32_t subscription_id);
  std::optional<std::uint32_t> subscription_of(ChannelId channel) const;

  void subscribe_params(const std::vector<std::string>& names);    // empty = all
  void unsubscribe_params(const std::vector<std::string>& names);  // empty = all
  bool wants_param(const std::string& name) const;

  // Each push returns true when the writer was idle: the caller must then wake it (exactly once).
  // Telemetry of `channel` for this client's subscription to it; does nothing (and takes no lock) when not
  // subscribed.
  bool offer(ChannelId channel, std::uint64_t timestamp_ns, const std::shared_ptr<const std::string>& payload);
  // A whole state of a delta channel: replaces that channel's queued messages (it supersedes them), so a resync
  // never drops anything and a slow client never queues the state twice.
  bool offer_state(ChannelId channel, std::uint64_t timestamp_ns, const std::shared_ptr<const std::string>& state);
  // A droppable binary frame that belongs to no subscription (time messages).
  bool offer_binary(std::shared_ptr<const std::string> frame);
  // A protocol reply (text). When the control queue is full the message is refused and overflowed() turns true.
  bool push_control(std::string text);

  // The next message to write, protocol replies first. nullopt marks the writer idle.
  std::optional<OutMessage> next();
  // Refuses every later push and empties the queues.
  void close();

  // Whether telemetry was dropped since the last take_lost(); take_lost() gives the channels that lost a message
  // and forgets them (delta channels resync then).
  bool lost_any() const { return lost_any_.load(std::memory_order_relaxed); }
  std::vector<ChannelId> take_lost();

  bool overflowed() const { return overflowed_.load(std::memory_order_relaxed); }
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }
  std::size_t depth() const;

 private:
  bool push_telemetry(OutMessage m);  // with m_ held
  bool subscribed(ChannelId channel) const;
  void drop(const OutMessage& lost);  // with m_ held

  const std::size_t telemetry_capacity_, control_capacity_;
  Counter* drops_;
  mutable std::mutex m_;
  std::array<std::atomic<std::uint64_t>, kMaxChannels / 64> subscribed_bits_{};  // bit (id - 1), for offer()
  std::unordered_map<ChannelId, std::uint32_t> sub_of_channel_;
  std::unordered_map<std::uint32_t, ChannelId> channel_of_sub_;
  bool all_params_ = false;
  std::set<std::string> params_;
  std::deque<OutMessage> telemetry_, control_;
  bool writing_ = false;
  bool closed_ = false;
  std::array<std::atomic<std::uint64_t>, kMaxChannels / 64> lost_bits_{};  // bit (id - 1): a message dropped
  std::atomic<bool> lost_any_{false};
  std::atomic<bool> overflowed_{false};
  std::atomic<std::uint64_t> dropped_{0};
};

}  // namespace fsd::web

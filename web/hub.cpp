#include "web/hub.hpp"

#include <algorithm>
#include <chrono>

#include "common/logging.hpp"
#include "web/auth.hpp"
#include "web/params_json.hpp"

namespace fsd::web {

using foxglove::StatusLevel;
using nlohmann::json;

namespace {
std::string join(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : ", ") + s;
  return out;
}
}  // namespace

Hub::Hub(ParamRegistry& params, std::string token, Metrics& metrics, HubLimits limits, std::string server_name)
    : params_(params),
      token_(std::move(token)),
      metrics_(metrics),
      limits_(limits),
      name_(std::move(server_name)),
      session_id_(std::to_string(std::chrono::system_clock::now().time_since_epoch().count())),
      peers_(std::make_shared<const PeerList>()),
      outbox_(limits.outbox),
      published_(metrics.counter("fsd_web_published_total", "Messages handed to the web server by publishers")),
      outbox_full_(metrics.counter("fsd_web_outbox_dropped_total",
                                   "Messages dropped because the web I/O thread fell behind the publishers")),
      dropped_(metrics.counter("fsd_web_messages_dropped_total",
                               "Telemetry messages dropped because a client read too slowly")),
      dropped_unknown_(
          metrics.counter("fsd_web_publish_unknown_channel_total", "Publishes to a channel id never added")),
      protocol_errors_(
          metrics.counter("fsd_web_protocol_errors_total", "Client messages refused as malformed or not allowed")),
      param_changes_(metrics.counter("fsd_web_param_changes_total", "Parameter changes made over the web")),
      param_refusals_(metrics.counter("fsd_web_param_refusals_total",
                                      "Parameter changes refused (no valid token or invalid value)")),
      refused_clients_(metrics.counter("fsd_web_clients_refused_total",
                                       "WebSocket clients refused because max_clients were connected")) {
  metrics.gauge_callback("fsd_web_clients", "Connected WebSocket clients",
                         [this] { return static_cast<double>(peer_count()); });
  metrics.gauge_callback("fsd_web_send_queue_depth_max", "Deepest send queue of any client (messages)", [this] {
    std::size_t deepest = 0;
    for (const auto& p : *peers()) deepest = std::max(deepest, p->state->depth());
    return static_cast<double>(deepest);
  });
  metrics.gauge_callback("fsd_web_outbox_depth", "Messages published and not yet fanned out by the web I/O thread",
                         [this] { return static_cast<double>(outbox_.approx_size()); });
}

void Hub::listen_to_params() {
  params_.subscribe([weak = weak_from_this()](const ParamChange& c) {
    if (auto self = weak.lock()) self->on_param_change(c);
  });
}

ChannelId Hub::add_channel(const std::string& topic, const std::string& schema_name, const std::string& json_schema,
                           ChannelOptions options) {
  foxglove::ChannelInfo info;
  {
    std::lock_guard lock(add_channel_m_);
    const std::size_t n = channel_count_.load();
    for (std::size_t i = 0; i < n; ++i)
      if (channels_[i]->info.topic == topic) throw std::logic_error("web: channel '" + topic + "' added twice");
    if (n == kMaxChannels) throw std::logic_error("web: more than " + std::to_string(kMaxChannels) + " channels");
    info.id = static_cast<ChannelId>(n + 1);
    info.topic = topic;
    info.schema_name = schema_name;
    info.schema = json_schema;
    auto c = std::make_unique<Channel>();
    c->info = info;
    c->options = options;
    c->keep = std::min(std::max(options.backlog, options.latched || options.delta ? std::size_t{1} : std::size_t{0}),
                       limits_.telemetry_queue);
    channels_[n] = std::move(c);
    channel_count_.store(n + 1);  // publishes the new slot
    if (options.delta) {
      std::lock_guard fanout(fanout_m_);
      delta_channels_.push_back(info.id);
    }
  }
  const std::string msg = foxglove::advertise({info});
  for (const auto& p : *peers()) push(*p, msg);
  return info.id;
}

std::vector<foxglove::ChannelInfo> Hub::channels() const {
  std::vector<foxglove::ChannelInfo> out;
  const std::size_t n = channel_count_.load();
  for (std::size_t i = 0; i < n; ++i) out.push_back(channels_[i]->info);
  return out;
}

Hub::Channel* Hub::channel(ChannelId id) const {
  return id >= 1 && id <= channel_count_.load() ? channels_[id - 1].get() : nullptr;
}

std::shared_ptr<const Hub::PeerList> Hub::peers() const { return peers_.load(); }

void Hub::publish(ChannelId channel, Stamp t, std::string payload, std::string state) {
  const std::uint64_t ns = foxglove::to_nanoseconds(t);
  if (!this->channel(channel)) {
    dropped_unknown_.inc();
    return;
  }
  auto whole = state.empty() ? nullptr : std::make_shared<const std::string>(std::move(state));
  if (outbox_.try_push({channel, ns, std::make_shared<const std::string>(std::move(payload)), std::move(whole)}))
    published_.inc();
  else
    outbox_full_.inc();
}

void Hub::drain() {
  std::lock_guard fanout(fanout_m_);
  const auto list = peers();
  Outgoing m;
  bool any = false;
  while (outbox_.try_pop(m)) {
    Channel* c = channel(m.channel);
    if (c->keep > 0) keep(*c, Latched{c->options.delta && m.state ? m.state : m.payload, m.ns});
    for (const auto& p : *list)
      if (p->state->offer(m.channel, m.ns, m.payload)) any = p->wake_pending = true;
  }
  for (const auto& p : *list)
    if (p->state->lost_any()) {
      resync(*p);
      any = true;
    }
  if (!any) return;
  for (const auto& p : *list)
    if (p->wake_pending.exchange(false)) p->wake();
}

void Hub::resync(Peer& peer) {
  for (const ChannelId id : peer.state->take_lost()) {
    if (std::find(delta_channels_.begin(), delta_channels_.end(), id) == delta_channels_.end()) continue;
    const auto kept = channel(id)->kept.load();
    if (kept && !kept->empty() && peer.state->offer_state(id, kept->back().ns, kept->back().payload))
      peer.wake_pending = true;
  }
}

void Hub::keep(Channel& c, Latched m) {
  // Copy-on-write, so a subscribe on another I/O thread reads a whole list; at most `keep` pointers copied.
  const auto old = c.kept.load();
  auto next = std::make_shared<std::vector<Latched>>();
  next->reserve(c.keep);
  if (old) {
    const std::size_t first = old->size() + 1 > c.keep ? old->size() + 1 - c.keep : 0;
    next->assign(old->begin() + static_cast<std::ptrdiff_t>(first), old->end());
  }
  next->push_back(std::move(m));
  c.kept.store(std::move(next));
}

void Hub::publish_time(Stamp t) {
  const auto msg = foxglove::time_message(foxglove::to_nanoseconds(t));
  auto frame = std::make_shared<const std::string>(msg.begin(), msg.end());
  for (const auto& p : *peers())
    if (p->state->offer_binary(frame)) p->wake();
}

std::shared_ptr<ClientState> Hub::make_client_state() {
  return std::make_shared<ClientState>(limits_.telemetry_queue, limits_.control_queue, &dropped_);
}

bool Hub::try_admit() {
  int n = admitted_.load();
  while (n < limits_.max_clients)
    if (admitted_.compare_exchange_weak(n, n + 1)) return true;
  refused_clients_.inc();
  return false;
}

void Hub::release() { admitted_.fetch_sub(1); }

void Hub::add_peer(const std::shared_ptr<Peer>& peer) {
  {
    std::lock_guard lock(peers_write_m_);
    auto next = std::make_shared<PeerList>(*peers_.load());
    next->push_back(peer);
    peers_.store(std::move(next));
  }
  std::vector<std::string> caps{"parameters", "parametersSubscribe", "time"};
  json meta{{"tuning", tuning_enabled() ? (peer->token_ok ? "authorised" : "token required") : "disabled"}};
  push(*peer, foxglove::server_info(name_, caps, meta, session_id_));
  push(*peer, foxglove::advertise(channels()));
  logger("web")->info("client {} connected{}", peer->address, peer->token_ok ? " (token ok)" : "");
}

void Hub::remove_peer(const Peer* peer) {
  std::lock_guard lock(peers_write_m_);
  auto next = std::make_shared<PeerList>();
  for (const auto& p : *peers_.load())
    if (p.get() != peer) next->push_back(p);
  peers_.store(std::move(next));
}

std::size_t Hub::peer_count() const { return peers()->size(); }

void Hub::push(Peer& peer, std::string text) {
  if (peer.state->push_control(std::move(text))) peer.wake();
}

void Hub::send_status(Peer& peer, StatusLevel level, const std::string& message) {
  push(peer, foxglove::status(level, message));
}

bool Hub::authorised(std::string_view given) const { return token_matches(given, token_); }

bool Hub::on_text(Peer& peer, std::string_view text) {
  auto parsed = foxglove::parse_client_message(text);
  if (!parsed.op) {
    protocol_errors_.inc();
    send_status(peer, StatusLevel::Error, parsed.error);
    return false;
  }
  return std::visit(
      [&](const auto& op) {
        if constexpr (std::is_same_v<std::decay_t<decltype(op)>, foxglove::SetParametersOp>) {
          return handle(peer, op);
        } else {
          handle(peer, op);
          return true;
        }
      },
      *parsed.op);
}

void Hub::handle(Peer& peer, const foxglove::SubscribeOp& op) {
  std::lock_guard fanout(fanout_m_);  // the kept messages, then exactly what the drain fans out after them
  for (const auto& s : op.subscriptions) {
    const Channel* c = channel(s.channel_id);
    if (!c) {
      send_status(peer, StatusLevel::Error, "subscribe: unknown channel " + std::to_string(s.channel_id));
      continue;
    }
    const auto kept = c->kept.load();
    switch (peer.state->subscribe(s.id, s.channel_id)) {
      case ClientState::SubscribeResult::IdInUse:
        send_status(peer, StatusLevel::Error, "subscribe: subscription id " + std::to_string(s.id) + " is in use");
        continue;
      case ClientState::SubscribeResult::ChannelAlreadySubscribed:
        send_status(peer, StatusLevel::Error,
                    "subscribe: channel " + std::to_string(s.channel_id) + " is already subscribed");
        continue;
      case ClientState::SubscribeResult::Ok:
        break;
    }
    bool wake = false;
    if (kept)
      for (const auto& m : *kept) wake = peer.state->offer(s.channel_id, m.ns, m.payload) || wake;
    if (wake) peer.wake();
  }
}

void Hub::handle(Peer& peer, const foxglove::UnsubscribeOp& op) {
  for (const auto id : op.subscription_ids)
    if (!peer.state->unsubscribe(id))
      send_status(peer, StatusLevel::Warning, "unsubscribe: no subscription " + std::to_string(id));
}

void Hub::handle(Peer& peer, const foxglove::GetParametersOp& op) {
  std::vector<std::string> unknown;
  auto values = parameters_json(params_, op.names, &unknown);
  if (!unknown.empty()) send_status(peer, StatusLevel::Warning, "getParameters: unknown parameters: " + join(unknown));
  push(peer, foxglove::parameter_values(values, op.id));
}

bool Hub::handle(Peer& peer, const foxglove::SetParametersOp& op) {
  std::vector<std::string> names;
  for (const auto& p : op.parameters) names.push_back(p.name);
  const auto reply_current = [&] {
    if (!names.empty()) push(peer, foxglove::parameter_values(parameters_json(params_, names), op.id));
  };
  const bool ok_token = peer.token_ok || (op.token && authorised(*op.token));
  if (!ok_token) {
    param_refusals_.inc();
    protocol_errors_.inc();
    const std::string why = !tuning_enabled() ? "parameter tuning is disabled on this car (no web token configured)"
                                              : "setParameters refused: no valid token";
    logger("web")->warn("{} tried to set [{}]: {}", peer.address, join(names), why);
    send_status(peer, StatusLevel::Error, why);
    reply_current();
    return false;
  }
  std::vector<std::pair<std::string, json>> changes;
  for (const auto& p : op.parameters) changes.emplace_back(p.name, p.value);
  const auto result = apply_parameters(params_, changes, "web " + peer.address + " (token ok)");
  if (!result.ok) {
    param_refusals_.inc();
    send_status(peer, StatusLevel::Error, "setParameters refused, nothing changed: " + join(result.errors));
  } else {
    param_changes_.inc(result.applied.size());
  }
  reply_current();
  return true;
}

void Hub::handle(Peer& peer, const foxglove::SubscribeParameterUpdatesOp& op) {
  std::vector<std::string> unknown;
  parameters_json(params_, op.names, &unknown);
  if (!unknown.empty())
    send_status(peer, StatusLevel::Warning, "subscribeParameterUpdates: unknown parameters: " + join(unknown));
  peer.state->subscribe_params(op.names);
}

void Hub::handle(Peer& peer, const foxglove::UnsubscribeParameterUpdatesOp& op) {
  peer.state->unsubscribe_params(op.names);
}

void Hub::on_param_change(const ParamChange& change) {
  std::string msg;
  for (const auto& p : *peers()) {
    if (!p->state->wants_param(change.key)) continue;
    if (msg.empty()) msg = foxglove::parameter_values(parameters_json(params_, {change.key}), std::nullopt);
    push(*p, msg);
  }
}

}  // namespace fsd::web

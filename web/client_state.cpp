#include "web/client_state.hpp"

#include <algorithm>

namespace fsd::web {

ClientState::ClientState(std::size_t telemetry_capacity, std::size_t control_capacity, Counter* drops)
    : telemetry_capacity_(std::max<std::size_t>(1, telemetry_capacity)),
      control_capacity_(std::max<std::size_t>(1, control_capacity)),
      drops_(drops) {}

ClientState::SubscribeResult ClientState::subscribe(std::uint32_t subscription_id, ChannelId channel) {
  std::lock_guard lock(m_);
  if (channel_of_sub_.count(subscription_id)) return SubscribeResult::IdInUse;
  if (sub_of_channel_.count(channel)) return SubscribeResult::ChannelAlreadySubscribed;
  channel_of_sub_[subscription_id] = channel;
  sub_of_channel_[channel] = subscription_id;
  if (channel >= 1 && channel <= kMaxChannels)
    subscribed_bits_[(channel - 1) / 64].fetch_or(1ull << ((channel - 1) % 64));
  return SubscribeResult::Ok;
}

std::optional<ChannelId> ClientState::unsubscribe(std::uint32_t subscription_id) {
  std::lock_guard lock(m_);
  const auto it = channel_of_sub_.find(subscription_id);
  if (it == channel_of_sub_.end()) return std::nullopt;
  const ChannelId channel = it->second;
  channel_of_sub_.erase(it);
  sub_of_channel_.erase(channel);
  if (channel >= 1 && channel <= kMaxChannels)
    subscribed_bits_[(channel - 1) / 64].fetch_and(~(1ull << ((channel - 1) % 64)));
  std::erase_if(telemetry_, [&](const OutMessage& m) { return m.header_size && m.subscription_id == subscription_id; });
  return channel;
}

std::optional<std::uint32_t> ClientState::subscription_of(ChannelId channel) const {
  std::lock_guard lock(m_);
  const auto it = sub_of_channel_.find(channel);
  if (it == sub_of_channel_.end()) return std::nullopt;
  return it->second;
}

void ClientState::subscribe_params(const std::vector<std::string>& names) {
  std::lock_guard lock(m_);
  if (names.empty()) all_params_ = true;
  params_.insert(names.begin(), names.end());
}

void ClientState::unsubscribe_params(const std::vector<std::string>& names) {
  std::lock_guard lock(m_);
  if (names.empty()) {
    all_params_ = false;
    params_.clear();
    return;
  }
  for (const auto& n : names) params_.erase(n);
}

bool ClientState::wants_param(const std::string& name) const {
  std::lock_guard lock(m_);
  return all_params_ || params_.count(name) > 0;
}

bool ClientState::subscribed(ChannelId channel) const {
  if (channel < 1 || channel > kMaxChannels) return false;
  return (subscribed_bits_[(channel - 1) / 64].load(std::memory_order_relaxed) >> ((channel - 1) % 64)) & 1u;
}

void ClientState::drop(const OutMessage& lost) {
  dropped_.fetch_add(1, std::memory_order_relaxed);
  if (drops_) drops_->inc();
  if (!lost.header_size) return;
  const auto it = channel_of_sub_.find(lost.subscription_id);
  if (it == channel_of_sub_.end() || it->second < 1 || it->second > kMaxChannels) return;
  lost_bits_[(it->second - 1) / 64].fetch_or(1ull << ((it->second - 1) % 64));
  lost_any_.store(true, std::memory_order_relaxed);
}

std::vector<ChannelId> ClientState::take_lost() {
  std::lock_guard lock(m_);
  lost_any_.store(false, std::memory_order_relaxed);
  std::vector<ChannelId> out;
  for (std::size_t w = 0; w < lost_bits_.size(); ++w) {
    const std::uint64_t bits = lost_bits_[w].exchange(0);
    for (std::size_t b = 0; b < 64; ++b)
      if ((bits >> b) & 1u) out.push_back(static_cast<ChannelId>(w * 64 + b + 1));
  }
  return out;
}

bool ClientState::push_telemetry(OutMessage m) {
  if (closed_) return false;
  if (telemetry_.size() >= telemetry_capacity_) {
    drop(telemetry_.front());
    telemetry_.pop_front();
  }
  telemetry_.push_back(std::move(m));
  const bool wake = !writing_;
  writing_ = true;
  return wake;
}

bool ClientState::offer(ChannelId channel, std::uint64_t timestamp_ns,
                        const std::shared_ptr<const std::string>& payload) {
  if (!subscribed(channel)) return false;
  std::lock_guard lock(m_);
  const auto it = sub_of_channel_.find(channel);
  if (it == sub_of_channel_.end()) return false;
  OutMessage m;
  m.binary = true;
  m.header = foxglove::message_data_header(it->second, timestamp_ns);
  m.header_size = m.header.size();
  m.body = payload;
  m.subscription_id = it->second;
  m.telemetry = true;
  return push_telemetry(std::move(m));
}

bool ClientState::offer_state(ChannelId channel, std::uint64_t timestamp_ns,
                              const std::shared_ptr<const std::string>& state) {
  if (!subscribed(channel)) return false;
  {
    std::lock_guard lock(m_);
    const auto it = sub_of_channel_.find(channel);
    if (it == sub_of_channel_.end()) return false;
    const std::uint32_t sub = it->second;
    std::erase_if(telemetry_, [&](const OutMessage& m) { return m.header_size && m.subscription_id == sub; });
  }
  return offer(channel, timestamp_ns, state);
}

bool ClientState::offer_binary(std::shared_ptr<const std::string> frame) {
  std::lock_guard lock(m_);
  OutMessage m;
  m.binary = true;
  m.body = std::move(frame);
  m.telemetry = true;
  return push_telemetry(std::move(m));
}

bool ClientState::push_control(std::string text) {
  std::lock_guard lock(m_);
  if (closed_) return false;
  if (control_.size() >= control_capacity_) {
    overflowed_.store(true, std::memory_order_relaxed);
    return false;
  }
  OutMessage m;
  m.body = std::make_shared<const std::string>(std::move(text));
  control_.push_back(std::move(m));
  const bool wake = !writing_;
  writing_ = true;
  return wake;
}

std::optional<OutMessage> ClientState::next() {
  std::lock_guard lock(m_);
  auto& q = !control_.empty() ? control_ : telemetry_;
  if (closed_ || q.empty()) {
    writing_ = false;
    return std::nullopt;
  }
  OutMessage m = std::move(q.front());
  q.pop_front();
  return m;
}

void ClientState::close() {
  std::lock_guard lock(m_);
  closed_ = true;
  telemetry_.clear();
  control_.clear();
}

std::size_t ClientState::depth() const {
  std::lock_guard lock(m_);
  return telemetry_.size() + control_.size();
}

}  // namespace fsd::web

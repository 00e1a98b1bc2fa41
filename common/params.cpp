#include "common/params.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "common/clock.hpp"
#include "common/logging.hpp"

namespace fsd {

ParamRegistry::ParamRegistry(const Config& config, const Clock* clock, std::size_t history)
    : schema_keepalive_(config.schema_ptr()), clock_(clock), history_max_(history) {
  for (const auto& e : config.schema().entries()) {
    if (!e.tunable) continue;
    if (e.type == ValueType::String) throw std::logic_error("parameter '" + e.key + "': strings cannot be tunable");
    const auto& v = config.value(e.key);
    auto& slot = slots_.emplace_back();
    slot.entry = &e;
    slot.value.store(v.is_boolean() ? (v.get<bool>() ? 1.0 : 0.0) : v.get<double>());
    by_key_.emplace(e.key, &slot);
  }
}

std::optional<double> ParamRegistry::get(const std::string& key) const {
  const auto it = by_key_.find(key);
  if (it == by_key_.end()) return std::nullopt;
  return it->second->value.load(std::memory_order_relaxed);
}

ParamRegistry::Result ParamRegistry::set(const std::string& key, double value, const std::string& who) {
  const auto it = by_key_.find(key);
  if (it == by_key_.end()) return {false, "unknown parameter '" + key + "'"};
  Slot& slot = *it->second;
  const ConfigEntry& e = *slot.entry;
  nlohmann::json candidate;
  if (e.type == ValueType::Boolean) {
    if (value != 0.0 && value != 1.0) return {false, "parameter '" + key + "': expected 0 or 1 (boolean)"};
    candidate = value != 0.0;
  } else if (e.type == ValueType::Integer) {
    if (!std::isfinite(value) || value != std::floor(value) || std::fabs(value) > 9.0e15)
      return {false, "parameter '" + key + "': expected an integer"};
    candidate = static_cast<long long>(value);
  } else {
    candidate = value;
  }
  if (auto why = e.check(candidate); !why.empty()) return {false, "parameter '" + key + "': " + why};

  ParamChange change;
  change.t = clock_ ? clock_->now() : 0.0;
  change.key = key;
  change.new_value = value;
  change.who = who;
  std::vector<Listener> listeners;
  {
    std::lock_guard lock(m_);  // serialises writers so old/new values in the history are consistent
    change.old_value = slot.value.exchange(value, std::memory_order_relaxed);
    history_.push_back(change);
    while (history_.size() > history_max_) history_.pop_front();
    listeners = listeners_;
  }
  logger("params")->info("{} changed {} from {} to {}", who, key, change.old_value, value);
  for (const auto& l : listeners) l(change);
  return {true, {}};
}

std::vector<ParamRegistry::Info> ParamRegistry::list() const {
  std::vector<Info> out;
  out.reserve(slots_.size());
  for (const auto& s : slots_) out.push_back({s.entry, s.value.load(std::memory_order_relaxed)});
  return out;
}

std::vector<ParamChange> ParamRegistry::history() const {
  std::lock_guard lock(m_);
  return {history_.begin(), history_.end()};
}

void ParamRegistry::subscribe(Listener l) {
  std::lock_guard lock(m_);
  listeners_.push_back(std::move(l));
}

}  // namespace fsd

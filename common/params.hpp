#pragma once
// The parameter registry: the tunable subset of the configuration, changeable while the car runs.
// Values live in atomics so that the control and perception threads read them without locks; a change is
// validated against the schema's type and bounds, applied atomically, logged with who made it, kept in a
// bounded history and announced to listeners (recorder, dashboard). Keys are fixed once the registry is built.
#include <atomic>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/config.hpp"
#include "common/time.hpp"

namespace fsd {

class Clock;

struct ParamChange {
  Stamp t = 0;
  std::string key;
  double old_value = 0, new_value = 0;
  std::string who;  // e.g. "web 192.168.1.20 (token ok)", "cli"
};

class ParamRegistry {
 public:
  struct Info {
    const ConfigEntry* entry;  // type, bounds, unit, doc, default
    double value;
  };
  struct Result {
    bool ok = false;
    std::string error;  // empty when ok
  };
  using Listener = std::function<void(const ParamChange&)>;

  // Declares every tunable key of the config's schema, with the config's current values.
  ParamRegistry(const Config& config, const Clock* clock = nullptr, std::size_t history = 256);

  std::optional<double> get(const std::string& key) const;
  // Validates and applies one change; on failure nothing changes and the error names the key and the problem.
  Result set(const std::string& key, double value, const std::string& who);
  std::vector<Info> list() const;
  std::vector<ParamChange> history() const;
  void subscribe(Listener l);

 private:
  struct Slot {
    const ConfigEntry* entry;
    std::atomic<double> value;
  };
  std::deque<Slot> slots_;  // stable addresses for by_key_
  std::unordered_map<std::string, Slot*> by_key_;
  std::shared_ptr<const ConfigSchema> schema_keepalive_;
  const Clock* clock_;
  std::size_t history_max_;
  mutable std::mutex m_;  // guards history_ and listeners_ (never taken by readers)
  std::deque<ParamChange> history_;
  std::vector<Listener> listeners_;
};

}  // namespace fsd

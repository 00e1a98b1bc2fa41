#pragma once
// Configuration: one JSON file whose every key is declared in a schema (type, bounds, unit, default, doc).
// Libraries declare their keys next to their plain Config structs with ConfigSection<S>, so a struct's defaults
// are the configuration's defaults; the daemon gathers all sections into one ConfigSchema. Loading merges a file
// over the defaults and rejects unknown keys, wrong types and out-of-range values with the key and the file.
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace fsd {

enum class ValueType { Number, Integer, Boolean, String };
const char* to_string(ValueType t);

struct ConfigEntry {
  std::string key;  // dotted path, e.g. "sim.vehicle.mass"
  ValueType type = ValueType::Number;
  std::shared_ptr<const nlohmann::json> default_value;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  std::vector<std::string> choices;  // for strings: allowed values, empty = any
  std::string unit;
  std::string doc;
  bool tunable = false;  // exposed in the parameter registry for live changes

  // Empty when `v` is acceptable, else a message naming the problem (without the key).
  std::string check(const nlohmann::json& v) const;
};

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ConfigSchema {
 public:
  void add(ConfigEntry e);  // throws std::logic_error on a duplicate or badly formed key
  const ConfigEntry* find(const std::string& key) const;
  const std::vector<ConfigEntry>& entries() const { return entries_; }
  nlohmann::json defaults() const;  // nested object with every key at its default
  std::string markdown() const;     // the reference table of docs/configuration.md

 private:
  std::vector<ConfigEntry> entries_;
};

class Config {
 public:
  explicit Config(std::shared_ptr<const ConfigSchema> schema);  // all defaults
  static Config load(std::shared_ptr<const ConfigSchema> schema, const std::filesystem::path& file);
  // Merges `overrides` (nested object) over the current values; `origin` names the source in errors.
  void merge(const nlohmann::json& overrides, const std::string& origin);
  // Sets one key (from the command line or a parameter change), validated like a file value.
  void set(const std::string& key, const nlohmann::json& value, const std::string& origin);

  double number(const std::string& key) const;
  long long integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  std::string string(const std::string& key) const;
  const nlohmann::json& value(const std::string& key) const;

  const ConfigSchema& schema() const { return *schema_; }
  std::shared_ptr<const ConfigSchema> schema_ptr() const { return schema_; }
  const nlohmann::json& as_json() const { return *values_; }
  std::string source() const { return source_; }

 private:
  const ConfigEntry& entry(const std::string& key, ValueType expected) const;
  std::shared_ptr<const ConfigSchema> schema_;
  std::shared_ptr<nlohmann::json> values_;
  std::string source_ = "defaults";
};

// Declares the keys of one plain struct S under a prefix and reads them back into an S. The struct's default
// member values are the configuration defaults.
template <class S>
class ConfigSection {
 public:
  explicit ConfigSection(std::string prefix, S defaults = S{}) : prefix_(std::move(prefix)), defaults_(defaults) {}

  ConfigSection& number(const std::string& name, double S::*m, double min, double max, std::string unit,
                        std::string doc, bool tunable = false);
  ConfigSection& integer(const std::string& name, int S::*m, int min, int max, std::string unit, std::string doc,
                         bool tunable = false);
  ConfigSection& boolean(const std::string& name, bool S::*m, std::string doc, bool tunable = false);
  ConfigSection& string(const std::string& name, std::string S::*m, std::vector<std::string> choices, std::string doc);

  void describe(ConfigSchema& schema) const {
    for (const auto& e : entries_) schema.add(e);
  }
  S read(const Config& cfg) const {
    S s = defaults_;
    for (const auto& r : readers_) r(cfg, s);
    return s;
  }
  // A live parameter change (ParamRegistry values are doubles; integers and booleans as numbers): sets the member
  // of `s` that the full dotted `key` names, through its member pointer. False when the key is not this section's
  // or not a number, integer or boolean.
  bool apply(const std::string& key, double value, S& s) const {
    for (const auto& [k, set] : setters_)
      if (k == key) {
        set(s, value);
        return true;
      }
    return false;
  }
  // The value of the member `key` names, as a parameter's number; nullopt when the key is not this section's.
  std::optional<double> value(const std::string& key, const S& s) const {
    for (const auto& [k, get] : getters_)
      if (k == key) return get(s);
    return std::nullopt;
  }
  const std::string& prefix() const { return prefix_; }

 private:
  std::string prefix_;
  S defaults_;
  std::vector<ConfigEntry> entries_;
  std::vector<std::function<void(const Config&, S&)>> readers_;
  std::vector<std::pair<std::string, std::function<void(S&, double)>>> setters_;
  std::vector<std::pair<std::string, std::function<double(const S&)>>> getters_;
  std::string key(const std::string& name) const { return prefix_.empty() ? name : prefix_ + "." + name; }
  ConfigEntry base(const std::string& name, ValueType t, std::string unit, std::string doc, bool tunable) const;
};

// Out-of-line helpers so that this header needs only json_fwd.
std::shared_ptr<const nlohmann::json> make_json_number(double v);
std::shared_ptr<const nlohmann::json> make_json_integer(long long v);
std::shared_ptr<const nlohmann::json> make_json_bool(bool v);
std::shared_ptr<const nlohmann::json> make_json_string(const std::string& v);

template <class S>
ConfigEntry ConfigSection<S>::base(const std::string& name, ValueType t, std::string unit, std::string doc,
                                   bool tunable) const {
  ConfigEntry e;
  e.key = key(name);
  e.type = t;
  e.unit = std::move(unit);
  e.doc = std::move(doc);
  e.tunable = tunable;
  return e;
}

template <class S>
ConfigSection<S>& ConfigSection<S>::number(const std::string& name, double S::*m, double min, double max,
                                           std::string unit, std::string doc, bool tunable) {
  ConfigEntry e = base(name, ValueType::Number, std::move(unit), std::move(doc), tunable);
  e.min = min;
  e.max = max;
  e.default_value = make_json_number(defaults_.*m);
  entries_.push_back(std::move(e));
  readers_.push_back([k = key(name), m](const Config& c, S& s) { s.*m = c.number(k); });
  setters_.emplace_back(key(name), [m](S& s, double v) { s.*m = v; });
  getters_.emplace_back(key(name), [m](const S& s) { return s.*m; });
  return *this;
}

template <class S>
ConfigSection<S>& ConfigSection<S>::integer(const std::string& name, int S::*m, int min, int max, std::string unit,
                                            std::string doc, bool tunable) {
  ConfigEntry e = base(name, ValueType::Integer, std::move(unit), std::move(doc), tunable);
  e.min = min;
  e.max = max;
  e.default_value = make_json_integer(defaults_.*m);
  entries_.push_back(std::move(e));
  readers_.push_back([k = key(name), m](const Config& c, S& s) { s.*m = static_cast<int>(c.integer(k)); });
  setters_.emplace_back(key(name), [m](S& s, double v) { s.*m = static_cast<int>(v); });
  getters_.emplace_back(key(name), [m](const S& s) { return static_cast<double>(s.*m); });
  return *this;
}

template <class S>
ConfigSection<S>& ConfigSection<S>::boolean(const std::string& name, bool S::*m, std::string doc, bool tunable) {
  ConfigEntry e = base(name, ValueType::Boolean, "", std::move(doc), tunable);
  e.default_value = make_json_bool(defaults_.*m);
  entries_.push_back(std::move(e));
  readers_.push_back([k = key(name), m](const Config& c, S& s) { s.*m = c.boolean(k); });
  setters_.emplace_back(key(name), [m](S& s, double v) { s.*m = v != 0.0; });
  getters_.emplace_back(key(name), [m](const S& s) { return s.*m ? 1.0 : 0.0; });
  return *this;
}

template <class S>
ConfigSection<S>& ConfigSection<S>::string(const std::string& name, std::string S::*m, std::vector<std::string> choices,
                                           std::string doc) {
  ConfigEntry e = base(name, ValueType::String, "", std::move(doc), false);
  e.choices = std::move(choices);
  e.default_value = make_json_string(defaults_.*m);
  entries_.push_back(std::move(e));
  readers_.push_back([k = key(name), m](const Config& c, S& s) { s.*m = c.string(k); });
  return *this;
}

}  // namespace fsd

#include "common/config.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

namespace fsd {

using nlohmann::json;

const char* to_string(ValueType t) {
  switch (t) {
    case ValueType::Number:
      return "number";
    case ValueType::Integer:
      return "integer";
    case ValueType::Boolean:
      return "boolean";
    case ValueType::String:
      return "string";
  }
  return "?";
}

std::shared_ptr<const json> make_json_number(double v) { return std::make_shared<const json>(v); }
std::shared_ptr<const json> make_json_integer(long long v) { return std::make_shared<const json>(v); }
std::shared_ptr<const json> make_json_bool(bool v) { return std::make_shared<const json>(v); }
std::shared_ptr<const json> make_json_string(const std::string& v) { return std::make_shared<const json>(v); }

namespace {
json::json_pointer pointer_of(const std::string& key) {
  std::string p = "/" + key;
  for (auto& ch : p)
    if (ch == '.') ch = '/';
  return json::json_pointer(p);
}

std::string fmt_num(double v) {
  std::ostringstream ss;
  ss << v;
  return ss.str();
}
}  // namespace

std::string ConfigEntry::check(const json& v) const {
  switch (type) {
    case ValueType::Number:
      if (!v.is_number()) return std::string("expected a number, got ") + v.type_name();
      break;
    case ValueType::Integer:
      if (!v.is_number_integer())
        return std::string("expected an integer, got ") + (v.is_number() ? v.dump() : v.type_name());
      break;
    case ValueType::Boolean:
      if (!v.is_boolean()) return std::string("expected true or false, got ") + v.type_name();
      return {};
    case ValueType::String: {
      if (!v.is_string()) return std::string("expected a string, got ") + v.type_name();
      if (choices.empty()) return {};
      const auto s = v.get<std::string>();
      for (const auto& c : choices)
        if (c == s) return {};
      std::string all;
      for (const auto& c : choices) all += (all.empty() ? "" : ", ") + c;
      return "'" + s + "' is not one of: " + all;
    }
  }
  const double d = v.get<double>();
  if (!std::isfinite(d)) return "not a finite number";
  if (d < min || d > max)
    return "value " + fmt_num(d) + " out of range [" + fmt_num(min) + ", " + fmt_num(max) + "]" +
           (unit.empty() ? "" : " " + unit);
  return {};
}

void ConfigSchema::add(ConfigEntry e) {
  if (e.key.empty() || e.key.front() == '.' || e.key.back() == '.' || !e.default_value)
    throw std::logic_error("config schema: malformed entry '" + e.key + "'");
  if (find(e.key)) throw std::logic_error("config schema: duplicate key '" + e.key + "'");
  // A key cannot also be a section: "a.b" and "a.b.c" would need "a.b" to be a value and an object at once.
  for (const auto& other : entries_)
    if (other.key.rfind(e.key + ".", 0) == 0 || e.key.rfind(other.key + ".", 0) == 0)
      throw std::logic_error("config schema: key '" + e.key + "' clashes with section of '" + other.key + "'");
  if (auto why = e.check(*e.default_value); !why.empty())
    throw std::logic_error("config schema: default of '" + e.key + "': " + why);
  entries_.push_back(std::move(e));
}

const ConfigEntry* ConfigSchema::find(const std::string& key) const {
  for (const auto& e : entries_)
    if (e.key == key) return &e;
  return nullptr;
}

json ConfigSchema::defaults() const {
  json root = json::object();
  for (const auto& e : entries_) root[pointer_of(e.key)] = *e.default_value;
  return root;
}

std::string ConfigSchema::markdown() const {
  std::ostringstream out;
  out << "| key | type | default | range / choices | unit | tunable | description |\n";
  out << "|---|---|---|---|---|---|---|\n";
  for (const auto& e : entries_) {
    std::string range;
    if (e.type == ValueType::String) {
      for (const auto& c : e.choices) range += (range.empty() ? "" : ", ") + ("`" + c + "`");
    } else if (e.type != ValueType::Boolean) {
      range = (std::isinf(e.min) ? std::string("−∞") : fmt_num(e.min)) + " … " +
              (std::isinf(e.max) ? std::string("∞") : fmt_num(e.max));
    }
    out << "| `" << e.key << "` | " << to_string(e.type) << " | `" << e.default_value->dump() << "` | " << range
        << " | " << e.unit << " | " << (e.tunable ? "yes" : "") << " | " << e.doc << " |\n";
  }
  return out.str();
}

Config::Config(std::shared_ptr<const ConfigSchema> schema)
    : schema_(std::move(schema)), values_(std::make_shared<json>(schema_->defaults())) {}

Config Config::load(std::shared_ptr<const ConfigSchema> schema, const std::filesystem::path& file) {
  std::ifstream f(file);
  if (!f) throw ConfigError(file.string() + ": cannot open configuration file");
  json j;
  try {
    j = json::parse(f, nullptr, true, /*ignore_comments=*/true);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number like 1e999
    throw ConfigError(file.string() + ": not valid JSON: " + e.what());
  }
  Config c(std::move(schema));
  c.merge(j, file.string());
  c.source_ = file.string();
  return c;
}

void Config::merge(const json& overrides, const std::string& origin) {
  if (!overrides.is_object()) throw ConfigError(origin + ": the configuration must be a JSON object");
  // Validate everything first so that a bad file changes nothing; every error is listed, not the first alone.
  std::vector<std::pair<std::string, const json*>> leaves;
  std::vector<std::string> errors;
  std::function<void(const json&, const std::string&)> walk = [&](const json& node, const std::string& prefix) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
      if (it.value().is_object()) {
        if (schema_->find(key)) {
          errors.push_back(origin + ": key '" + key + "': expected a " + to_string(schema_->find(key)->type) +
                           ", got object");
          continue;
        }
        bool any = false;
        for (const auto& e : schema_->entries())
          if (e.key.rfind(key + ".", 0) == 0) {
            any = true;
            break;
          }
        if (!any) {
          errors.push_back(origin + ": unknown key '" + key + "'");
          continue;
        }
        walk(it.value(), key);
        continue;
      }
      const ConfigEntry* e = schema_->find(key);
      if (!e) {
        errors.push_back(origin + ": unknown key '" + key + "'");
        continue;
      }
      if (auto why = e->check(it.value()); !why.empty()) {
        errors.push_back(origin + ": key '" + key + "': " + why);
        continue;
      }
      leaves.emplace_back(key, &it.value());
    }
  };
  walk(overrides, "");
  if (!errors.empty()) {
    std::string all = errors.front();
    for (std::size_t i = 1; i < errors.size(); ++i) all += "\n" + errors[i];
    throw ConfigError(all);
  }
  for (const auto& [key, v] : leaves) (*values_)[pointer_of(key)] = *v;
  source_ = origin;
}

void Config::set(const std::string& key, const json& value, const std::string& origin) {
  const ConfigEntry* e = schema_->find(key);
  if (!e) throw ConfigError(origin + ": unknown key '" + key + "'");
  if (auto why = e->check(value); !why.empty()) throw ConfigError(origin + ": key '" + key + "': " + why);
  (*values_)[pointer_of(key)] = value;
}

const ConfigEntry& Config::entry(const std::string& key, ValueType expected) const {
  const ConfigEntry* e = schema_->find(key);
  if (!e) throw std::logic_error("config: key '" + key + "' is not in the schema");
  if (e->type != expected && !(expected == ValueType::Number && e->type == ValueType::Integer))
    throw std::logic_error("config: key '" + key + "' is a " + to_string(e->type) + ", read as " + to_string(expected));
  return *e;
}

const json& Config::value(const std::string& key) const {
  if (!schema_->find(key)) throw std::logic_error("config: key '" + key + "' is not in the schema");
  return values_->at(pointer_of(key));
}

double Config::number(const std::string& key) const {
  entry(key, ValueType::Number);
  return value(key).get<double>();
}
long long Config::integer(const std::string& key) const {
  entry(key, ValueType::Integer);
  return value(key).get<long long>();
}
bool Config::boolean(const std::string& key) const {
  entry(key, ValueType::Boolean);
  return value(key).get<bool>();
}
std::string Config::string(const std::string& key) const {
  entry(key, ValueType::String);
  return value(key).get<std::string>();
}

}  // namespace fsd

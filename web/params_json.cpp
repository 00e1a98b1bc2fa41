#include "web/params_json.hpp"

#include <cmath>
#include <unordered_map>

namespace fsd::web {

using nlohmann::json;

namespace {

json bound(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::unordered_map<std::string, ParamRegistry::Info> by_key(const ParamRegistry& params) {
  std::unordered_map<std::string, ParamRegistry::Info> out;
  for (const auto& info : params.list()) out.emplace(info.entry->key, info);
  return out;
}

}  // namespace

json parameter_json(const ConfigEntry& entry, double value) {
  switch (entry.type) {
    case ValueType::Boolean:
      return {{"name", entry.key}, {"value", value != 0.0}};
    case ValueType::Integer:
      return {{"name", entry.key}, {"value", static_cast<long long>(value)}};
    default:
      return {{"name", entry.key}, {"value", value}, {"type", "float64"}};
  }
}

json parameters_json(const ParamRegistry& params, const std::vector<std::string>& names,
                     std::vector<std::string>* unknown) {
  json out = json::array();
  const auto list = params.list();
  if (names.empty()) {
    for (const auto& info : list) out.push_back(parameter_json(*info.entry, info.value));
    return out;
  }
  const auto keyed = by_key(params);
  for (const auto& n : names) {
    const auto it = keyed.find(n);
    if (it != keyed.end())
      out.push_back(parameter_json(*it->second.entry, it->second.value));
    else if (unknown)
      unknown->push_back(n);
  }
  return out;
}

json params_listing(const ParamRegistry& params) {
  json out = json::array();
  for (const auto& info : params.list()) {
    const ConfigEntry& e = *info.entry;
    json item = parameter_json(e, info.value);
    out.push_back({{"key", e.key},
                   {"type", to_string(e.type)},
                   {"unit", e.unit},
                   {"min", bound(e.min)},
                   {"max", bound(e.max)},
                   {"default", e.default_value ? *e.default_value : json(nullptr)},
                   {"value", item["value"]},
                   {"doc", e.doc}});
  }
  return out;
}

std::optional<double> parameter_from_json(const ConfigEntry& entry, const json& value, std::string& error) {
  json candidate;
  switch (entry.type) {
    case ValueType::Boolean:
      if (value.is_boolean())
        candidate = value;
      else if (value.is_number() && (value.get<double>() == 0.0 || value.get<double>() == 1.0))
        candidate = value.get<double>() != 0.0;
      break;
    case ValueType::Integer:
      // Foxglove sends whole numbers as float64 too; accept them when integral.
      if (value.is_number_integer())
        candidate = value;
      else if (value.is_number_float() && std::isfinite(value.get<double>()) &&
               value.get<double>() == std::floor(value.get<double>()) && std::fabs(value.get<double>()) < 9.0e15)
        candidate = static_cast<long long>(value.get<double>());
      break;
    case ValueType::Number:
      if (value.is_number()) candidate = value;
      break;
    case ValueType::String:
      break;
  }
  if (candidate.is_null()) {
    error = "parameter '" + entry.key + "': expected " +
            (entry.type == ValueType::Boolean   ? "a boolean"
             : entry.type == ValueType::Integer ? "an integer"
                                                : "a number") +
            ", got " +
            (value.is_null() ? std::string("nothing (parameters cannot be unset)")
                             : value.dump(-1, ' ', false, json::error_handler_t::replace));
    return std::nullopt;
  }
  if (auto why = entry.check(candidate); !why.empty()) {
    error = "parameter '" + entry.key + "': " + why;
    return std::nullopt;
  }
  return candidate.is_boolean() ? (candidate.get<bool>() ? 1.0 : 0.0) : candidate.get<double>();
}

ApplyResult apply_parameters(ParamRegistry& params, const std::vector<std::pair<std::string, json>>& changes,
                             const std::string& who) {
  ApplyResult r;
  const auto keyed = by_key(params);
  std::vector<std::pair<std::string, double>> checked;
  for (const auto& [key, value] : changes) {
    const auto it = keyed.find(key);
    if (it == keyed.end()) {
      r.errors.push_back("unknown parameter '" + key + "'");
      continue;
    }
    std::string error;
    if (const auto v = parameter_from_json(*it->second.entry, value, error))
      checked.emplace_back(key, *v);
    else
      r.errors.push_back(error);
  }
  if (!r.errors.empty()) return r;
  for (const auto& [key, v] : checked) {
    const auto res = params.set(key, v, who);
    if (res.ok)
      r.applied.push_back(key);
    else
      r.errors.push_back(res.error);
  }
  r.ok = r.errors.empty();
  return r;
}

}  // namespace fsd::web

#pragma once
// Parameters between the registry (doubles, typed by the config schema) and JSON: Foxglove parameterValues,
// the /api/params listing and validated, all-or-nothing changes.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/params.hpp"

namespace fsd::web {

// {name, value[, type]}: booleans and integers as such, numbers with type "float64" as the protocol asks.
nlohmann::json parameter_json(const ConfigEntry& entry, double value);

// parameterValues entries of `names` (all when empty); unknown names are appended to `unknown`.
nlohmann::json parameters_json(const ParamRegistry& params, const std::vector<std::string>& names,
                               std::vector<std::string>* unknown = nullptr);

// The /api/params listing: key, type, unit, min, max (null when unbounded), default, value, doc.
nlohmann::json params_listing(const ParamRegistry& params);

// The registry's double for a JSON value of `entry`'s type; nullopt with `error` set when it does not fit.
std::optional<double> parameter_from_json(const ConfigEntry& entry, const nlohmann::json& value, std::string& error);

struct ApplyResult {
  bool ok = false;
  std::vector<std::string> errors;   // each names the key and the problem
  std::vector<std::string> applied;  // keys changed, in order
};
// Checks every change first (known key, type, bounds); applies them only when all pass.
ApplyResult apply_parameters(ParamRegistry& params, const std::vector<std::pair<std::string, nlohmann::json>>& changes,
                             const std::string& who);

}  // namespace fsd::web

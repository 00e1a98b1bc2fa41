#pragma once
// Request targets: percent-decoding and the query string. Decoding is strict so that a malformed or sneaky
// encoding (%2e%2e, %00, a lone %) is refused instead of guessed at.
#include <optional>
#include <string>
#include <string_view>

namespace fsd::web {

// Decodes %XX escapes (and '+' as space when `plus_is_space`, for query values). nullopt on a malformed escape
// or a decoded NUL byte.
std::optional<std::string> percent_decode(std::string_view s, bool plus_is_space = false);

struct Target {
  std::string_view path;   // before '?', still encoded
  std::string_view query;  // after '?', without it
};
Target split_target(std::string_view target);

// The path with each run of '/' made one: "//api/state" (what a base URL ending in '/' plus "/api/state" gives)
// is "/api/state".
std::string collapse_slashes(std::string_view path);

// The decoded value of `name` in a query string "a=1&b=2"; nullopt when absent or malformed.
std::optional<std::string> query_param(std::string_view query, std::string_view name);

}  // namespace fsd::web

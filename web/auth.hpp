#pragma once
// Who may do what over the web (DESIGN.md §7): reading is open on the configured network; changing a parameter
// needs the bearer token. Browsers are held to their origin so that a page elsewhere cannot drive the dashboard.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fsd::web {

// True when `given` equals `expected` and `expected` is not empty (an empty token disables tuning). The time
// taken depends on the length of `expected` only, not on where the first difference is.
bool token_matches(std::string_view given, std::string_view expected);

// The token of an "Authorization: Bearer <token>" header value; nullopt for another scheme or an empty token.
std::optional<std::string> bearer_token(std::string_view authorization);

// "a, b ,c" → {"a","b","c"}; empty entries dropped.
std::vector<std::string> split_list(std::string_view comma_separated);

// Whether a request carrying `origin` (the Origin header, empty when absent) may proceed. Requests without an
// Origin come from programs, not from a page, and pass. With `allowed` empty only the server's own host (the
// Host header) passes; "*" in `allowed` lets any origin in. Scheme and host compare case-insensitively and a
// missing port means the scheme's default.
bool origin_allowed(std::string_view origin, std::string_view host, const std::vector<std::string>& allowed);

}  // namespace fsd::web

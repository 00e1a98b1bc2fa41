#include "web/auth.hpp"

#include <algorithm>
#include <cctype>

namespace fsd::web {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// "host:port" with the default port of `scheme` added when missing; IPv6 literals keep their brackets.
std::string with_port(std::string_view authority, std::string_view scheme) {
  std::string a = lower(authority);
  const auto bracket = a.rfind(']');
  const auto colon = a.rfind(':');
  const bool has_port = colon != std::string::npos && (bracket == std::string::npos || colon > bracket);
  if (!has_port) a += (scheme == "https" || scheme == "wss") ? ":443" : ":80";
  return a;
}

struct Origin {
  std::string scheme, authority;  // authority with port
};

std::optional<Origin> parse_origin(std::string_view origin) {
  const auto sep = origin.find("://");
  if (sep == std::string_view::npos || sep == 0) return std::nullopt;
  const std::string scheme = lower(origin.substr(0, sep));
  std::string_view rest = origin.substr(sep + 3);
  if (!rest.empty() && rest.back() == '/') rest.remove_suffix(1);
  if (rest.empty() || rest.find('/') != std::string_view::npos) return std::nullopt;
  return Origin{scheme, with_port(rest, scheme)};
}

}  // namespace

bool token_matches(std::string_view given, std::string_view expected) {
  if (expected.empty()) return false;
  // Accumulate differences over every byte of `expected`, so the loop length never depends on `given`.
  volatile unsigned char diff = given.size() == expected.size() ? 0 : 1;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const unsigned char g = i < given.size() ? static_cast<unsigned char>(given[i]) : 0;
    diff = diff | static_cast<unsigned char>(g ^ static_cast<unsigned char>(expected[i]));
  }
  return diff == 0;
}

std::optional<std::string> bearer_token(std::string_view authorization) {
  authorization = trim(authorization);
  constexpr std::string_view scheme = "bearer ";
  if (authorization.size() <= scheme.size() || lower(authorization.substr(0, scheme.size())) != scheme)
    return std::nullopt;
  const auto token = trim(authorization.substr(scheme.size()));
  if (token.empty()) return std::nullopt;
  return std::string(token);
}

std::vector<std::string> split_list(std::string_view s) {
  std::vector<std::string> out;
  while (!s.empty()) {
    const auto comma = s.find(',');
    const auto item = trim(s.substr(0, comma));
    if (!item.empty()) out.emplace_back(item);
    if (comma == std::string_view::npos) break;
    s.remove_prefix(comma + 1);
  }
  return out;
}

bool origin_allowed(std::string_view origin, std::string_view host, const std::vector<std::string>& allowed) {
  origin = trim(origin);
  if (origin.empty()) return true;
  const auto o = parse_origin(origin);
  if (!o) return false;  // includes the literal "null" of sandboxed pages and file:// documents
  if (allowed.empty()) {
    const auto h = trim(host);
    return !h.empty() && o->authority == with_port(h, o->scheme);
  }
  for (const auto& a : allowed) {
    if (a == "*") return true;
    const auto p = parse_origin(a);
    if (p && p->scheme == o->scheme && p->authority == o->authority) return true;
  }
  return false;
}

}  // namespace fsd::web

#include "web/http_api.hpp"

#include <fstream>
#include <sstream>

#include "common/logging.hpp"
#include "web/auth.hpp"
#include "web/json_text.hpp"
#include "web/params_json.hpp"
#include "web/url.hpp"

namespace fsd::web {

using nlohmann::json;

namespace {

constexpr const char* kCsp =
    "default-src 'self'; script-src 'self'; style-src 'self' 'unsafe-inline'; img-src 'self' data: blob:; "
    "connect-src 'self' ws: wss:; font-src 'self'; object-src 'none'; frame-ancestors 'none'; base-uri 'self'";

const char* kNotBuilt =
    "<!doctype html><meta charset=utf-8><title>fsd dashboard</title>"
    "<h1>The dashboard is not built</h1><p>Build it with <code>cmake --build build --target dashboard</code> "
    "(needs <code>npm ci</code> in web/dashboard; <code>deploy/install-deps.sh</code> does it). The API answers: "
    "<a href=/api/state>/api/state</a>, <a href=/api/params>/api/params</a>, <a href=/healthz>/healthz</a>, "
    "<a href=/metrics>/metrics</a>; Foxglove Studio can connect to this port.</p>";

HttpResponse method_not_allowed(const HttpRequest& req, const char* allow) {
  auto res = json_response(req, http::status::method_not_allowed, {{"error", "method not allowed"}});
  res.set(http::field::allow, allow);
  return res;
}

}  // namespace

HttpResponse make_response(const HttpRequest& req, http::status status, const std::string& content_type,
                           std::string body) {
  HttpResponse res{status, req.version()};
  res.set(http::field::server, "fsd");
  res.set(http::field::content_type, content_type);
  res.set(http::field::cache_control, "no-cache");
  res.set("X-Content-Type-Options", "nosniff");
  res.set("X-Frame-Options", "DENY");
  res.set("Referrer-Policy", "no-referrer");
  res.set("Content-Security-Policy", kCsp);
  res.keep_alive(req.keep_alive());
  if (req.method() == http::verb::head) {
    res.content_length(body.size());
  } else {
    res.body() = std::move(body);
    res.prepare_payload();
  }
  return res;
}

HttpResponse json_response(const HttpRequest& req, http::status status, const json& body) {
  return make_response(req, status, "application/json",
                       body.dump(-1, ' ', false, json::error_handler_t::replace) + "\n");
}

HttpApi::HttpApi(Hub& hub, StaticFiles files, std::vector<std::string> allowed_origins)
    : hub_(hub), files_(std::move(files)), allowed_origins_(std::move(allowed_origins)) {}

void HttpApi::set_state_provider(std::function<json()> provider) {
  std::lock_guard lock(provider_m_);
  provider_ = std::move(provider);
}

HttpResponse HttpApi::handle(const HttpRequest& req, const std::string& peer) {
  auto res = route(req, peer);
  const auto code = std::to_string(res.result_int() / 100) + "xx";
  hub_.metrics()
      .counter("fsd_web_http_requests_total", "HTTP requests answered, by status class", {{"code", code}})
      .inc();
  return res;
}

HttpResponse HttpApi::route(const HttpRequest& req, const std::string& peer) {
  const auto target = split_target(std::string_view(req.target().data(), req.target().size()));
  const std::string path = collapse_slashes(target.path);
  const auto method = req.method();
  const bool get = method == http::verb::get || method == http::verb::head;

  if (path == "/healthz")
    return get ? make_response(req, http::status::ok, "text/plain; charset=utf-8", "ok\n")
               : method_not_allowed(req, "GET, HEAD");
  if (path == "/metrics")
    return get ? make_response(req, http::status::ok, "text/plain; version=0.0.4; charset=utf-8",
                               hub_.metrics().render())
               : method_not_allowed(req, "GET, HEAD");
  if (path == "/api/state") return get ? api_state(req) : method_not_allowed(req, "GET, HEAD");
  if (path == "/api/params") {
    if (get)
      return json_response(req, http::status::ok,
                           {{"tuning_enabled", hub_.tuning_enabled()}, {"params", params_listing(hub_.params())}});
    if (method == http::verb::put) return api_params_put(req, peer);
    return method_not_allowed(req, "GET, HEAD, PUT");
  }
  if (path == "/api/params/history") {
    if (!get) return method_not_allowed(req, "GET, HEAD");
    json out = json::array();
    for (const auto& c : hub_.params().history())
      out.push_back({{"t", c.t}, {"key", c.key}, {"old", c.old_value}, {"new", c.new_value}, {"who", c.who}});
    return json_response(req, http::status::ok, out);
  }
  if (path.rfind("/api/", 0) == 0) return json_response(req, http::status::not_found, {{"error", "no such endpoint"}});
  if (!get) return method_not_allowed(req, "GET, HEAD");
  return static_file(req, path);
}

HttpResponse HttpApi::api_state(const HttpRequest& req) {
  std::function<json()> provider;
  {
    std::lock_guard lock(provider_m_);
    provider = provider_;
  }
  if (!provider) return json_response(req, http::status::ok, json::object());
  try {
    return json_response(req, http::status::ok, provider());
  } catch (const std::exception& e) {
    logger("web")->error("/api/state provider failed: {}", e.what());
    return json_response(req, http::status::internal_server_error, {{"error", "state unavailable"}});
  }
}

HttpResponse HttpApi::api_params_put(const HttpRequest& req, const std::string& peer) {
  // A page elsewhere must not be able to use a browser that holds the token.
  const auto origin = req[http::field::origin];
  if (!origin_allowed({origin.data(), origin.size()}, {req[http::field::host].data(), req[http::field::host].size()},
                      allowed_origins_))
    return json_response(req, http::status::forbidden, {{"error", "origin not allowed"}});
  if (!hub_.tuning_enabled()) {
    hub_.note_param_refusal();
    return json_response(req, http::status::forbidden,
                         {{"error", "parameter tuning is disabled on this car (no web token configured)"}});
  }
  const auto auth = req[http::field::authorization];
  const auto token = bearer_token({auth.data(), auth.size()});
  if (!token || !hub_.authorised(*token)) {
    hub_.note_param_refusal();
    logger("web")->warn("{} tried PUT /api/params without a valid token", peer);
    auto res = json_response(req, http::status::unauthorized, {{"error", "a valid bearer token is required"}});
    res.set(http::field::www_authenticate, "Bearer realm=\"fsd\"");
    return res;
  }
  const auto body = parse_json_text(req.body());
  if (body.number_out_of_range)
    return json_response(req, http::status::unprocessable_entity,
                         {{"error", "nothing changed"}, {"errors", json::array({body.error})}});
  if (!body.value.is_object() || body.value.empty())
    return json_response(req, http::status::bad_request,
                         {{"error", "the body must be a JSON object {\"key\": value, ...}"}});
  std::vector<std::pair<std::string, json>> changes;
  for (auto it = body.value.begin(); it != body.value.end(); ++it) changes.emplace_back(it.key(), it.value());
  const auto result = apply_parameters(hub_.params(), changes, "web " + peer + " (token ok)");
  if (!result.ok) {
    hub_.note_param_refusal();
    return json_response(req, http::status::unprocessable_entity,
                         {{"error", "nothing changed"}, {"errors", result.errors}});
  }
  hub_.note_param_changes(result.applied.size());
  return json_response(req, http::status::ok, {{"applied", result.applied}});
}

HttpResponse HttpApi::static_file(const HttpRequest& req, std::string_view path) {
  if (!files_.available()) {
    if (path == "/" || path == "/index.html")
      return make_response(req, http::status::service_unavailable, "text/html; charset=utf-8", kNotBuilt);
    return make_response(req, http::status::not_found, "text/plain; charset=utf-8", "not found\n");
  }
  const auto r = files_.resolve(path);
  switch (r.status) {
    case StaticFiles::Status::BadRequest:
      return make_response(req, http::status::bad_request, "text/plain; charset=utf-8", "bad request\n");
    case StaticFiles::Status::Forbidden:
      return make_response(req, http::status::forbidden, "text/plain; charset=utf-8", "forbidden\n");
    case StaticFiles::Status::NotFound:
      return make_response(req, http::status::not_found, "text/plain; charset=utf-8", "not found\n");
    case StaticFiles::Status::Ok:
      break;
  }
  std::ifstream f(r.file, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  if (!f) return make_response(req, http::status::not_found, "text/plain; charset=utf-8", "not found\n");
  auto res = make_response(req, http::status::ok, r.content_type, ss.str());
  if (r.immutable) res.set(http::field::cache_control, "public, max-age=31536000, immutable");
  return res;
}

}  // namespace fsd::web

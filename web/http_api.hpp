#pragma once
// The HTTP side of the server: the dashboard's files, /api/state, /api/params (GET open, PUT with the bearer
// token), /api/params/history, /healthz and /metrics. A pure request → response function, so the rules are
// tested without sockets.
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <boost/beast/http.hpp>
#include <nlohmann/json.hpp>

#include "web/hub.hpp"
#include "web/static_files.hpp"

namespace fsd::web {

namespace http = boost::beast::http;
using HttpRequest = http::request<http::string_body>;
using HttpResponse = http::response<http::string_body>;

class HttpApi {
 public:
  HttpApi(Hub& hub, StaticFiles files, std::vector<std::string> allowed_origins);
  // `peer` is the client's "ip:port", for the log and the attribution of parameter changes.
  HttpResponse handle(const HttpRequest& req, const std::string& peer);
  // The body of /api/state. Called on a web I/O thread: it must be thread-safe.
  void set_state_provider(std::function<nlohmann::json()> provider);

 private:
  HttpResponse route(const HttpRequest& req, const std::string& peer);
  HttpResponse api_state(const HttpRequest& req);
  HttpResponse api_params_put(const HttpRequest& req, const std::string& peer);
  HttpResponse static_file(const HttpRequest& req, std::string_view path);

  Hub& hub_;
  const StaticFiles files_;
  const std::vector<std::string> allowed_origins_;
  std::mutex provider_m_;
  std::function<nlohmann::json()> provider_;
};

// A response with the security headers every answer carries; HEAD gets the headers only.
HttpResponse make_response(const HttpRequest& req, http::status status, const std::string& content_type,
                           std::string body);
HttpResponse json_response(const HttpRequest& req, http::status status, const nlohmann::json& body);

}  // namespace fsd::web

// libFuzzer target for the HTTP API's request handling (web/http_api, url, static_files, params_json).
// Byte 0 picks the mode:
//   odd:  the rest is the bytes of a request as a client sends it, parsed by Beast's request parser with the
//         server's header and body limits, then answered by HttpApi::handle.
//   even: a request built from the rest, so that the deeper paths are reached without a matching
//         Content-Length: the first line is the target (path and query), what follows the body; bits 1-3 of
//         byte 0 pick the method, bit 4 adds the bearer token, bit 5 a foreign Origin.
// Invariants beyond "no crash": a 200 for a file is one of the web root's files (nothing outside it is
// served); a parameter changes only with the token and stays within its bounds.
#include <unistd.h>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <boost/beast/http.hpp>

#include "tests/fuzz/web_fixture.hpp"
#include "web/http_api.hpp"

namespace {

namespace fs = std::filesystem;
namespace http = boost::beast::http;
using fsd::web::HttpApi;
using fsd::web::HttpRequest;
using fsd::web::fuzz::WebFixture;

constexpr std::size_t kMaxBody = 4096;
const std::string kIndex = "<!doctype html><title>dash</title>", kAsset = "console.log(1)", kSecret = "TOP SECRET";

// web/index.html, web/assets/app-1234.js; secret.txt beside the root and a symlink to it inside.
fs::path make_web_root() {
  const fs::path base = fs::temp_directory_path() / ("fsd-http-fuzz-" + std::to_string(::getpid()));
  fs::create_directories(base / "web" / "assets");
  std::ofstream(base / "web" / "index.html") << kIndex;
  std::ofstream(base / "web" / "assets" / "app-1234.js") << kAsset;
  std::ofstream(base / "secret.txt") << kSecret;
  std::error_code ec;
  fs::create_symlink(base / "secret.txt", base / "web" / "link.txt", ec);
  return base / "web";
}

struct Fixture {
  WebFixture web;
  HttpApi api{*web.hub, fsd::web::StaticFiles(make_web_root()), {}};
  Fixture() {
    api.set_state_provider([] { return nlohmann::json{{"as_state", "Driving"}, {"lap", 1}}; });
  }
};

const http::verb kMethods[] = {http::verb::get,     http::verb::head,    http::verb::put,   http::verb::post,
                               http::verb::delete_, http::verb::options, http::verb::patch, http::verb::get};

bool parse_raw(std::string_view bytes, HttpRequest& req) {
  http::request_parser<http::string_body> parser;
  parser.header_limit(8192);
  parser.body_limit(kMaxBody);
  parser.eager(true);
  boost::beast::error_code ec;
  parser.put(boost::asio::buffer(bytes.data(), bytes.size()), ec);
  if (ec || !parser.is_done()) return false;
  req = parser.release();
  return true;
}

HttpRequest build(std::uint8_t mode, std::string_view rest) {
  const auto nl = rest.find('\n');
  HttpRequest req;
  req.method(kMethods[(mode >> 1) & 7]);
  req.target(std::string(rest.substr(0, nl)));
  req.version(11);
  req.set(http::field::host, "car:8080");
  if (mode & 16) req.set(http::field::authorization, std::string("Bearer ") + fsd::web::fuzz::kToken);
  if (mode & 32) req.set(http::field::origin, "http://evil.example");
  if (nl != std::string_view::npos) req.body() = std::string(rest.substr(nl + 1));
  req.prepare_payload();
  return req;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Fixture f;
  if (size < 1) return 0;
  const std::uint8_t mode = data[0];
  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  HttpRequest req;
  if (mode & 1) {
    if (!parse_raw(rest, req)) return 0;
  } else {
    req = build(mode, rest);
  }
  const std::size_t before = f.web.changes;
  const auto res = f.api.handle(req, "127.0.0.1:9");
  const std::string_view target(req.target().data(), req.target().size());
  const bool api = target.find("/api/") != std::string_view::npos || target.find("healthz") != std::string_view::npos ||
                   target.find("metrics") != std::string_view::npos;
  if (res.result() == http::status::ok && !api && req.method() == http::verb::get && res.body() != kIndex &&
      res.body() != kAsset)
    std::abort();  // a file from outside the web root (or something that is no file) was served
  // The file beside the root never leaks (an answer may echo what the input itself said, e.g. an unknown key).
  if (res.body().find(kSecret) != std::string::npos && rest.find(kSecret) == std::string_view::npos) std::abort();
  const auto auth = req[http::field::authorization];
  const bool token = std::string_view(auth.data(), auth.size()).find(fsd::web::fuzz::kToken) != std::string_view::npos;
  f.web.check(before, token);
  return 0;
}

// The HTTP side end to end: static files and path escapes, /api/params with and without the token, /api/state,
// /healthz and /metrics.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "tests/scratch_dir.hpp"
#include "tests/web/test_client.hpp"

namespace fsd::web::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// web_root/index.html, web_root/assets/app.js, web_root/link → ../secret.txt (outside the root).
struct WebRoot {
  WebRoot() {
    base = fsd::test::scratch_path("web");
    fs::remove_all(base);
    fs::create_directories(base / "root" / "assets");
    write(base / "root" / "index.html", "<!doctype html><title>dash</title>");
    write(base / "root" / "assets" / "app-1234.js", "console.log(1)");
    write(base / "secret.txt", "TOP SECRET");
    fs::create_symlink(base / "secret.txt", base / "root" / "link.txt");
  }
  ~WebRoot() { fs::remove_all(base); }
  static void write(const fs::path& p, const std::string& s) { std::ofstream(p) << s; }
  fs::path base;
};

TEST(Http, ServesStaticFilesWithContentTypes) {
  WebRoot root;
  auto cfg = TestServer::base_config();
  cfg.web_root = (root.base / "root").string();
  TestServer s(cfg);
  auto r = http_request(s.port(), http::verb::get, "/");
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(r.body, "<!doctype html><title>dash</title>");
  EXPECT_EQ(r.headers["content-type"], "text/html; charset=utf-8");
  EXPECT_NE(r.headers["content-security-policy"].find("default-src 'self'"), std::string::npos);

  r = http_request(s.port(), http::verb::get, "/assets/app-1234.js?v=2");
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(r.body, "console.log(1)");
  EXPECT_EQ(r.headers["content-type"], "text/javascript; charset=utf-8");
  EXPECT_NE(r.headers["cache-control"].find("immutable"), std::string::npos);

  r = http_request(s.port(), http::verb::head, "/index.html");
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(r.headers["content-length"], "34");

  EXPECT_EQ(http_request(s.port(), http::verb::get, "/missing.js").status, 404u);
  EXPECT_EQ(http_request(s.port(), http::verb::post, "/index.html").status, 405u);
}

TEST(Http, NoPathLeavesTheWebRoot) {
  WebRoot root;
  auto cfg = TestServer::base_config();
  cfg.web_root = (root.base / "root").string();
  TestServer s(cfg);
  for (const char* target :
       {"/../secret.txt", "/assets/../../secret.txt", "/%2e%2e/secret.txt", "/assets/..%2f..%2fsecret.txt",
        "/%2E%2E%2Fsecret.txt", "//etc/passwd", "/link.txt", "/..\\secret.txt", "/%00index.html", "/%zz", "/."}) {
    auto r = http_request(s.port(), http::verb::get, target);
    // 0: Beast's parser refused the target outright.
    EXPECT_TRUE(r.status == 0u || r.status == 400u || r.status == 403u || r.status == 404u)
        << target << " → " << r.status;
    EXPECT_EQ(r.body.find("TOP SECRET"), std::string::npos) << target;
  }
}

TEST(Http, MissingDashboardBuildSaysHowToBuildIt) {
  TestServer s;  // web_root does not exist
  auto r = http_request(s.port(), http::verb::get, "/");
  EXPECT_EQ(r.status, 503u);
  EXPECT_NE(r.body.find("not built"), std::string::npos);
}

TEST(Http, ParamsListingCarriesTypesUnitsAndBounds) {
  TestServer s;
  auto r = http_request(s.port(), http::verb::get, "/api/params");
  ASSERT_EQ(r.status, 200u);
  EXPECT_EQ(r.headers["content-type"], "application/json");
  const auto j = json::parse(r.body);
  EXPECT_EQ(j["tuning_enabled"], true);
  std::map<std::string, json> by_key;
  for (const auto& p : j["params"]) by_key[p["key"]] = p;
  ASSERT_EQ(by_key.size(), 3u);
  const auto& speed = by_key["control.target_speed"];
  EXPECT_EQ(speed["type"], "number");
  EXPECT_EQ(speed["unit"], "m/s");
  EXPECT_DOUBLE_EQ(speed["min"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(speed["max"].get<double>(), 20.0);
  EXPECT_DOUBLE_EQ(speed["value"].get<double>(), 5.0);
  EXPECT_EQ(speed["doc"], "Target speed");
  EXPECT_EQ(by_key["control.use_gnss"]["type"], "boolean");
  EXPECT_EQ(by_key["control.use_gnss"]["value"], true);
}

TEST(Http, ParamsPutNeedsTheBearerToken) {
  TestServer s;
  const std::string body = R"({"control.target_speed": 6.5})";
  auto r = http_request(s.port(), http::verb::put, "/api/params", body);
  EXPECT_EQ(r.status, 401u);
  EXPECT_EQ(r.headers["www-authenticate"].rfind("Bearer", 0), 0u);
  r = http_request(s.port(), http::verb::put, "/api/params", body, {{"Authorization", "Bearer s3cret-tokeN"}});
  EXPECT_EQ(r.status, 401u);
  r = http_request(s.port(), http::verb::put, "/api/params", body, {{"Authorization", "Basic czNjcmV0LXRva2Vu"}});
  EXPECT_EQ(r.status, 401u);
  EXPECT_DOUBLE_EQ(*s.params.get("control.target_speed"), 5.0);

  r = http_request(s.port(), http::verb::put, "/api/params", body,
                   {{"Authorization", std::string("Bearer ") + kToken}});
  ASSERT_EQ(r.status, 200u) << r.body;
  EXPECT_EQ(json::parse(r.body)["applied"], json::array({"control.target_speed"}));
  EXPECT_DOUBLE_EQ(*s.params.get("control.target_speed"), 6.5);
  ASSERT_EQ(s.params.history().size(), 1u);
  EXPECT_NE(s.params.history()[0].who.find("127.0.0.1"), std::string::npos);

  const auto hist = json::parse(http_request(s.port(), http::verb::get, "/api/params/history").body);
  ASSERT_EQ(hist.size(), 1u);
  EXPECT_DOUBLE_EQ(hist[0]["old"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(hist[0]["new"].get<double>(), 6.5);
}

TEST(Http, ParamsPutIsBoundedAndAllOrNothing) {
  TestServer s;
  const std::vector<std::pair<std::string, std::string>> auth{{"Authorization", std::string("Bearer ") + kToken}};
  auto r = http_request(s.port(), http::verb::put, "/api/params",
                        R"({"control.target_speed": 7, "control.lookahead_points": 99})", auth);
  EXPECT_EQ(r.status, 422u);
  EXPECT_NE(r.body.find("control.lookahead_points"), std::string::npos);
  EXPECT_DOUBLE_EQ(*s.params.get("control.target_speed"), 5.0);
  r = http_request(s.port(), http::verb::put, "/api/params", R"({"run.mission": 1})", auth);  // not a parameter
  EXPECT_EQ(r.status, 422u);
  r = http_request(s.port(), http::verb::put, "/api/params", "[1,2", auth);
  EXPECT_EQ(r.status, 400u);
  r = http_request(s.port(), http::verb::put, "/api/params", R"({"control.target_speed": 7})",
                   {{"Authorization", std::string("Bearer ") + kToken}, {"Origin", "http://evil.example"}});
  EXPECT_EQ(r.status, 403u);
  EXPECT_TRUE(s.params.history().empty());
}

TEST(Http, ParamsPutOfAnOverflowingNumberSaysItIsOutOfRange) {
  TestServer s;
  const std::vector<std::pair<std::string, std::string>> auth{{"Authorization", std::string("Bearer ") + kToken}};
  for (const char* number : {"1e999", "-1e999"}) {
    const auto r = http_request(s.port(), http::verb::put, "/api/params",
                                std::string(R"({"control.target_speed": )") + number + "}", auth);
    EXPECT_EQ(r.status, 422u) << r.body;
    const auto body = json::parse(r.body);
    ASSERT_EQ(body["errors"].size(), 1u) << r.body;
    const auto error = body["errors"][0].get<std::string>();
    EXPECT_NE(error.find(number), std::string::npos) << error;
    EXPECT_NE(error.find("out of range"), std::string::npos) << error;
    EXPECT_EQ(error.find("JSON object"), std::string::npos) << error;
  }
  EXPECT_DOUBLE_EQ(*s.params.get("control.target_speed"), 5.0);
  EXPECT_TRUE(s.params.history().empty());
}

TEST(Http, RepeatedSlashesInThePathAreOne) {
  TestServer s;
  s.server->set_state_provider([] { return json{{"as_state", "Ready"}}; });
  for (const char* target : {"//api/state", "///api//state", "/api/state/"}) {
    const auto r = http_request(s.port(), http::verb::get, target);
    if (std::string(target) == "/api/state/") {
      EXPECT_EQ(r.status, 404u) << target;  // a trailing slash is another path
      continue;
    }
    EXPECT_EQ(r.status, 200u) << target;
    EXPECT_EQ(json::parse(r.body), (json{{"as_state", "Ready"}})) << target;
  }
  EXPECT_EQ(http_request(s.port(), http::verb::get, "//healthz").body, "ok\n");
}

TEST(Http, ParamsPutRefusedWhenTuningIsDisabled) {
  auto cfg = TestServer::base_config();
  cfg.token = "";
  TestServer s(cfg);
  auto r = http_request(s.port(), http::verb::put, "/api/params", R"({"control.target_speed": 7})",
                        {{"Authorization", "Bearer "}});
  EXPECT_EQ(r.status, 403u);
  EXPECT_DOUBLE_EQ(*s.params.get("control.target_speed"), 5.0);
}

TEST(Http, OversizeBodyIsRefused) {
  auto cfg = TestServer::base_config();
  cfg.max_frame_bytes = 1024;
  TestServer s(cfg);
  auto r = http_request(s.port(), http::verb::put, "/api/params", std::string(4096, ' '),
                        {{"Authorization", std::string("Bearer ") + kToken}});
  EXPECT_EQ(r.status, 413u);
}

TEST(Http, StateComesFromTheProvider) {
  TestServer s;
  EXPECT_EQ(json::parse(http_request(s.port(), http::verb::get, "/api/state").body), json::object());
  s.server->set_state_provider([] { return json{{"as_state", "Driving"}, {"lap", 1}}; });
  auto r = http_request(s.port(), http::verb::get, "/api/state");
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(json::parse(r.body), (json{{"as_state", "Driving"}, {"lap", 1}}));
  EXPECT_EQ(http_request(s.port(), http::verb::get, "/api/nothing").status, 404u);
}

TEST(Http, HealthzAndMetrics) {
  TestServer s;
  auto r = http_request(s.port(), http::verb::get, "/healthz");
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(r.body, "ok\n");

  auto& lat = s.server->metrics().summary("fsd_stage_latency_seconds", "Latency per stage", {{"stage", "control"}});
  for (int i = 1; i <= 100; ++i) lat.observe(i * 1e-3);
  s.server->metrics().gauge("fsd_as_state", "AS state (0 Off … 4 Finished)").set(2);
  r = http_request(s.port(), http::verb::get, "/metrics");
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(r.headers["content-type"].rfind("text/plain; version=0.0.4", 0), 0u);
  // Every line is a comment (# HELP / # TYPE) or a sample "name{labels} value".
  const std::regex comment(R"(^# (HELP|TYPE) [a-zA-Z_:][a-zA-Z0-9_:]* .*$)");
  const std::regex sample(R"(^[a-zA-Z_:][a-zA-Z0-9_:]*(\{([a-zA-Z_][a-zA-Z0-9_]*="[^"]*",?)*\})? [-+0-9.eEInfNa]+$)");
  std::istringstream lines(r.body);
  int samples = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty()) continue;
    EXPECT_TRUE(std::regex_match(line, comment) || std::regex_match(line, sample)) << line;
    samples += line[0] != '#';
  }
  EXPECT_GT(samples, 5);
  EXPECT_NE(r.body.find("# TYPE fsd_stage_latency_seconds summary\n"), std::string::npos);
  EXPECT_NE(r.body.find("fsd_stage_latency_seconds{stage=\"control\",quantile=\"0.99\"} 0.099\n"), std::string::npos);
  EXPECT_NE(r.body.find("fsd_stage_latency_seconds_count{stage=\"control\"} 100\n"), std::string::npos);
  EXPECT_NE(r.body.find("fsd_as_state 2\n"), std::string::npos);
  EXPECT_NE(r.body.find("fsd_web_clients 0\n"), std::string::npos);
}

}  // namespace
}  // namespace fsd::web::test

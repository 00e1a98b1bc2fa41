#pragma once
// What the two web fuzz targets share: a Hub as the server builds it (three tunable parameters with bounds, a
// token, two channels, one latched and one with a backlog), made once per process, and the invariants after each
// input: every parameter still within its schema bounds, and changed only by an input that held the token.
#include <cstdlib>
#include <memory>
#include <string>

#include <spdlog/spdlog.h>

#include "common/clock.hpp"
#include "common/config.hpp"
#include "common/params.hpp"
#include "web/hub.hpp"
#include "web/metrics.hpp"

namespace fsd::web::fuzz {

inline constexpr const char* kToken = "fuzz-token";

struct Tuning {
  double target_speed = 5;
  int lookahead_points = 10;
  bool use_gnss = true;
};

inline std::shared_ptr<const ConfigSchema> schema() {
  static const auto section = ConfigSection<Tuning>("control")
                                  .number("target_speed", &Tuning::target_speed, 0.0, 20.0, "m/s", "Target speed", true)
                                  .integer("lookahead_points", &Tuning::lookahead_points, 1, 50, "", "Look-ahead", true)
                                  .boolean("use_gnss", &Tuning::use_gnss, "Use GNSS in lap 2", true);
  auto s = std::make_shared<ConfigSchema>();
  section.describe(*s);
  return s;
}

struct WebFixture {
  WebFixture() {
    spdlog::set_level(spdlog::level::off);  // the refusals are logged: millions of lines otherwise
    hub->listen_to_params();
    params.subscribe([this](const ParamChange&) { ++changes; });
    hub->add_channel("/a", "A", "{}", ChannelOptions{true});
    hub->add_channel("/log", "L", "{}", ChannelOptions{false, 4});
    hub->publish(1, 1.0, "\"a\"");
    hub->publish(2, 1.0, "\"l\"");
    hub->drain();
  }
  // Aborts (a finding) when a parameter left its bounds, or changed during an input without the token.
  void check(std::size_t changes_before, bool token_given) const {
    const double v = *params.get("control.target_speed"), n = *params.get("control.lookahead_points");
    const double g = *params.get("control.use_gnss");
    if (!(v >= 0 && v <= 20) || !(n >= 1 && n <= 50 && n == static_cast<int>(n)) || !(g == 0 || g == 1)) std::abort();
    if (!token_given && changes != changes_before) std::abort();
  }
  std::size_t changes = 0;

  RealClock clock;
  Config config{schema()};
  ParamRegistry params{config, &clock, 16};
  Metrics metrics;
  std::shared_ptr<Hub> hub = std::make_shared<Hub>(params, kToken, metrics, HubLimits{4, 64, 64, 64}, "fuzz");
};

}  // namespace fsd::web::fuzz

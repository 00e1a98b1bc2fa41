#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "common/clock.hpp"
#include "common/params.hpp"

namespace fsd {
namespace {

struct Tun {
  double speed = 5.0;
  int window = 3;
  bool enabled = true;
  double fixed = 1.0;
};

std::shared_ptr<const ConfigSchema> schema() {
  auto s = std::make_shared<ConfigSchema>();
  ConfigSection<Tun>("c")
      .number("speed", &Tun::speed, 0.0, 20.0, "m/s", "speed", true)
      .integer("window", &Tun::window, 1, 8, "", "window", true)
      .boolean("enabled", &Tun::enabled, "on", true)
      .number("fixed", &Tun::fixed, 0.0, 2.0, "", "not tunable")
      .describe(*s);
  return s;
}

TEST(ParamRegistry, HoldsOnlyTunablesWithConfigValues) {
  Config cfg(schema());
  cfg.set("c.speed", nlohmann::json(7.0), "test");
  ParamRegistry reg(cfg);
  EXPECT_EQ(reg.list().size(), 3u);
  EXPECT_EQ(reg.get("c.speed"), 7.0);
  EXPECT_EQ(reg.get("c.enabled"), 1.0);
  EXPECT_FALSE(reg.get("c.fixed"));
}

TEST(ParamRegistry, EnforcesBoundsAndTypes) {
  Config cfg(schema());
  ParamRegistry reg(cfg);
  EXPECT_FALSE(reg.set("c.speed", 25.0, "t").ok);
  EXPECT_FALSE(reg.set("c.speed", -0.1, "t").ok);
  EXPECT_FALSE(reg.set("c.speed", std::nan(""), "t").ok);
  EXPECT_FALSE(reg.set("c.window", 2.5, "t").ok);
  EXPECT_FALSE(reg.set("c.window", 9, "t").ok);
  EXPECT_FALSE(reg.set("c.enabled", 0.5, "t").ok);
  EXPECT_FALSE(reg.set("c.fixed", 1.5, "t").ok);
  EXPECT_FALSE(reg.set("nope", 1.0, "t").ok);
  EXPECT_EQ(reg.get("c.speed"), 5.0);
  EXPECT_EQ(reg.history().size(), 0u);
  const auto r = reg.set("c.speed", 25.0, "t");
  EXPECT_EQ(r.error, "parameter 'c.speed': value 25 out of range [0, 20] m/s");
}

TEST(ParamRegistry, ChangesAreVisibleAndLoggedWithWho) {
  Config cfg(schema());
  LockstepClock clock(12.5);
  ParamRegistry reg(cfg, &clock, 2);
  std::vector<ParamChange> seen;
  reg.subscribe([&](const ParamChange& c) { seen.push_back(c); });
  ASSERT_TRUE(reg.set("c.speed", 8.0, "web 10.0.0.2").ok);
  EXPECT_EQ(*reg.get("c.speed"), 8.0);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].who, "web 10.0.0.2");
  EXPECT_EQ(seen[0].old_value, 5.0);
  EXPECT_EQ(seen[0].new_value, 8.0);
  EXPECT_EQ(seen[0].t, 12.5);
  ASSERT_TRUE(reg.set("c.speed", 9.0, "a").ok);
  ASSERT_TRUE(reg.set("c.speed", 10.0, "b").ok);
  const auto hist = reg.history();
  ASSERT_EQ(hist.size(), 2u);  // bounded
  EXPECT_EQ(hist[0].new_value, 9.0);
  EXPECT_EQ(hist[1].old_value, 9.0);
}

TEST(ParamRegistry, ConcurrentWritersAndReadersSeeOnlyValidValues) {
  Config cfg(schema());
  ParamRegistry reg(cfg, nullptr, 100000);
  std::atomic<bool> stop{false};
  std::atomic<int> bad{0};
  std::thread reader([&] {
    while (!stop.load()) {
      const double v = *reg.get("c.speed");
      if (v != 5.0 && v != 1.0 && v != 2.0) bad.fetch_add(1);
    }
  });
  std::vector<std::thread> writers;
  for (int w = 0; w < 2; ++w)
    writers.emplace_back([&, w] {
      for (int i = 0; i < 5000; ++i) reg.set("c.speed", w == 0 ? 1.0 : 2.0, "w");
    });
  for (auto& t : writers) t.join();
  stop = true;
  reader.join();
  EXPECT_EQ(bad.load(), 0);
  // Every change was recorded, and each one's old value is the previous one's new value.
  const auto hist = reg.history();
  ASSERT_EQ(hist.size(), 10000u);
  for (std::size_t i = 1; i < hist.size(); ++i) ASSERT_EQ(hist[i].old_value, hist[i - 1].new_value);
  EXPECT_EQ(*reg.get("c.speed"), hist.back().new_value);
}

}  // namespace
}  // namespace fsd

// The virtual car's GNSS-INS checked through the project's own NMEA driver against the truth it was given.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/wire/nmea.hpp"
#include "drivers/gnss/gnss_driver.hpp"
#include "drivers/gnss/nmea_sentences.hpp"
#include "drivers/sim/sensors/gnss_model.hpp"

namespace fsd::sim {
namespace {

// A car on a 20 m circle at 10 m/s, turning left, slightly rolled and pitched, with some sideslip.
VehicleTruth circle(Stamp t) {
  constexpr double r = 20.0, v = 10.0, w = v / r;
  VehicleTruth s;
  s.t = t;
  s.pose = {r * std::sin(w * t), r * (1.0 - std::cos(w * t)), wrap_angle(w * t)};
  s.vx = v;
  s.vy = 0.4;
  s.yaw_rate = w;
  s.roll = 0.03;
  s.pitch = -0.01;
  return s;
}

GnssConfig driver_config_for(const GnssModelConfig& m) {
  GnssConfig c;
  c.use_first_fix = false;
  c.origin_lat_deg = m.origin_lat_deg;
  c.origin_lon_deg = m.origin_lon_deg;
  c.origin_height_m = m.origin_height_m;
  c.antenna_x = m.antenna_x;
  c.antenna_y = m.antenna_y;
  c.antenna_z = m.antenna_z;
  return c;
}

struct RunResult {
  std::vector<std::string> sentences;
  std::vector<Stamp> sentence_stamps;
  std::vector<GnssSample> samples;
  GnssCounters counters;
  GnssModelStats stats;
};

RunResult run(const GnssModelConfig& mc, std::uint64_t seed, double duration, double step = 0.005) {
  RunResult r;
  GnssModel model(mc, seed);
  GnssDriver driver(driver_config_for(mc), [&](const GnssSample& s) { r.samples.push_back(s); });
  const ByteSink sink = [&](Stamp t, std::span<const std::uint8_t> bytes) {
    r.sentences.emplace_back(bytes.begin(), bytes.end());
    r.sentence_stamps.push_back(t);
    driver.feed(bytes, t);
  };
  const auto steps = static_cast<long>(std::llround(duration / step));
  for (long i = 0; i <= steps; ++i) model.advance_to(static_cast<double>(i) * step, circle, sink);
  // Let the last epoch's sentences leave the line (< 20 ms at the default latency and baud), no new epoch yet.
  model.advance_to(duration + 0.0195, circle, sink);
  r.counters = driver.counters();
  r.stats = model.stats();
  return r;
}

// Epoch time of a sample: the GGA left `latency` after the epoch plus its few milliseconds of line time.
Stamp epoch_of(const GnssSample& s, const GnssModelConfig& m) {
  return std::round((s.stamp - m.latency_s) * m.rate_hz) / m.rate_hz;
}

struct Stat {
  double mean = 0, sd = 0;
};
Stat stat(const std::vector<double>& v) {
  Stat s;
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = std::sqrt(s.sd / static_cast<double>(v.size() - 1));
  return s;
}

TEST(GnssModel, EverySentenceParsesWithAValidChecksum) {
  const GnssModelConfig mc;
  const RunResult r = run(mc, 1, 10.0);
  ASSERT_EQ(r.sentences.size(), 6u * 501u);  // epochs at 0, 0.02, ..., 10.0 s
  EXPECT_EQ(r.stats.sentences, r.sentences.size());
  for (const auto& s : r.sentences) {
    ASSERT_GE(s.size(), 2u);
    EXPECT_EQ(s.substr(s.size() - 2), "\r\n");
    const std::string line = s.substr(0, s.size() - 2);
    const nmea::Unframed u = nmea::unframe(line);
    ASSERT_EQ(u.error, nmea::FrameError::None) << s;
    EXPECT_EQ(parse_sentence(u.payload).error, SentenceError::None) << s;
    // Like real RTK receivers' high-precision GGA, longer than the standard's 82 but within the driver's limit.
    EXPECT_LE(line.size(), static_cast<std::size_t>(GnssConfig{}.max_line_length) - 20) << s;
  }
  EXPECT_EQ(r.counters.bad_checksum + r.counters.malformed + r.counters.unsupported + r.counters.late_sentences, 0u);
  EXPECT_EQ(r.counters.sentences, r.sentences.size());
  EXPECT_EQ(r.samples.size(), 501u);  // the driver learnt ROT as the epoch's last sentence from the first epoch on
  for (std::size_t i = 1; i < r.sentence_stamps.size(); ++i) EXPECT_GE(r.sentence_stamps[i], r.sentence_stamps[i - 1]);
}

TEST(GnssModel, NoiseFreeRoundTripsTheTruth) {
  GnssModelConfig mc;
  mc.rtk_sigma_m = 0.0;
  mc.heading_sigma_rad = mc.attitude_sigma_rad = mc.yaw_rate_sigma_rad_s = mc.velocity_sigma_m_s = 0.0;
  const RunResult r = run(mc, 7, 5.0);
  ASSERT_GT(r.samples.size(), 240u);
  for (const auto& s : r.samples) {
    const VehicleTruth t = circle(epoch_of(s, mc));
    ASSERT_TRUE(s.good);
    EXPECT_NEAR(s.enu.x(), t.pose.x, 1e-3);
    EXPECT_NEAR(s.enu.y(), t.pose.y, 1e-3);
    EXPECT_NEAR(s.enu.z(), 0.0, 1e-3);
    EXPECT_NEAR(wrap_angle(s.heading - t.pose.yaw), 0.0, 1e-4);  // 0.001° on the wire
    EXPECT_NEAR(s.yaw_rate, t.yaw_rate, 1e-5);
    EXPECT_NEAR(s.roll, t.roll, 1e-4);
    EXPECT_NEAR(s.pitch, t.pitch, 1e-4);
    EXPECT_NEAR(s.speed, t.speed(), 1e-3);
    EXPECT_NEAR(wrap_angle(s.course - (t.pose.yaw + t.sideslip())), 0.0, 1e-3);
    EXPECT_EQ(s.fix_quality, 4);
    EXPECT_EQ(s.satellites, mc.rtk_satellites);
    EXPECT_NEAR(s.alt_m, mc.origin_height_m + mc.antenna_z * std::cos(t.roll) * std::cos(t.pitch), 0.05);
  }
}

TEST(GnssModel, RtkNoiseMatchesTheConfiguredSigma) {
  const GnssModelConfig mc;  // 2 cm per horizontal axis, 3 cm vertical
  const RunResult r = run(mc, 42, 80.0);
  ASSERT_GT(r.samples.size(), 3900u);
  std::vector<double> ex, ey, ez, eh, er, ep, ew, ev;
  for (const auto& s : r.samples) {
    const VehicleTruth t = circle(epoch_of(s, mc));
    EXPECT_TRUE(s.good);
    ex.push_back(s.enu.x() - t.pose.x);
    ey.push_back(s.enu.y() - t.pose.y);
    ez.push_back(s.enu.z());
    eh.push_back(wrap_angle(s.heading - t.pose.yaw));
    er.push_back(s.roll - t.roll);
    ep.push_back(s.pitch - t.pitch);
    ew.push_back(s.yaw_rate - t.yaw_rate);
    ev.push_back(s.speed - t.speed());
  }
  const double n = static_cast<double>(ex.size());
  auto expect_noise = [&](const std::vector<double>& e, double sigma, const char* what) {
    const Stat s = stat(e);
    EXPECT_NEAR(s.mean, 0.0, 4.0 * sigma / std::sqrt(n)) << what;
    EXPECT_NEAR(s.sd, sigma, 0.08 * sigma) << what;
  };
  // The lever arm is removed with the noisy heading and attitude: ≤ 1 mm more, well inside the tolerance.
  expect_noise(ex, mc.rtk_sigma_m, "east");
  expect_noise(ey, mc.rtk_sigma_m, "north");
  expect_noise(ez, 1.5 * mc.rtk_sigma_m, "up");
  expect_noise(eh, mc.heading_sigma_rad, "heading");
  expect_noise(er, mc.attitude_sigma_rad, "roll");
  expect_noise(ep, mc.attitude_sigma_rad, "pitch");
  expect_noise(ew, mc.yaw_rate_sigma_rad_s, "yaw rate");
  // Speed is the length of the true velocity plus noise per axis: σ along the velocity.
  expect_noise(ev, mc.velocity_sigma_m_s, "speed");
}

TEST(GnssModel, SinglePointIsQualityOneAndNotGoodWithAWanderingBias) {
  GnssModelConfig mc;
  mc.mode = "single";
  const RunResult r = run(mc, 3, 600.0, 0.02);
  ASSERT_GT(r.samples.size(), 29000u);
  std::vector<double> ex, step;
  for (std::size_t i = 0; i < r.samples.size(); ++i) {
    const GnssSample& s = r.samples[i];
    EXPECT_EQ(s.fix_quality, 1);
    EXPECT_FALSE(s.good);
    ex.push_back(s.enu.x() - circle(epoch_of(s, mc)).pose.x);
    if (i > 0) step.push_back(ex[i] - ex[i - 1]);
  }
  // From one epoch to the next only the white part changes: √2 σ_white. The whole error also has the bias.
  EXPECT_NEAR(stat(step).sd, std::sqrt(2.0) * mc.single_sigma_m, 0.05 * std::sqrt(2.0) * mc.single_sigma_m);
  const double total = std::hypot(mc.single_sigma_m, mc.single_bias_sigma_m);
  EXPECT_NEAR(stat(ex).sd, total, 0.35 * total);  // 20 correlation times: a loose estimate
  EXPECT_GT(stat(ex).sd, 2.0 * mc.single_sigma_m);
}

TEST(GnssModel, ScheduledOutageLeavesAGap) {
  GnssModelConfig mc;
  mc.outage_start_s = 4.0;
  mc.outage_duration_s = 2.0;
  const RunResult r = run(mc, 5, 10.0);
  double before = -1, after = 1e9;
  for (const auto& s : r.samples) {
    const double te = epoch_of(s, mc);
    EXPECT_FALSE(te >= 4.0 && te < 6.0) << te;
    if (te < 4.0)
      before = std::max(before, te);
    else
      after = std::min(after, te);
  }
  EXPECT_NEAR(before, 3.98, 1e-9);
  EXPECT_NEAR(after, 6.0, 1e-9);
  EXPECT_EQ(r.stats.silent_epochs, 100u);
}

TEST(GnssModel, NoFixOutageKeepsTheInertialPart) {
  GnssModelConfig mc;
  mc.outage_start_s = 2.0;
  mc.outage_duration_s = 1.0;
  mc.outage_mode = "no_fix";
  const RunResult r = run(mc, 5, 4.0);
  int lost = 0;
  for (const auto& s : r.samples) {
    const double te = epoch_of(s, mc);
    const bool in = te >= 2.0 && te < 3.0;
    EXPECT_EQ(s.fix_quality, in ? 0 : 4) << te;
    EXPECT_EQ(s.good, !in) << te;
    EXPECT_TRUE(s.heading_valid);
    EXPECT_TRUE(s.yaw_rate_valid);
    lost += in;
  }
  EXPECT_EQ(lost, 50);
  EXPECT_EQ(r.counters.malformed, 0u);
}

TEST(GnssModel, SingleFallbackOutage) {
  GnssModelConfig mc;
  mc.outage_start_s = 1.0;
  mc.outage_duration_s = 1.0;
  mc.outage_mode = "single";
  const RunResult r = run(mc, 5, 3.0);
  for (const auto& s : r.samples) {
    const double te = epoch_of(s, mc);
    EXPECT_EQ(s.fix_quality, te >= 1.0 && te < 2.0 ? 1 : 4) << te;
  }
}

TEST(GnssModel, RandomDropoutsAtTheConfiguredRate) {
  GnssModelConfig mc;
  mc.dropout_probability = 0.2;
  const RunResult r = run(mc, 9, 60.0);
  ASSERT_EQ(r.stats.epochs, 3001u);
  EXPECT_NEAR(static_cast<double>(r.samples.size()) / 3001.0, 0.8, 0.03);
  EXPECT_EQ(r.stats.silent_epochs + r.samples.size(), 3001u);
}

TEST(GnssModel, MultipathShiftsThePositionForAWhile) {
  GnssModelConfig mc;
  mc.multipath_rate_hz = 0.1;
  mc.multipath_step_m = 1.5;
  mc.multipath_duration_s = 2.0;
  const RunResult r = run(mc, 11, 120.0);
  ASSERT_GT(r.stats.multipath_events, 3u);
  int shifted = 0;
  for (const auto& s : r.samples) {
    const VehicleTruth t = circle(epoch_of(s, mc));
    const double e = std::hypot(s.enu.x() - t.pose.x, s.enu.y() - t.pose.y);
    EXPECT_TRUE(e < 0.15 || std::abs(e - 1.5) < 0.15) << e;  // either RTK noise or one step
    EXPECT_TRUE(s.good);                                     // the receiver does not notice
    shifted += e > 0.75;
  }
  EXPECT_EQ(shifted, static_cast<int>(r.stats.multipath_events) * 100);  // 2 s at 50 Hz each
}

TEST(GnssModel, CorruptedSentencesFailTheChecksum) {
  GnssModelConfig mc;
  mc.corrupt_probability = 0.05;
  const RunResult r = run(mc, 13, 20.0);
  ASSERT_GT(r.stats.corrupted, 100u);
  EXPECT_EQ(r.counters.bad_checksum, r.stats.corrupted);
  EXPECT_EQ(r.counters.sentences + r.counters.bad_checksum, r.stats.sentences);
}

TEST(GnssModel, DeterministicForASeedAndIndependentOfTheStep) {
  const GnssModelConfig mc;
  const RunResult a = run(mc, 21, 3.0, 0.005);
  const RunResult b = run(mc, 21, 3.0, 0.1);
  const RunResult c = run(mc, 22, 3.0, 0.005);
  EXPECT_EQ(a.sentences, b.sentences);
  EXPECT_EQ(a.sentence_stamps, b.sentence_stamps);
  EXPECT_NE(a.sentences, c.sentences);
}

TEST(GnssModel, LatencyAndLineTime) {
  GnssModelConfig mc;
  mc.latency_s = 0.03;
  mc.baud = 230400;
  const RunResult r = run(mc, 1, 1.0);
  // Each sentence is stamped when its last byte is out: latency after the epoch, then back to back at 10 bits
  // per byte; the line is idle again before the next epoch.
  ASSERT_GT(r.sentences.size(), 6u * 45u);
  for (std::size_t i = 0; i < r.sentences.size(); ++i) {
    const double epoch = static_cast<double>(i / 6) / mc.rate_hz;
    const double start = i % 6 == 0 ? epoch + mc.latency_s : r.sentence_stamps[i - 1];
    EXPECT_NEAR(r.sentence_stamps[i], start + static_cast<double>(r.sentences[i].size()) * 10.0 / mc.baud, 1e-9);
  }
  // Nothing is handed over before its time: the sentences of the last epochs are still on the line at 1.0195 s.
  EXPECT_LT(r.sentences.size(), r.stats.sentences);
  EXPECT_LE(r.sentence_stamps.back(), 1.0195);
}

TEST(GnssModel, TooSlowALineFallsBehindAndDropsEpochs) {
  GnssModelConfig mc;
  mc.baud = 115200;  // ~30 ms of sentences per 20 ms epoch
  const RunResult r = run(mc, 1, 10.0);
  for (std::size_t i = 1; i < r.sentences.size(); ++i)  // the line never idles
    EXPECT_NEAR(r.sentence_stamps[i] - r.sentence_stamps[i - 1], r.sentences[i].size() * 10.0 / mc.baud, 1e-9);
  EXPECT_GT(r.stats.silent_epochs, 0u);  // the receiver's buffer (1 s of output) overflowed
  EXPECT_EQ(r.counters.bad_checksum + r.counters.malformed, 0u);
}

TEST(GnssModel, UtcDateRollsOverAtMidnight) {
  GnssModelConfig mc;
  mc.utc_year = 2024;
  mc.utc_month = 12;
  mc.utc_day = 31;
  mc.utc_start_s = 86399.0;
  const RunResult r = run(mc, 1, 2.0);
  std::vector<nmea::Date> dates;
  std::vector<double> times;
  for (const auto& s : r.sentences) {
    const auto p = parse_sentence(nmea::unframe(s.substr(0, s.size() - 2)).payload);
    if (const auto* rmc = std::get_if<RmcSentence>(&p.sentence)) {
      dates.push_back(*rmc->date);
      times.push_back(*rmc->utc_s);
    }
  }
  ASSERT_EQ(dates.size(), 101u);  // epochs at 0, 0.02, ..., 2.0 s
  EXPECT_EQ(dates.front(), (nmea::Date{2024, 12, 31}));
  EXPECT_DOUBLE_EQ(times.front(), 86399.0);
  EXPECT_EQ(dates[49], (nmea::Date{2024, 12, 31}));
  EXPECT_EQ(dates[50], (nmea::Date{2025, 1, 1}));
  EXPECT_DOUBLE_EQ(times[50], 0.0);
}

TEST(GnssModel, ConfigSectionDeclaresEveryKey) {
  ConfigSchema schema;
  gnss_model_section().describe(schema);
  EXPECT_EQ(schema.entries().size(), 34u);  // one per GnssModelConfig member but the antenna (car.gnss_antenna)
  for (const auto& e : schema.entries()) EXPECT_EQ(e.key.rfind("sim.gnss.", 0), 0u) << e.key;
  const GnssModelConfig read = gnss_model_section().read(Config(std::make_shared<const ConfigSchema>(schema)));
  EXPECT_EQ(read.mode, "rtk");
  EXPECT_EQ(read.rate_hz, 50.0);
  EXPECT_EQ(read.origin_lat_deg, GnssModelConfig{}.origin_lat_deg);
}

TEST(GnssModel, RejectsImpossibleSettings) {
  GnssModelConfig mc;
  mc.utc_month = 2;
  mc.utc_day = 30;
  EXPECT_THROW(GnssModel(mc, 1), std::invalid_argument);
  mc = GnssModelConfig{};
  mc.mode = "ppp";
  EXPECT_THROW(GnssModel(mc, 1), std::invalid_argument);
}

}  // namespace
}  // namespace fsd::sim

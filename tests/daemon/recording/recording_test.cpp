// Record and replay (issue #14) as a user runs them: `fsd run --sim --headless --record` then `fsd run --replay`.
// A lockstep recording replays bit for bit: every command the Stack computes equals the recorded one, and two
// replays give the same scorecard (wall time and latencies aside), which is also the live run's. The truth the
// replay scores against is the recorded one, so the mission's outcome (finished, laps, cones) must be the live
// run's. Damaged and foreign files get a clear message (cut off: played up to the cut; not MCAP, empty, a newer
// version: exit 2).
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "common/mcap/byte_io.hpp"
#include "common/mcap/fsd_profile.hpp"
#include "common/mcap/summary_reader.hpp"
#include "common/mcap/writer.hpp"
#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd {
namespace {

using nlohmann::json;

const std::string kFast = test::truth_sources();

std::string write_text(const std::string& name, const std::string& text) {
  const auto p = test::scratch_path(name);
  std::ofstream(p) << text;
  return p;
}

json read_json(const std::string& path) {
  std::ifstream f(path);
  return json::parse(f);
}

// What may differ between two runs of the same input: compute time, and the replay's bookkeeping of its own.
json without_wall_time(json j) {
  j.erase("wall_time_s");
  j.erase("latency_ms");
  j.erase("recording");
  if (j.contains("replay")) {
    j["replay"].erase("wall_time_s");
    j["replay"].erase("speed_x");
    j["replay"].erase("file");
  }
  return j;
}

// One recorded acceleration run for the tests of this file (recorded once: about a second).
struct Recorded {
  std::string file, live_report, log;
  int rc = -1;
};
const Recorded& acceleration() {
  static const Recorded r = [] {
    Recorded x;
    x.file = test::scratch_path("acc.mcap");
    x.live_report = test::scratch_path("acc_live.json");
    const auto cfg = write_text("fast.json", kFast);
    x.rc = test::run_fsd(
        "run --sim --headless --until-finished --mission acceleration --track "
        "../shared/tracks/epfl_acceleration.csv --config " +
            cfg + " --record " + x.file + " --report " + x.live_report,
        &x.log);
    return x;
  }();
  return r;
}

TEST(Recording, AHeadlessRunRecordsEveryFrameCycleAndCommand) {
  const auto& rec = acceleration();
  ASSERT_EQ(rec.rc, 0) << rec.log;
  const json live = read_json(rec.live_report);
  ASSERT_TRUE(live.contains("recording")) << live.dump(2);
  const json& st = live["recording"];
  EXPECT_EQ(st["dropped"], 0);
  EXPECT_EQ(st["error"], "");
  ASSERT_EQ(st["files"].size(), 1u);
  EXPECT_EQ(st["files"][0], rec.file);
  // 100 Hz control: one cycle marker and one command per 10 ms of the run's simulated time.
  const double sim_time = live["sim_time_s"].get<double>();
  EXPECT_NEAR(st["cycles_written"].get<double>(), sim_time * 100, 1.5);
  EXPECT_EQ(st["commands_written"], st["cycles_written"]);
  // Each cycle feeds a truth state frame at least (and NMEA, VCU status, VCU commands).
  EXPECT_GT(st["frames_written"].get<double>(), 3 * st["cycles_written"].get<double>());
  EXPECT_EQ(static_cast<std::uintmax_t>(st["bytes"].get<double>()), std::filesystem::file_size(rec.file));

  // `fsd mcap info` sees a whole file with the recorder's channels and metadata.
  std::string out;
  ASSERT_EQ(test::run_fsd("mcap info --json " + rec.file, &out), 0) << out;
  const json info = json::parse(out.substr(out.find('{')));
  EXPECT_TRUE(info["complete"].get<bool>());
  std::set<std::string> topics;
  for (const auto& c : info["channels"]) topics.insert(c["topic"].get<std::string>());
  for (const char* t : {"/raw/nmea", "/raw/vcu_rx", "/raw/vcu_tx", "/raw/truth_state", "/raw/truth_cones",
                        "/stack/cycle", "/stack/command"})
    EXPECT_TRUE(topics.count(t)) << t << " in " << out;
  std::set<std::string> metadata;
  for (const auto& m : info["metadata"]) metadata.insert(m["name"].get<std::string>());
  for (const char* m : {"fsd.recording", "fsd.config", "fsd.run", "fsd.recorder"}) EXPECT_TRUE(metadata.count(m)) << m;
  ASSERT_EQ(info["attachments"].size(), 1u);
  EXPECT_EQ(info["attachments"][0]["name"], "track.csv");
}

TEST(Recording, ReplayRepeatsTheRunBitForBitAndScoresAsTheLiveRun) {
  const auto& rec = acceleration();
  ASSERT_EQ(rec.rc, 0) << rec.log;
  const json live = read_json(rec.live_report);
  json replays[2];
  for (int i = 0; i < 2; ++i) {
    const auto report = test::scratch_path("acc_replay" + std::to_string(i) + ".json");
    std::string out;
    ASSERT_EQ(test::run_fsd("run --replay " + rec.file + " --headless --until-finished --report " + report, &out), 0)
        << out;
    replays[i] = read_json(report);
    const json& rp = replays[i]["replay"];
    EXPECT_EQ(rp["cycles"], live["recording"]["cycles_written"]);
    EXPECT_EQ(rp["frames"], live["recording"]["frames_written"]);
    EXPECT_EQ(rp["inexact_frames"], 0);
    EXPECT_EQ(rp["commands_compared"], live["recording"]["commands_written"]);
    EXPECT_EQ(rp["command_mismatches"], 0) << out;
    EXPECT_TRUE(rp["first_mismatch_t"].is_null());
    EXPECT_GT(rp["vcu_frames_compared"].get<int>(), 0);
    EXPECT_EQ(rp["vcu_frame_mismatches"], 0);
    EXPECT_TRUE(rp["complete"].get<bool>());
  }
  EXPECT_EQ(without_wall_time(replays[0]), without_wall_time(replays[1]));
  // Scored against the recorded truth: the live run's outcome, figure for figure.
  json replayed = without_wall_time(replays[0]);
  replayed.erase("replay");
  EXPECT_EQ(replayed, without_wall_time(live));
  EXPECT_TRUE(replays[0]["finished"].get<bool>());
  EXPECT_EQ(replays[0]["mission"], "acceleration");
  EXPECT_EQ(replays[0]["track"], "epfl_acceleration");
}

// A run recorded with `run_args` (plus --config and --record) and its replay: both scorecards, the replay's log.
struct LiveAndReplay {
  json live, replay;
  std::string log;
};
LiveAndReplay record_and_replay(const std::string& name, const std::string& config_text, const std::string& run_args) {
  LiveAndReplay r;
  const auto file = test::scratch_path(name + ".mcap");
  const auto live_report = test::scratch_path(name + "_live.json");
  const auto report = test::scratch_path(name + "_replay.json");
  const auto cfg = write_text(name + ".json", config_text);
  const int live_rc = test::run_fsd("run --sim --headless --until-finished " + run_args + " --config " + cfg +
                                        " --record " + file + " --report " + live_report,
                                    &r.log);
  EXPECT_EQ(live_rc, 0) << r.log;
  if (live_rc != 0) return r;
  r.live = read_json(live_report);
  EXPECT_EQ(test::run_fsd("run --replay " + file + " --headless --until-finished --report " + report, &r.log), 0)
      << r.log;
  r.replay = read_json(report);
  return r;
}

TEST(Recording, ATwoLapTrackdriveReplaysBitForBit) {
  const auto r = record_and_replay("td", kFast, "--track ../shared/tracks/epfl_track_1.csv --laps 2");
  ASSERT_FALSE(r.replay.is_null()) << r.log;
  ASSERT_EQ(r.live["laps"].size(), 2u);
  EXPECT_EQ(r.replay["replay"]["command_mismatches"], 0);
  EXPECT_EQ(r.replay["replay"]["commands_compared"], r.live["recording"]["commands_written"]);
  json replayed = without_wall_time(r.replay);
  replayed.erase("replay");
  EXPECT_EQ(replayed, without_wall_time(r.live));
}

TEST(Recording, AReplayOnTheLidarScoresWhatTheSensorCouldSeeAsTheLiveRun) {
  // The LiDAR pipeline (camera off): the scorecard's recall over the cones the simulated LiDAR returned points
  // from comes from the recorded truth in the replay, figure for figure.
  const auto r = record_and_replay(
      "lidar",
      R"({"sim": {"enable_camera": false}, "run": {"perception_source": "lidar", "localization_source": "truth"}})",
      "--mission acceleration --track ../shared/tracks/epfl_acceleration.csv");
  ASSERT_FALSE(r.replay.is_null()) << r.log;
  const json& live = r.live["perception"];
  ASSERT_TRUE(live.contains("recall_visible_15m")) << live.dump();
  EXPECT_GE(live["recall_visible_15m"].get<double>(), 0.97) << live.dump();
  EXPECT_EQ(r.replay["replay"]["command_mismatches"], 0);
  EXPECT_EQ(r.replay["perception"], live);
}

TEST(Recording, AConfigOnTopOfTheRecordedOneChangesTheReplay) {
  const auto& rec = acceleration();
  ASSERT_EQ(rec.rc, 0) << rec.log;
  // A lower top speed: the stack plans other commands from the same frames, which the replay reports as not
  // repeating the run (exit 1), with the first mismatch after the go (RES at 6.02 s, recorded truth).
  const auto slower = write_text("slower.json", R"({"control": {"speed": {"v_max": 5.0}}})");
  const auto report = test::scratch_path("acc_slower.json");
  std::string out;
  EXPECT_EQ(test::run_fsd("run --replay " + rec.file + " --headless --config " + slower + " --report " + report, &out),
            1)
      << out;
  EXPECT_NE(out.find("did not repeat the recorded run bit for bit"), std::string::npos) << out;
  const json r = read_json(report)["replay"];
  EXPECT_GT(r["command_mismatches"].get<int>(), 0);
  EXPECT_GT(r["first_mismatch_t"].get<double>(), 6.0);
  // A key no fsd knows, or a value out of bounds, is refused before anything replays.
  const auto bad = write_text("bad_override.json", R"({"control": {"speed": {"v_max": -1}}})");
  EXPECT_EQ(test::run_fsd("run --replay " + rec.file + " --headless --config " + bad, &out), 2) << out;
  EXPECT_NE(out.find("control.speed.v_max"), std::string::npos) << out;
}

TEST(Recording, ACutOffRecordingReplaysUpToItsLastCompleteChunk) {
  const auto& rec = acceleration();
  ASSERT_EQ(rec.rc, 0) << rec.log;
  // Cut in the middle of the last chunk (the summary's chunk index says where it lies).
  std::uint64_t last_chunk = 0, cut_at = 0;
  {
    const mcap::MappedFile mapped(rec.file);
    std::string why;
    const auto summary = mcap::read_summary(mapped.bytes(), {}, &why);
    ASSERT_TRUE(summary && summary->chunk_indexes.size() >= 2) << why;
    const auto& c = summary->chunk_indexes.back();
    last_chunk = c.chunk_start_offset;
    cut_at = c.chunk_start_offset + c.chunk_length / 2;
  }
  const auto cut = test::scratch_path("acc_cut.mcap");
  std::filesystem::copy_file(rec.file, cut, std::filesystem::copy_options::overwrite_existing);
  std::filesystem::resize_file(cut, cut_at);
  const auto report = test::scratch_path("acc_cut.json");
  std::string out;
  ASSERT_EQ(test::run_fsd("run --replay " + cut + " --headless --report " + report, &out), 0) << out;
  EXPECT_NE(out.find("cut off at offset"), std::string::npos) << out;
  EXPECT_NE(out.find("replayed up to its last complete chunk"), std::string::npos) << out;
  const json r = read_json(report)["replay"];
  EXPECT_FALSE(r["complete"].get<bool>());
  ASSERT_TRUE(r["truncated_at"].is_number());
  EXPECT_EQ(r["truncated_at"].get<std::uint64_t>(), last_chunk);  // the incomplete chunk is not read
  const json live = read_json(rec.live_report);
  EXPECT_GT(r["cycles"].get<int>(), 0);
  EXPECT_LT(r["cycles"].get<int>(), live["recording"]["cycles_written"].get<int>());
  EXPECT_EQ(r["command_mismatches"], 0);  // what is there replays exactly
}

TEST(Recording, ADamagedChunkIsReportedWithItsOffset) {
  const auto& rec = acceleration();
  ASSERT_EQ(rec.rc, 0) << rec.log;
  // Flip a byte in the middle of a chunk in the middle of the file (the summary's chunk index says where).
  std::uint64_t flip_at = 0;
  {
    const mcap::MappedFile mapped(rec.file);
    std::string why;
    const auto summary = mcap::read_summary(mapped.bytes(), {}, &why);
    ASSERT_TRUE(summary && summary->chunk_indexes.size() >= 3) << why;
    const auto& c = summary->chunk_indexes[summary->chunk_indexes.size() / 2];
    flip_at = c.chunk_start_offset + c.chunk_length / 2;
  }
  const auto bad = test::scratch_path("acc_flipped.mcap");
  std::filesystem::copy_file(rec.file, bad, std::filesystem::copy_options::overwrite_existing);
  {
    std::fstream f(bad, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(flip_at));
    char c = 0;
    f.read(&c, 1);
    f.seekp(-1, std::ios::cur);
    c = static_cast<char>(c ^ 0x5a);
    f.write(&c, 1);
  }
  std::string out;
  const int rc = test::run_fsd("run --replay " + bad + " --headless", &out);
  EXPECT_NE(rc, 2) << out;  // the file is read, less the damaged chunk
  EXPECT_NE(out.find("chunk at offset"), std::string::npos) << out;
}

TEST(Recording, FilesThatAreNoRecordingExitTwoWithAClearMessage) {
  std::string out;
  const auto empty = write_text("empty.mcap", "");
  EXPECT_EQ(test::run_fsd("run --replay " + empty + " --headless", &out), 2) << out;
  EXPECT_NE(out.find(empty + ": empty file"), std::string::npos) << out;

  const auto garbage = write_text("garbage.mcap", "this is not an MCAP file at all, just text\n");
  EXPECT_EQ(test::run_fsd("run --replay " + garbage + " --headless", &out), 2) << out;
  EXPECT_NE(out.find(garbage + ": not an MCAP file"), std::string::npos) << out;

  // A recording of a newer fsd: its version says so before anything is read.
  const auto newer = test::scratch_path("newer.mcap");
  {
    mcap::FileSink sink(newer);
    mcap::Writer w(sink);
    w.write_metadata(std::string(mcap::kRecordingMetadata), {{std::string(mcap::kRecordingVersionKey), "2"}});
    w.close();
  }
  EXPECT_EQ(test::run_fsd("run --replay " + newer + " --headless", &out), 2) << out;
  EXPECT_NE(out.find("recording version 2 is newer than this fsd's (1)"), std::string::npos) << out;

  // An MCAP file of someone else's: no configuration to build the stack from.
  const auto foreign = test::scratch_path("foreign.mcap");
  {
    mcap::FileSink sink(foreign);
    mcap::Writer w(sink);
    const auto ch = w.add_channel("/chatter", "json", 0);
    const std::string msg = "{}";
    w.write_message(ch, 1, 1, {reinterpret_cast<const std::uint8_t*>(msg.data()), msg.size()});
    w.close();
  }
  EXPECT_EQ(test::run_fsd("run --replay " + foreign + " --headless", &out), 2) << out;
  EXPECT_NE(out.find("not a recording of fsd run"), std::string::npos) << out;

  EXPECT_EQ(test::run_fsd("run --replay " + test::scratch_path("missing.mcap") + " --headless", &out), 2) << out;
  EXPECT_NE(out.find("cannot open"), std::string::npos) << out;
}

TEST(Recording, AnUncreatableRecordingIsRefusedBeforeTheRun) {
  std::string out;
  EXPECT_EQ(test::run_fsd("run --sim --headless --record /nonexistent-dir/r.mcap", &out), 2) << out;
  EXPECT_NE(out.find("--record /nonexistent-dir/r.mcap"), std::string::npos) << out;
  EXPECT_EQ(out.find("driving"), std::string::npos) << out;
}

TEST(Recording, AFullDiskStopsTheRecordingNotTheRun) {
  // A file size limit (ulimit -f, 512-byte blocks) stands for the full disk: write(2) fails with EFBIG once the
  // recording reaches 64 KiB. SIGXFSZ is ignored, as it would be for the service, so the write fails instead of
  // the signal ending the process (the disposition is inherited through exec).
  std::signal(SIGXFSZ, SIG_IGN);
  const auto file = test::scratch_path("full.mcap");
  const auto report = test::scratch_path("full.json");
  const auto cfg = write_text("fast_full.json", kFast);
  std::string out;
  const int rc = test::run_fsd_with("ulimit -f 128;",
                                    "run --sim --headless --until-finished --mission acceleration "
                                    "--track ../shared/tracks/epfl_acceleration.csv --config " +
                                        cfg + " --record " + file + " --report " + report,
                                    &out);
  std::signal(SIGXFSZ, SIG_DFL);
  EXPECT_EQ(rc, 0) << out;  // the run went on and finished its mission
  EXPECT_NE(out.find("recording stopped: "), std::string::npos) << out;
  EXPECT_NE(out.find("File too large"), std::string::npos) << out;
  const json r = read_json(report);
  EXPECT_TRUE(r["finished"].get<bool>());
  EXPECT_NE(r["recording"]["error"], "");
  EXPECT_GT(r["recording"]["dropped"].get<int>(), 0);
  EXPECT_LE(std::filesystem::file_size(file), 64u * 1024);
  // What reached the disk replays up to its cut.
  EXPECT_EQ(test::run_fsd("run --replay " + file + " --headless", &out), 0) << out;
  EXPECT_NE(out.find("cut off at offset"), std::string::npos) << out;
}

TEST(Recording, AHeadlessRunWaitsForTheWriterRatherThanDropping) {
  // A queue of 16 items against a run that makes ~800 a simulated second at ~50x real time: the lockstep loop
  // waits for the writer, so nothing is lost and the replay still repeats the run.
  const auto file = test::scratch_path("small_queue.mcap");
  const auto report = test::scratch_path("small_queue.json");
  const auto cfg = write_text("small_queue_cfg.json", test::truth_sources({{"record", {{"queue_frames", 16}}}}));
  std::string out;
  ASSERT_EQ(test::run_fsd("run --sim --headless --until-finished --mission acceleration --track "
                          "../shared/tracks/epfl_acceleration.csv --config " +
                              cfg + " --record " + file + " --report " + report,
                          &out),
            0)
      << out;
  const json st = read_json(report)["recording"];
  EXPECT_EQ(st["dropped"], 0);
  EXPECT_LE(st["queue_high_water"].get<int>(), 16);
  const auto replay = test::scratch_path("small_queue_replay.json");
  ASSERT_EQ(test::run_fsd("run --replay " + file + " --headless --report " + replay, &out), 0) << out;
  const json r = read_json(replay)["replay"];
  EXPECT_EQ(r["commands_compared"], st["commands_written"]);
  EXPECT_EQ(r["command_mismatches"], 0);
}

TEST(Recording, LargeRecordingsSplitIntoPartsThatEachReplay) {
  const auto file = test::scratch_path("split.mcap");
  const auto report = test::scratch_path("split.json");
  const auto cfg = write_text("split_cfg.json", test::truth_sources({{"record", {{"split_mb", 0.05}}}}));
  std::string out;
  ASSERT_EQ(test::run_fsd("run --sim --headless --until-finished --mission acceleration --track "
                          "../shared/tracks/epfl_acceleration.csv --config " +
                              cfg + " --record " + file + " --report " + report,
                          &out),
            0)
      << out;
  const json st = read_json(report)["recording"];
  ASSERT_GE(st["files"].size(), 3u);  // the run records several hundred KiB
  std::uintmax_t total = 0;
  for (const auto& f : st["files"]) total += std::filesystem::file_size(f.get<std::string>());
  EXPECT_EQ(static_cast<double>(total), st["bytes"].get<double>());
  for (const auto& f : st["files"]) {
    // A part ends after the first whole cycle past 50 KiB of messages. A cycle's frames are well under a KiB here,
    // but a cycle may also carry the derived scene of the paths (up to ~40 KiB of JSON on this layout,
    // daemon/derived_channels); every part also holds the configuration (~35 KiB of metadata) and the derived
    // channels' schemas twice (data section and summary, ~10 KiB each).
    EXPECT_LE(std::filesystem::file_size(f.get<std::string>()), 128u * 1024) << f;
    EXPECT_EQ(test::run_fsd("mcap info " + f.get<std::string>(), &out), 0) << out;
  }
  // The second part alone replays (it carries the configuration); it starts mid-run, so its commands differ.
  const auto part = st["files"][1].get<std::string>();
  EXPECT_EQ(part, test::scratch_path("split-001.mcap"));
  EXPECT_EQ(test::run_fsd("run --replay " + part + " --headless", &out), 1) << out;
  EXPECT_NE(out.find("did not repeat the recorded run bit for bit"), std::string::npos) << out;
}

}  // namespace
}  // namespace fsd

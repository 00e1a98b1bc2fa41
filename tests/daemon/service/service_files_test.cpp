// What the service leaves for the pit lane: log lines the journal files at their priority, and recordings in the
// configured folder held under its size cap.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "tests/daemon/fsd_child.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/truth_sources.hpp"

namespace fsd {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

std::string config(const std::string& name, const std::string& json) {
  const auto p = test::scratch_path(name);
  std::ofstream(p) << json;
  return p;
}

const std::string kTrack = "../shared/tracks/epfl_acceleration.csv";

// systemd connects stderr to the journal and names that stream in JOURNAL_STREAM (device:inode); journald reads a
// leading "<N>" as the line's priority (sd-daemon(3): 4 warning, 6 info).
TEST(ServiceFiles, UnderTheJournalEachLineCarriesItsPriority) {
  const auto log = test::scratch_path("journal.log");
  std::ofstream(log).flush();
  struct stat st {};
  ASSERT_EQ(::stat(log.c_str(), &st), 0);
  const std::string stream = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  const auto cfg = config("journal.json", test::truth_sources({{"run", {{"max_sim_time", 1}}}}));
  ::setenv("JOURNAL_STREAM", stream.c_str(), 1);
  test::Fsd fsd({"run", "--sim", "--headless", "--track", kTrack, "--config", cfg}, log);
  ::unsetenv("JOURNAL_STREAM");
  ASSERT_EQ(fsd.wait(60s), 0) << fsd.output();
  std::istringstream lines(fsd.output());
  std::string line;
  int warnings = 0, infos = 0, unmarked = 0;
  while (std::getline(lines, line)) {
    if (line.find("giving up after") != std::string::npos) {
      EXPECT_EQ(line.rfind("<4>", 0), 0u) << line;
      ++warnings;
    } else if (line.rfind("<6>", 0) == 0) {
      ++infos;
    } else if (line.rfind("<", 0) != 0) {
      ++unmarked;
    }
  }
  EXPECT_EQ(warnings, 1) << fsd.output();
  EXPECT_GE(infos, 2);  // the run's start and end lines at least
  EXPECT_EQ(unmarked, 0) << fsd.output();

  // Not the journal's stream (another inode): the lines stay as they were, with their time and level.
  const auto other = test::scratch_path("other.log");
  ::setenv("JOURNAL_STREAM", stream.c_str(), 1);
  test::Fsd plain({"run", "--sim", "--headless", "--track", kTrack, "--config", cfg}, other);
  ::unsetenv("JOURNAL_STREAM");
  ASSERT_EQ(plain.wait(60s), 0);
  EXPECT_EQ(plain.output().find("<6>"), std::string::npos);
  EXPECT_NE(plain.output().find("warning [run] giving up after"), std::string::npos) << plain.output();
}

// service.recordings_dir: each run records there by itself, and the oldest recordings go to keep the cap.
TEST(ServiceFiles, RecordingsGoToTheFolderUnderItsCap) {
  const fs::path dir = test::scratch_path("recordings");
  fs::create_directories(dir);
  // Three old recordings of 1 MiB each, oldest first.
  for (int k = 0; k < 3; ++k) {
    const auto p = dir / ("old-" + std::to_string(k) + ".mcap");
    std::ofstream(p) << std::string(1 << 20, 'x');
    fs::last_write_time(p, fs::file_time_type::clock::now() - std::chrono::hours(10 - k));
  }
  std::ofstream(dir / "notes.txt") << "not a recording";
  const auto cfg = config(
      "rec.json", test::truth_sources({{"run", {{"max_sim_time", 2}}},
                                       {"service", {{"recordings_dir", dir.string()}, {"recordings_max_mb", 2.5}}}}));
  test::Fsd fsd({"run", "--sim", "--headless", "--track", kTrack, "--config", cfg}, test::scratch_path("rec.log"));
  ASSERT_EQ(fsd.wait(60s), 0) << fsd.output();
  std::uintmax_t total = 0;
  int fresh = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".mcap") continue;
    total += e.file_size();
    fresh += e.path().filename().string().rfind("fsd-", 0) == 0;
  }
  EXPECT_EQ(fresh, 1) << fsd.output();
  EXPECT_FALSE(fs::exists(dir / "old-0.mcap"));  // the oldest went first
  EXPECT_TRUE(fs::exists(dir / "old-2.mcap"));   // the newest old one fits beside the new recording
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));    // only recordings are pruned
  EXPECT_LE(total, static_cast<std::uintmax_t>(2.5 * 1024 * 1024));
}

}  // namespace
}  // namespace fsd

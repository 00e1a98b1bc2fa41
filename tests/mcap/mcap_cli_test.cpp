// `fsd mcap info` and `fsd mcap recover` as a user runs them: the real binary, its output and exit status, on
// files of known content.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "common/mcap/byte_io.hpp"
#include "common/mcap/summary_reader.hpp"
#include "tests/daemon/fsd_process.hpp"
#include "tests/mcap/test_recording.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd::mcap {
namespace {

using nlohmann::json;

std::string write_file(const std::string& name, std::span<const std::uint8_t> bytes) {
  const auto path = fsd::test::scratch_path(name);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return path;
}

struct Run {
  int status;
  std::string out;
};
Run fsd(const std::string& args) {
  Run r;
  r.status = fsd::test::run_fsd(args, &r.out);
  return r;
}

TEST(McapCli, InfoListsWhatTheFileHolds) {
  const auto rec = test::make_recording({});
  const auto path = write_file("info.mcap", rec.file);
  const auto r = fsd("mcap info --json " + path);
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["profile"], "fsd");
  EXPECT_EQ(j["library"], std::string("fsd-daemon ") + FSD_VERSION);
  EXPECT_EQ(j["messages"], rec.messages.size());
  EXPECT_DOUBLE_EQ(j["start_s"].get<double>(), 1.0);
  EXPECT_NEAR(j["duration_s"].get<double>(), (rec.messages.size() - 1) * 1e-3, 1e-9);
  ASSERT_EQ(j["channels"].size(), 3u);
  EXPECT_EQ(j["channels"][1]["topic"], "/test/1");
  EXPECT_EQ(j["channels"][1]["schema"], "fsd.Test");
  EXPECT_EQ(j["channels"][1]["messages"], rec.messages.size() / 3);
  EXPECT_EQ(j["chunks"], rec.chunks.size());
  EXPECT_EQ(j["chunk_compression"]["zstd"], rec.chunks.size());
  EXPECT_EQ(j["metadata"][1]["name"], "fsd.recorder");
  EXPECT_EQ(j["metadata"][1]["values"]["dropped"], "3");
  EXPECT_EQ(j["attachments"][0]["name"], "track.csv");
  EXPECT_EQ(j["summary_present"], true);
  EXPECT_EQ(j["complete"], true);
  EXPECT_TRUE(j["issues"].empty());

  const auto text = fsd("mcap info " + path);
  ASSERT_EQ(text.status, 0);
  EXPECT_NE(text.out.find("fsd.recorder  dropped=3  queue_high_water=17"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("status:      complete"), std::string::npos) << text.out;
}

TEST(McapCli, InfoOnACutOffFileSaysSoAndRecoverMendsIt) {
  const auto rec = test::make_recording({});
  const auto chunks = SummaryReader(rec.file).summary()->chunk_indexes;
  const auto& c = chunks[5];
  const std::uint64_t cut = c.chunk_start_offset + c.chunk_length / 2;
  const auto path = write_file("cut.mcap", std::span(rec.file).first(cut));
  std::size_t kept = 0;
  for (std::size_t k = 0; k < 5; ++k) kept += rec.chunks[k].size();

  const auto r = fsd("mcap info --json " + path);
  ASSERT_EQ(r.status, 0) << r.out;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["complete"], false);
  EXPECT_EQ(j["summary_present"], false);
  EXPECT_EQ(j["truncated_at"], c.chunk_start_offset);
  EXPECT_EQ(j["messages"], kept);
  const auto text = fsd("mcap info " + path);
  EXPECT_NE(text.out.find("cut off at offset " + std::to_string(c.chunk_start_offset)), std::string::npos) << text.out;

  const auto out = fsd::test::scratch_path("mended.mcap");
  const auto rr = fsd("mcap recover " + path + " " + out);
  ASSERT_EQ(rr.status, 0) << rr.out;
  EXPECT_NE(rr.out.find("kept: " + std::to_string(kept) + " messages"), std::string::npos) << rr.out;
  EXPECT_NE(rr.out.find("bytes at the cut-off end"), std::string::npos) << rr.out;
  MappedFile mended(out);
  SummaryReader s(mended.bytes());
  ASSERT_TRUE(s.has_summary());
  EXPECT_EQ(s.summary()->statistics->message_count, kept);
}

TEST(McapCli, BadFilesExitTwoNamingTheFile) {
  const auto empty = write_file("empty.mcap", {});
  auto r = fsd("mcap info " + empty);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "fsd: " + empty + ": empty file\n");

  const std::string csv = "tag,x,y\n";
  const auto text = write_file("track.mcap", std::span(reinterpret_cast<const std::uint8_t*>(csv.data()), csv.size()));
  r = fsd("mcap info " + text);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "fsd: " + text + ": not an MCAP file (it does not start with the MCAP magic)\n");

  Bytes future(kMagic.begin(), kMagic.end());
  future[5] = '1';
  future.resize(64, 0);
  const auto newer = write_file("newer.mcap", future);
  r = fsd("mcap info " + newer);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("fsd: " + newer + ": MCAP format version 1 is newer"), std::string::npos) << r.out;

  const auto out = fsd::test::scratch_path("never.mcap");
  r = fsd("mcap recover " + text + " " + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_FALSE(std::filesystem::exists(out));
  const auto magic_only = write_file("magic.mcap", Bytes(kMagic.begin(), kMagic.end()));
  r = fsd("mcap recover " + magic_only + " " + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("nothing to recover"), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists(out));
  r = fsd("mcap recover " + magic_only + " " + magic_only);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(fsd("mcap info /nonexistent.mcap").status, 2);
  EXPECT_EQ(fsd("mcap").status, 2);
}

}  // namespace
}  // namespace fsd::mcap

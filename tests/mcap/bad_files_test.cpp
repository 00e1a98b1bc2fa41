// Files that are no MCAP of this version at all get one clear sentence each (the CLI prints "fsd: FILE: <it>").
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "common/mcap/byte_io.hpp"
#include "common/mcap/fsd_profile.hpp"
#include "common/mcap/linear_reader.hpp"
#include "common/mcap/summary_reader.hpp"
#include "common/mcap/writer.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd::mcap {
namespace {

std::string error_of(const Bytes& file) {
  try {
    LinearReader r(file);
    return "";
  } catch (const McapError& e) {
    std::string linear = e.what();
    try {
      SummaryReader s(file);
      return "summary reader accepted what the linear reader refused";
    } catch (const McapError& e2) {
      EXPECT_EQ(linear, e2.what());
    }
    return linear;
  }
}

Bytes of(const std::string& s) { return Bytes(s.begin(), s.end()); }

TEST(McapBadFiles, EmptyFile) { EXPECT_EQ(error_of({}), "empty file"); }

TEST(McapBadFiles, NotMcap) {
  EXPECT_EQ(error_of(of("tag,x,y,direction\nblue,1,2,0\n")),
            "not an MCAP file (it does not start with the MCAP magic)");
  const Bytes pcap = {0xD4, 0xC3, 0xB2, 0xA1, 0x02, 0x00, 0x04, 0x00, 0, 0, 0, 0};
  EXPECT_EQ(error_of(pcap), "not an MCAP file (it does not start with the MCAP magic)");
  EXPECT_EQ(error_of(of("\x89MCAPx\r\n")), "not an MCAP file (bad magic)");
  EXPECT_EQ(error_of(of("\x89MC")), "not a complete MCAP file: only 3 bytes");
}

TEST(McapBadFiles, NewerMajorVersion) {
  Bytes file = of("\x89MCAP1\r\n");
  file.resize(100, 0);
  EXPECT_EQ(error_of(file), "MCAP format version 1 is newer than this reader's (0): written by a newer MCAP library");
}

TEST(McapBadFiles, MissingFileAndDirectory) {
  try {
    MappedFile f("/nonexistent/x.mcap");
    ADD_FAILURE();
  } catch (const McapError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot open: No such file or directory");
  }
  EXPECT_THROW(MappedFile(test::scratch_dir().string()), McapError);
}

TEST(McapBadFiles, MagicOnlyIsCutOffNotRefused) {
  const Bytes file(kMagic.begin(), kMagic.end());
  LinearReader r(file);
  EXPECT_FALSE(r.next());
  ASSERT_TRUE(r.truncated_at());
  EXPECT_EQ(*r.truncated_at(), 8u);
}

TEST(McapRecordingVersion, NewerVersionsAreRefusedWithASentence) {
  EXPECT_FALSE(recording_version_problem({}));
  EXPECT_FALSE(recording_version_problem({Metadata{"fsd.recording", recording_metadata()}}));
  EXPECT_EQ(recording_metadata().at("fsd.recording_version"), "1");
  const auto newer = recording_version_problem({Metadata{"fsd.recording", {{"fsd.recording_version", "2"}}}});
  ASSERT_TRUE(newer);
  EXPECT_EQ(*newer, "recording version 2 is newer than this fsd's (1): replay it with a newer fsd-daemon");
  EXPECT_TRUE(recording_version_problem({Metadata{"fsd.recording", {{"fsd.recording_version", "x1"}}}}));
  EXPECT_TRUE(recording_version_problem({Metadata{"fsd.recording", {{"fsd.recording_version", "0"}}}}));
  // Another record's key of the same name is not the recording's version.
  EXPECT_FALSE(recording_version_problem({Metadata{"other", {{"fsd.recording_version", "9"}}}}));
}

// A sink that fails after a number of bytes, as a full disk does.
class FailingSink final : public ByteSink {
 public:
  explicit FailingSink(std::size_t room) : room_(room) {}
  void write(std::span<const std::uint8_t> b) override {
    if (b.size() > room_) throw McapError("writing run.mcap: No space left on device");
    room_ -= b.size();
  }

 private:
  std::size_t room_;
};

TEST(McapWriterErrors, AFullSinkIsAnErrorAndStaysOne) {
  FailingSink sink(4096);
  WriterOptions o;
  o.chunk_size = 2048;
  o.compression = Compression::None;  // zstd would fit these repeated bytes in the room
  Writer w(sink, o);
  const auto ch = w.add_channel("/a", "fsd.raw", 0);
  const Bytes data(1500, 1);
  bool failed = false;
  for (int i = 0; i < 10 && !failed; ++i) {
    try {
      w.write_message(ch, i, i, data);
    } catch (const McapError& e) {
      EXPECT_STREQ(e.what(), "writing run.mcap: No space left on device");
      failed = true;
    }
  }
  EXPECT_TRUE(failed);
  EXPECT_THROW(w.write_message(ch, 99, 99, data), McapError);
  EXPECT_THROW(w.close(), McapError);
}

TEST(McapWriterErrors, FileSinkReportsENOSPC) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  FileSink sink("/dev/full");
  const Bytes data(100, 1);
  try {
    sink.write(data);
    ADD_FAILURE() << "a write to /dev/full succeeded";
  } catch (const McapError& e) {
    EXPECT_EQ(std::string(e.what()), "writing /dev/full: No space left on device");
  }
}

TEST(McapWriterErrors, FileSinkWritesAFileTheReaderReads) {
  const auto path = test::scratch_path("sink.mcap");
  {
    FileSink sink(path);
    Writer w(sink);
    const auto ch = w.add_channel("/a", "fsd.raw", 0);
    w.write_message(ch, 1, 1, Bytes{9, 8, 7});
    w.close();
    sink.close();
  }
  MappedFile f(path);
  SummaryReader r(f.bytes());
  ASSERT_TRUE(r.has_summary());
  EXPECT_EQ(r.summary()->statistics->message_count, 1u);
  EXPECT_THROW(FileSink("/nonexistent/dir/x.mcap"), McapError);
}

}  // namespace
}  // namespace fsd::mcap

// `fsd lidar-dump` on a capture cut off mid-packet (a logger killed while writing): it prints the points it read
// and then names the damage, exit 2 (issue #18). The points are those of the whole capture up to the cut.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream s(text);
  for (std::string l; std::getline(s, l);) out.push_back(l);
  return out;
}

TEST(LidarDumpCli, ACutOffCaptureListsWhatItReadThenTheDamage) {
  const std::string full_pcap = "../shared/data/vlp16/velodyne_vlp16.pcap";
  std::ifstream in(full_pcap, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 60000u);
  const auto cut = test::scratch_path("cut.pcap");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, 30000);  // inside the 24th packet record

  std::string full, part;
  ASSERT_EQ(test::run_fsd("lidar-dump --csv " + full_pcap, &full), 0) << full.substr(0, 500);
  EXPECT_EQ(test::run_fsd("lidar-dump --csv " + cut, &part), 2) << part.substr(0, 500);
  const auto all = lines_of(full), got = lines_of(part);
  ASSERT_GT(got.size(), 2u);
  // The damage is named on the last line; everything before it is the full dump's beginning, row for row.
  EXPECT_NE(got.back().find("truncated"), std::string::npos) << got.back();
  EXPECT_NE(got.back().find("cut.pcap"), std::string::npos) << got.back();
  const std::size_t rows = got.size() - 1;
  ASSERT_LT(rows, all.size());
  EXPECT_GT(rows, 1000u);  // ~20 packets of 384 firings, the valid ones
  for (std::size_t i = 0; i < rows; ++i) ASSERT_EQ(got[i], all[i]) << "row " << i;
}

}  // namespace
}  // namespace fsd

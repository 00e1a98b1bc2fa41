// CRC-32 against the published check value of the zlib polynomial and its incremental form.
#include <gtest/gtest.h>

#include <string>

#include "common/mcap/crc32.hpp"

namespace fsd::mcap {
namespace {

std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

TEST(McapCrc32, CheckValueOfTheZlibPolynomial) {
  EXPECT_EQ(crc32(bytes_of("123456789")), 0xCBF43926u);  // the CRC-32/ISO-HDLC check value
  EXPECT_EQ(crc32(bytes_of("")), 0u);
  EXPECT_EQ(crc32(bytes_of("The quick brown fox jumps over the lazy dog")), 0x414FA339u);
}

TEST(McapCrc32, IncrementalEqualsWhole) {
  std::string s;
  for (int i = 0; i < 1000; ++i) s.push_back(static_cast<char>(i * 7 + 3));
  const std::uint32_t whole = crc32(bytes_of(s));
  for (std::size_t cut : {0ul, 1ul, 7ul, 8ul, 9ul, 500ul, 999ul, 1000ul}) {
    const auto all = bytes_of(s);
    EXPECT_EQ(crc32_update(crc32(all.first(cut)), all.subspan(cut)), whole) << cut;
  }
}

}  // namespace
}  // namespace fsd::mcap

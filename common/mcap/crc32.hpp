#pragma once
// CRC-32 as MCAP uses it: the zlib/PNG polynomial (reflected 0xEDB88320), initial value and final xor 0xFFFFFFFF.
// Incremental: crc32_update(crc32_update(0, a), b) == crc32(a + b).
#include <cstdint>
#include <span>

namespace fsd::mcap {

std::uint32_t crc32_update(std::uint32_t crc, std::span<const std::uint8_t> bytes);
inline std::uint32_t crc32(std::span<const std::uint8_t> bytes) { return crc32_update(0, bytes); }

}  // namespace fsd::mcap

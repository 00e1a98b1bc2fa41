#pragma once
// Standard base64 (RFC 4648, with padding): how the Foxglove JSON encoding carries bytes (point clouds, images).
#include <cstdint>
#include <span>
#include <string>

namespace fsd::web {

std::string base64_encode(std::span<const std::uint8_t> bytes);

}  // namespace fsd::web

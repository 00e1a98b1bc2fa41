#pragma once
// Frames from JPEG bytes: what an MJPEG camera, and the virtual car's camera model, send.
#include <cstdint>
#include <span>
#include <stdexcept>

#include "drivers/camera/frame.hpp"

namespace fsd {

// Thrown for bytes that are not one complete, decodable JPEG image; what() says what is wrong.
class CameraDataError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr std::size_t kMaxJpegBytes = 32u << 20;  // far above any camera frame

// Decodes one JPEG image into a BGR frame. Rejects (CameraDataError) empty or oversized input, a missing
// start-of-image or end-of-image marker (a truncated transfer) and data the decoder cannot read.
Frame decode_jpeg_frame(std::span<const std::uint8_t> bytes, Stamp stamp, std::uint32_t seq = 0);

}  // namespace fsd

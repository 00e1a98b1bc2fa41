#include "drivers/camera/jpeg_frame.hpp"

#include <string>

#include <opencv2/imgcodecs.hpp>

namespace fsd {

namespace {
// An MJPEG payload may carry a few padding bytes after the end-of-image marker.
constexpr std::size_t kMaxTrailingPadding = 16;

bool ends_with_eoi(std::span<const std::uint8_t> b) {
  const std::size_t limit = std::min(b.size(), kMaxTrailingPadding + 2);
  for (std::size_t back = 2; back <= limit; ++back) {
    const std::size_t i = b.size() - back;
    if (b[i] == 0xFF && b[i + 1] == 0xD9) return true;
    if (b[i + 1] != 0x00) return false;  // only zero padding may follow the marker
  }
  return false;
}
}  // namespace

Frame decode_jpeg_frame(std::span<const std::uint8_t> bytes, Stamp stamp, std::uint32_t seq) {
  if (bytes.empty()) throw CameraDataError("JPEG frame: no data");
  if (bytes.size() > kMaxJpegBytes)
    throw CameraDataError("JPEG frame: " + std::to_string(bytes.size()) + " bytes, more than the limit of " +
                          std::to_string(kMaxJpegBytes));
  if (bytes.size() < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8 || bytes[2] != 0xFF)
    throw CameraDataError("JPEG frame: no start-of-image marker (FF D8 FF); not a JPEG image");
  if (!ends_with_eoi(bytes))
    throw CameraDataError("JPEG frame: no end-of-image marker (FF D9); truncated after " +
                          std::to_string(bytes.size()) + " bytes");
  Frame f;
  f.stamp = stamp;
  f.seq = seq;
  try {
    // imdecode wants a Mat header; it only reads the bytes.
    const cv::Mat raw(1, static_cast<int>(bytes.size()), CV_8U, const_cast<std::uint8_t*>(bytes.data()));
    f.bgr = cv::imdecode(raw, cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    throw CameraDataError(std::string("JPEG frame: decoder error: ") + e.what());
  }
  if (f.bgr.empty()) throw CameraDataError("JPEG frame: corrupt data, the decoder produced no image");
  return f;
}

}  // namespace fsd

#include "drivers/camera/image_file.hpp"

#include <array>
#include <fstream>
#include <vector>

#include <opencv2/imgcodecs.hpp>

namespace fsd {

namespace {
constexpr std::array<std::uint8_t, 8> kPngSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};

std::uint32_t be32(std::span<const std::uint8_t> b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) | (std::uint32_t{b[at + 2]} << 8) | b[at + 3];
}
unsigned be16(std::span<const std::uint8_t> b, std::size_t at) { return (unsigned{b[at]} << 8) | b[at + 1]; }

[[noreturn]] void fail(const std::string& origin, const std::string& problem) {
  throw ImageFileError(origin + ": " + problem);
}

ImageHeader png_header(std::span<const std::uint8_t> b, const std::string& origin) {
  // Signature, then the IHDR chunk: length 13, type, width, height.
  if (b.size() < 33) fail(origin, "truncated PNG: " + std::to_string(b.size()) + " bytes, no complete header");
  if (be32(b, 8) != 13 || b[12] != 'I' || b[13] != 'H' || b[14] != 'D' || b[15] != 'R')
    fail(origin, "corrupt PNG: the first chunk is not a 13-byte IHDR");
  const std::uint32_t w = be32(b, 16), h = be32(b, 20);
  if (w > static_cast<std::uint32_t>(kMaxImageSide) || h > static_cast<std::uint32_t>(kMaxImageSide))
    fail(origin, "image of " + std::to_string(w) + " x " + std::to_string(h) + " px is too large (at most " +
                     std::to_string(kMaxImageSide) + " px on a side)");
  return {ImageFormat::Png, static_cast<int>(w), static_cast<int>(h)};
}

bool is_frame_header(unsigned marker) {
  // SOF0..SOF15 without DHT (C4), JPG (C8) and DAC (CC).
  return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

ImageHeader jpeg_header(std::span<const std::uint8_t> b, const std::string& origin) {
  std::size_t at = 2;
  while (true) {
    if (at >= b.size() || b[at] != 0xFF)
      fail(origin, "corrupt JPEG: no frame header (SOF) before byte " + std::to_string(at));
    while (at < b.size() && b[at] == 0xFF) ++at;  // fill bytes
    if (at >= b.size()) fail(origin, "truncated JPEG: ends inside a marker");
    const unsigned marker = b[at++];
    if (marker == 0xD8 || marker == 0xD9 || marker == 0xDA)
      fail(origin, "corrupt JPEG: no frame header (SOF) before the image data");
    if ((marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) continue;  // markers without a length
    if (at + 2 > b.size()) fail(origin, "truncated JPEG: ends inside a segment header");
    const unsigned length = be16(b, at);
    if (length < 2) fail(origin, "corrupt JPEG: segment length " + std::to_string(length));
    if (is_frame_header(marker)) {
      if (length < 8 || at + 7 > b.size()) fail(origin, "truncated JPEG: ends inside the frame header");
      const int h = static_cast<int>(be16(b, at + 3)), w = static_cast<int>(be16(b, at + 5));
      return {ImageFormat::Jpeg, w, h};
    }
    at += length;
  }
}
}  // namespace

ImageHeader read_image_header(std::span<const std::uint8_t> b, const std::string& origin) {
  if (b.empty()) fail(origin, "empty file, not an image");
  if (b.size() > kMaxImageFileBytes)
    fail(origin, std::to_string(b.size()) + " bytes, more than the limit of " + std::to_string(kMaxImageFileBytes));
  ImageHeader h;
  if (b.size() >= 8 && std::equal(kPngSignature.begin(), kPngSignature.end(), b.begin()))
    h = png_header(b, origin);
  else if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF)
    h = jpeg_header(b, origin);
  else
    fail(origin, "not a PNG or JPEG image");
  if (h.width <= 0 || h.height <= 0)
    fail(origin, "image of " + std::to_string(h.width) + " x " + std::to_string(h.height) + " px has no pixels");
  if (h.width > kMaxImageSide || h.height > kMaxImageSide ||
      static_cast<std::int64_t>(h.width) * h.height > kMaxImagePixels)
    fail(origin, "image of " + std::to_string(h.width) + " x " + std::to_string(h.height) +
                     " px is too large (at most " + std::to_string(kMaxImageSide) + " px on a side and " +
                     std::to_string(kMaxImagePixels / 1'000'000) + " MP)");
  return h;
}

cv::Mat decode_image(std::span<const std::uint8_t> bytes, const std::string& origin) {
  const ImageHeader h = read_image_header(bytes, origin);
  cv::Mat img;
  try {
    const cv::Mat raw(1, static_cast<int>(bytes.size()), CV_8U, const_cast<std::uint8_t*>(bytes.data()));
    img = cv::imdecode(raw, cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    fail(origin, std::string("decoder error: ") + e.what());
  }
  if (img.empty())
    fail(origin, std::string("corrupt ") + (h.format == ImageFormat::Png ? "PNG" : "JPEG") +
                     " data: the decoder produced no image");
  return img;
}

cv::Mat read_image_file(const std::filesystem::path& file) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) fail(file.string(), "cannot read: " + ec.message());
  if (size > kMaxImageFileBytes)
    fail(file.string(), std::to_string(size) + " bytes, more than the limit of " + std::to_string(kMaxImageFileBytes));
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file.string(), "cannot open");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())))
    fail(file.string(), "read failed");
  return decode_image(bytes, file.string());
}

}  // namespace fsd

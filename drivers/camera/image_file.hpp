#pragma once
// Still images from files a user hands over (`fsd classify --image`, `fsd train-classifier --real DIR`): PNG or JPEG
// only. The header is read and checked first (format, dimensions), so that a corrupt file or a decompression bomb
// is refused with a message before OpenCV's decoder allocates anything; then the image is decoded to 8-bit BGR.
#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>

#include <opencv2/core/mat.hpp>

namespace fsd {

// Thrown for files that are not a readable PNG or JPEG image within the limits; what() names the file and the problem.
class ImageFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr std::size_t kMaxImageFileBytes = 64u << 20;
inline constexpr int kMaxImageSide = 8192;                   // px
inline constexpr std::int64_t kMaxImagePixels = 40'000'000;  // a 40 MP photo; more is not a crop of a cone

enum class ImageFormat { Png, Jpeg };

struct ImageHeader {
  ImageFormat format = ImageFormat::Png;
  int width = 0, height = 0;
};

// The format and size from the first bytes (PNG signature and IHDR; JPEG markers up to the frame header).
// `origin` names the source in messages. Throws ImageFileError.
ImageHeader read_image_header(std::span<const std::uint8_t> bytes, const std::string& origin);

// Header checks, then decoding to CV_8UC3 BGR (grey images become three equal channels). Throws ImageFileError.
cv::Mat decode_image(std::span<const std::uint8_t> bytes, const std::string& origin);

// Reads and decodes a file; the path is the origin in messages.
cv::Mat read_image_file(const std::filesystem::path& file);

}  // namespace fsd

#pragma once
// VLP-16 packets built byte by byte for the tests, straight from the manual's layout (not from the decoder).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace fsd::test {

class Vlp16PacketBytes {
 public:
  // 12 blocks with flags, azimuth of block b = first + b × step (0.01° counts, wrapping at 36000), all
  // distances 0, the timestamp and the two factory bytes.
  Vlp16PacketBytes(std::uint32_t timestamp_us, int first_azimuth, int step, std::uint8_t mode = 0x37,
                   std::uint8_t product = 0x22)
      : bytes_(1206, 0) {
    for (int b = 0; b < 12; ++b) {
      bytes_[static_cast<std::size_t>(b) * 100] = 0xFF;
      bytes_[static_cast<std::size_t>(b) * 100 + 1] = 0xEE;
      azimuth(b, ((first_azimuth + b * step) % 36000 + 36000) % 36000);
    }
    put_u32(1200, timestamp_us);
    bytes_[1204] = mode;
    bytes_[1205] = product;
  }
  // In dual mode blocks come in pairs with the same azimuth: first + (b / 2) × step.
  static Vlp16PacketBytes dual(std::uint32_t timestamp_us, int first_azimuth, int step) {
    Vlp16PacketBytes p(timestamp_us, first_azimuth, step, 0x39);
    for (int b = 0; b < 12; ++b) p.azimuth(b, (first_azimuth + (b / 2) * step) % 36000);
    return p;
  }
  Vlp16PacketBytes& azimuth(int block, int counts) {
    put_u16(static_cast<std::size_t>(block) * 100 + 2, static_cast<std::uint16_t>(counts));
    return *this;
  }
  // Distance in 2 mm counts and reflectivity of one channel.
  Vlp16PacketBytes& channel(int block, int seq, int laser, std::uint16_t distance, std::uint8_t reflectivity) {
    const std::size_t at = static_cast<std::size_t>(block) * 100 + 4 + static_cast<std::size_t>(seq * 16 + laser) * 3;
    put_u16(at, distance);
    bytes_[at + 2] = reflectivity;
    return *this;
  }
  // Every channel of every block returns `distance` with reflectivity = laser id.
  Vlp16PacketBytes& fill(std::uint16_t distance) {
    for (int b = 0; b < 12; ++b)
      for (int s = 0; s < 2; ++s)
        for (int l = 0; l < 16; ++l) channel(b, s, l, distance, static_cast<std::uint8_t>(l));
    return *this;
  }
  std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  void put_u16(std::size_t at, std::uint16_t v) {
    bytes_[at] = static_cast<std::uint8_t>(v & 0xFF);
    bytes_[at + 1] = static_cast<std::uint8_t>(v >> 8);
  }
  void put_u32(std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes_[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
  }
  std::vector<std::uint8_t> bytes_;
};

// A 512-byte position packet: timestamp at 198, PPS state at 202, sentence at 206 (NUL padded).
inline std::vector<std::uint8_t> position_packet_bytes(std::uint32_t timestamp_us, std::uint8_t pps,
                                                       const std::string& sentence) {
  std::vector<std::uint8_t> p(512, 0);
  for (int i = 0; i < 4; ++i) p[198 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(timestamp_us >> (8 * i));
  p[202] = pps;
  for (std::size_t i = 0; i < sentence.size() && i < 128; ++i) p[206 + i] = static_cast<std::uint8_t>(sentence[i]);
  return p;
}

}  // namespace fsd::test

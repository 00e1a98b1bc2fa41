#pragma once
// Records to bytes and back. Every length read from the input is checked against the bytes that remain in the
// record before anything is allocated from it, so a damaged or hostile file can cost at most its own size.
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>

#include "common/mcap/records.hpp"

namespace fsd::mcap {

// Opcode (1 byte) and record length (uint64): what precedes every record's fields.
inline constexpr std::size_t kRecordPrefix = 9;

// A record whose fields do not fit its length, or break a rule of the specification (what() says which).
class FormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Appends the whole record (opcode, length, fields) to `out`. An Attachment's crc is computed here when it is 0.
void append_record(Bytes& out, const Record& r);

// The fields of one record from its body (the bytes after opcode and length). Bytes after the known fields are
// a newer writer's fields and are ignored, as the specification says. nullopt for an opcode it does not know.
// An attachment whose stored CRC does not match its fields is a FormatError.
std::optional<Record> parse_record(std::uint8_t opcode, std::span<const std::uint8_t> body);

// Little-endian helpers shared by the reader and writer.
inline std::uint64_t load_u64(const std::uint8_t* p) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
inline void store_u64(std::uint8_t* p, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

}  // namespace fsd::mcap

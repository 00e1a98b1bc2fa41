#pragma once
// The records of the MCAP file format, version 0 (mcap.dev/spec): one plain struct per opcode, field for field as
// the specification lists them. Integers are little-endian on disk; strings and byte arrays carry a length prefix;
// maps are written in key order (std::map), which is what the specification's own writers do.
#include <array>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace fsd::mcap {

// "\x89MCAP0\r\n": the '0' is the major format version, the one this library reads and writes.
inline constexpr std::array<std::uint8_t, 8> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

enum class Opcode : std::uint8_t {
  Header = 0x01,
  Footer = 0x02,
  Schema = 0x03,
  Channel = 0x04,
  Message = 0x05,
  Chunk = 0x06,
  MessageIndex = 0x07,
  ChunkIndex = 0x08,
  Attachment = 0x09,
  AttachmentIndex = 0x0A,
  Statistics = 0x0B,
  Metadata = 0x0C,
  MetadataIndex = 0x0D,
  SummaryOffset = 0x0E,
  DataEnd = 0x0F,
};
const char* to_string(Opcode op);  // "Header", "Chunk", ... ; "Unknown" for other values

using Bytes = std::vector<std::uint8_t>;
using StringMap = std::map<std::string, std::string>;
using Timestamp = std::uint64_t;  // nanoseconds; the epoch is the writer's (fsd: the run's clock)

struct Header {
  std::string profile;
  std::string library;
};

struct Footer {
  std::uint64_t summary_start = 0;         // 0: no summary section
  std::uint64_t summary_offset_start = 0;  // 0: no summary offset records
  std::uint32_t summary_crc = 0;           // 0: not computed
};

struct Schema {
  std::uint16_t id = 0;  // 0 is reserved: a channel with schema_id 0 has no schema
  std::string name;
  std::string encoding;
  Bytes data;
};

struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;
  StringMap metadata;
};

struct Message {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  Timestamp log_time = 0;
  Timestamp publish_time = 0;
  Bytes data;
};

struct Chunk {
  Timestamp message_start_time = 0;
  Timestamp message_end_time = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;  // 0: not computed
  std::string compression;             // "" or "zstd" here ("lz4" exists in the spec; not read by this library)
  Bytes records;                       // as stored, i.e. compressed
};

struct MessageIndex {
  std::uint16_t channel_id = 0;
  std::vector<std::pair<Timestamp, std::uint64_t>> records;  // log time, offset in the uncompressed chunk
};

struct ChunkIndex {
  Timestamp message_start_time = 0;
  Timestamp message_end_time = 0;
  std::uint64_t chunk_start_offset = 0;
  std::uint64_t chunk_length = 0;
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;  // channel id -> file offset of its index
  std::uint64_t message_index_length = 0;
  std::string compression;
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
};

struct Attachment {
  Timestamp log_time = 0;
  Timestamp create_time = 0;
  std::string name;
  std::string media_type;
  Bytes data;
  std::uint32_t crc = 0;  // of all fields before it; 0: not computed
};

struct AttachmentIndex {
  std::uint64_t offset = 0;
  std::uint64_t length = 0;
  Timestamp log_time = 0;
  Timestamp create_time = 0;
  std::uint64_t data_size = 0;
  std::string name;
  std::string media_type;
};

struct Statistics {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0;
  std::uint32_t attachment_count = 0;
  std::uint32_t metadata_count = 0;
  std::uint32_t chunk_count = 0;
  Timestamp message_start_time = 0;
  Timestamp message_end_time = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};

struct Metadata {
  std::string name;
  StringMap metadata;
};

struct MetadataIndex {
  std::uint64_t offset = 0;
  std::uint64_t length = 0;
  std::string name;
};

struct SummaryOffset {
  std::uint8_t group_opcode = 0;
  std::uint64_t group_start = 0;
  std::uint64_t group_length = 0;
};

struct DataEnd {
  std::uint32_t data_section_crc = 0;  // 0: not computed
};

using Record = std::variant<Header, Footer, Schema, Channel, Message, Chunk, MessageIndex, ChunkIndex, Attachment,
                            AttachmentIndex, Statistics, Metadata, MetadataIndex, SummaryOffset, DataEnd>;
Opcode opcode_of(const Record& r);

// A file this library cannot read at all (empty, not MCAP, a newer major version, unreadable) or, in strict mode,
// refuses (a damaged chunk); what() is a sentence fit for "fsd: <file>: <what>".
class McapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace fsd::mcap

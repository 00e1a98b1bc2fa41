#include "common/mcap/codec.hpp"

#include <string>
#include <type_traits>

#include "common/mcap/crc32.hpp"

namespace fsd::mcap {
namespace {

class Out {
 public:
  explicit Out(Bytes& b) : b_(b) {}
  void u8(std::uint8_t v) { b_.push_back(v); }
  void u16(std::uint16_t v) { le(v, 2); }
  void u32(std::uint32_t v) { le(v, 4); }
  void u64(std::uint64_t v) { le(v, 8); }
  void raw(std::span<const std::uint8_t> s) { b_.insert(b_.end(), s.begin(), s.end()); }
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    b_.insert(b_.end(), s.begin(), s.end());
  }
  void bytes32(const Bytes& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    raw(s);
  }
  void bytes64(const Bytes& s) {
    u64(s.size());
    raw(s);
  }
  // A map or array: uint32 byte length, then the entries `body` appends.
  template <typename F>
  void sized(F body) {
    const std::size_t at = b_.size();
    u32(0);
    body();
    const auto n = static_cast<std::uint32_t>(b_.size() - at - 4);
    for (int i = 0; i < 4; ++i) b_[at + i] = static_cast<std::uint8_t>(n >> (8 * i));
  }
  void string_map(const StringMap& m) {
    sized([&] {
      for (const auto& [k, v] : m) {
        str(k);
        str(v);
      }
    });
  }
  std::size_t size() const { return b_.size(); }

 private:
  void le(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) b_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  Bytes& b_;
};

// Reads fields front to back; every read is checked against what remains of the record.
class In {
 public:
  In(std::span<const std::uint8_t> s, const char* record) : s_(s), record_(record) {}
  std::uint8_t u8(const char* f) { return static_cast<std::uint8_t>(le(1, f)); }
  std::uint16_t u16(const char* f) { return static_cast<std::uint16_t>(le(2, f)); }
  std::uint32_t u32(const char* f) { return static_cast<std::uint32_t>(le(4, f)); }
  std::uint64_t u64(const char* f) { return le(8, f); }
  std::string str(const char* f) {
    const auto s = take(u32(f), f);
    return std::string(s.begin(), s.end());
  }
  Bytes bytes32(const char* f) { return as_bytes(take(u32(f), f)); }
  Bytes bytes64(const char* f) { return as_bytes(take(u64(f), f)); }
  // The bytes of a uint32-length-prefixed map or array.
  In sized(const char* f) { return In(take(u32(f), f), record_); }
  bool empty() const { return pos_ == s_.size(); }
  std::size_t pos() const { return pos_; }
  StringMap string_map(const char* f) {
    In m = sized(f);
    StringMap out;
    while (!m.empty()) {
      std::string k = m.str(f);
      out[std::move(k)] = m.str(f);
    }
    return out;
  }

 private:
  static Bytes as_bytes(std::span<const std::uint8_t> s) { return Bytes(s.begin(), s.end()); }
  std::span<const std::uint8_t> take(std::uint64_t n, const char* f) {
    if (n > s_.size() - pos_) fail(f);
    const auto out = s_.subspan(pos_, static_cast<std::size_t>(n));
    pos_ += static_cast<std::size_t>(n);
    return out;
  }
  std::uint64_t le(int n, const char* f) {
    const auto s = take(static_cast<std::uint64_t>(n), f);
    std::uint64_t v = 0;
    for (int i = n - 1; i >= 0; --i) v = (v << 8) | s[i];
    return v;
  }
  [[noreturn]] void fail(const char* f) const {
    throw FormatError(std::string(record_) + " record: field " + f + " runs past the end of the record");
  }
  std::span<const std::uint8_t> s_;
  std::size_t pos_ = 0;
  const char* record_;
};

void append_fields(Out& o, const Header& r) {
  o.str(r.profile);
  o.str(r.library);
}
void append_fields(Out& o, const Footer& r) {
  o.u64(r.summary_start);
  o.u64(r.summary_offset_start);
  o.u32(r.summary_crc);
}
void append_fields(Out& o, const Schema& r) {
  o.u16(r.id);
  o.str(r.name);
  o.str(r.encoding);
  o.bytes32(r.data);
}
void append_fields(Out& o, const Channel& r) {
  o.u16(r.id);
  o.u16(r.schema_id);
  o.str(r.topic);
  o.str(r.message_encoding);
  o.string_map(r.metadata);
}
void append_fields(Out& o, const Message& r) {
  o.u16(r.channel_id);
  o.u32(r.sequence);
  o.u64(r.log_time);
  o.u64(r.publish_time);
  o.raw(r.data);
}
void append_fields(Out& o, const Chunk& r) {
  o.u64(r.message_start_time);
  o.u64(r.message_end_time);
  o.u64(r.uncompressed_size);
  o.u32(r.uncompressed_crc);
  o.str(r.compression);
  o.bytes64(r.records);
}
void append_fields(Out& o, const MessageIndex& r) {
  o.u16(r.channel_id);
  o.sized([&] {
    for (const auto& [t, off] : r.records) {
      o.u64(t);
      o.u64(off);
    }
  });
}
void append_fields(Out& o, const ChunkIndex& r) {
  o.u64(r.message_start_time);
  o.u64(r.message_end_time);
  o.u64(r.chunk_start_offset);
  o.u64(r.chunk_length);
  o.sized([&] {
    for (const auto& [id, off] : r.message_index_offsets) {
      o.u16(id);
      o.u64(off);
    }
  });
  o.u64(r.message_index_length);
  o.str(r.compression);
  o.u64(r.compressed_size);
  o.u64(r.uncompressed_size);
}
void append_fields(Out& o, const Attachment& r) {
  o.u64(r.log_time);
  o.u64(r.create_time);
  o.str(r.name);
  o.str(r.media_type);
  o.bytes64(r.data);
  o.u32(r.crc);  // patched by append_record when 0
}
void append_fields(Out& o, const AttachmentIndex& r) {
  o.u64(r.offset);
  o.u64(r.length);
  o.u64(r.log_time);
  o.u64(r.create_time);
  o.u64(r.data_size);
  o.str(r.name);
  o.str(r.media_type);
}
void append_fields(Out& o, const Statistics& r) {
  o.u64(r.message_count);
  o.u16(r.schema_count);
  o.u32(r.channel_count);
  o.u32(r.attachment_count);
  o.u32(r.metadata_count);
  o.u32(r.chunk_count);
  o.u64(r.message_start_time);
  o.u64(r.message_end_time);
  o.sized([&] {
    for (const auto& [id, n] : r.channel_message_counts) {
      o.u16(id);
      o.u64(n);
    }
  });
}
void append_fields(Out& o, const Metadata& r) {
  o.str(r.name);
  o.string_map(r.metadata);
}
void append_fields(Out& o, const MetadataIndex& r) {
  o.u64(r.offset);
  o.u64(r.length);
  o.str(r.name);
}
void append_fields(Out& o, const SummaryOffset& r) {
  o.u8(r.group_opcode);
  o.u64(r.group_start);
  o.u64(r.group_length);
}
void append_fields(Out& o, const DataEnd& r) { o.u32(r.data_section_crc); }

Record parse(Opcode op, In& in) {
  switch (op) {
    case Opcode::Header: {
      Header r;
      r.profile = in.str("profile");
      r.library = in.str("library");
      return r;
    }
    case Opcode::Footer: {
      Footer r;
      r.summary_start = in.u64("summary_start");
      r.summary_offset_start = in.u64("summary_offset_start");
      r.summary_crc = in.u32("summary_crc");
      return r;
    }
    case Opcode::Schema: {
      Schema r;
      r.id = in.u16("id");
      r.name = in.str("name");
      r.encoding = in.str("encoding");
      r.data = in.bytes32("data");
      return r;
    }
    case Opcode::Channel: {
      Channel r;
      r.id = in.u16("id");
      r.schema_id = in.u16("schema_id");
      r.topic = in.str("topic");
      r.message_encoding = in.str("message_encoding");
      r.metadata = in.string_map("metadata");
      return r;
    }
    case Opcode::Message:
      break;  // handled by the caller: its data runs to the end of the record
    case Opcode::Chunk: {
      Chunk r;
      r.message_start_time = in.u64("message_start_time");
      r.message_end_time = in.u64("message_end_time");
      r.uncompressed_size = in.u64("uncompressed_size");
      r.uncompressed_crc = in.u32("uncompressed_crc");
      r.compression = in.str("compression");
      r.records = in.bytes64("records");
      return r;
    }
    case Opcode::MessageIndex: {
      MessageIndex r;
      r.channel_id = in.u16("channel_id");
      In a = in.sized("records");
      while (!a.empty()) {
        const auto t = a.u64("records");
        r.records.emplace_back(t, a.u64("records"));
      }
      return r;
    }
    case Opcode::ChunkIndex: {
      ChunkIndex r;
      r.message_start_time = in.u64("message_start_time");
      r.message_end_time = in.u64("message_end_time");
      r.chunk_start_offset = in.u64("chunk_start_offset");
      r.chunk_length = in.u64("chunk_length");
      In m = in.sized("message_index_offsets");
      while (!m.empty()) {
        const auto id = m.u16("message_index_offsets");
        r.message_index_offsets[id] = m.u64("message_index_offsets");
      }
      r.message_index_length = in.u64("message_index_length");
      r.compression = in.str("compression");
      r.compressed_size = in.u64("compressed_size");
      r.uncompressed_size = in.u64("uncompressed_size");
      return r;
    }
    case Opcode::Attachment: {
      Attachment r;
      r.log_time = in.u64("log_time");
      r.create_time = in.u64("create_time");
      r.name = in.str("name");
      r.media_type = in.str("media_type");
      r.data = in.bytes64("data");
      r.crc = in.u32("crc");
      return r;
    }
    case Opcode::AttachmentIndex: {
      AttachmentIndex r;
      r.offset = in.u64("offset");
      r.length = in.u64("length");
      r.log_time = in.u64("log_time");
      r.create_time = in.u64("create_time");
      r.data_size = in.u64("data_size");
      r.name = in.str("name");
      r.media_type = in.str("media_type");
      return r;
    }
    case Opcode::Statistics: {
      Statistics r;
      r.message_count = in.u64("message_count");
      r.schema_count = in.u16("schema_count");
      r.channel_count = in.u32("channel_count");
      r.attachment_count = in.u32("attachment_count");
      r.metadata_count = in.u32("metadata_count");
      r.chunk_count = in.u32("chunk_count");
      r.message_start_time = in.u64("message_start_time");
      r.message_end_time = in.u64("message_end_time");
      In m = in.sized("channel_message_counts");
      while (!m.empty()) {
        const auto id = m.u16("channel_message_counts");
        r.channel_message_counts[id] = m.u64("channel_message_counts");
      }
      return r;
    }
    case Opcode::Metadata: {
      Metadata r;
      r.name = in.str("name");
      r.metadata = in.string_map("metadata");
      return r;
    }
    case Opcode::MetadataIndex: {
      MetadataIndex r;
      r.offset = in.u64("offset");
      r.length = in.u64("length");
      r.name = in.str("name");
      return r;
    }
    case Opcode::SummaryOffset: {
      SummaryOffset r;
      r.group_opcode = in.u8("group_opcode");
      r.group_start = in.u64("group_start");
      r.group_length = in.u64("group_length");
      return r;
    }
    case Opcode::DataEnd: {
      DataEnd r;
      r.data_section_crc = in.u32("data_section_crc");
      return r;
    }
  }
  throw FormatError("unknown opcode");  // not reached: the caller filters unknown opcodes
}

}  // namespace

const char* to_string(Opcode op) {
  switch (op) {
    case Opcode::Header:
      return "Header";
    case Opcode::Footer:
      return "Footer";
    case Opcode::Schema:
      return "Schema";
    case Opcode::Channel:
      return "Channel";
    case Opcode::Message:
      return "Message";
    case Opcode::Chunk:
      return "Chunk";
    case Opcode::MessageIndex:
      return "MessageIndex";
    case Opcode::ChunkIndex:
      return "ChunkIndex";
    case Opcode::Attachment:
      return "Attachment";
    case Opcode::AttachmentIndex:
      return "AttachmentIndex";
    case Opcode::Statistics:
      return "Statistics";
    case Opcode::Metadata:
      return "Metadata";
    case Opcode::MetadataIndex:
      return "MetadataIndex";
    case Opcode::SummaryOffset:
      return "SummaryOffset";
    case Opcode::DataEnd:
      return "DataEnd";
  }
  return "Unknown";
}

Opcode opcode_of(const Record& r) {
  // The variant's alternatives are in opcode order, 0x01 first.
  return static_cast<Opcode>(r.index() + 1);
}

void append_record(Bytes& out, const Record& r) {
  const std::size_t start = out.size();
  out.push_back(static_cast<std::uint8_t>(opcode_of(r)));
  out.resize(out.size() + 8);
  Out o(out);
  std::visit([&](const auto& rec) { append_fields(o, rec); }, r);
  const std::size_t body = start + kRecordPrefix;
  store_u64(out.data() + start + 1, out.size() - body);
  if (const auto* a = std::get_if<Attachment>(&r); a && a->crc == 0) {
    const auto crc = crc32(std::span(out.data() + body, out.size() - body - 4));
    for (int i = 0; i < 4; ++i) out[out.size() - 4 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
  }
}

std::optional<Record> parse_record(std::uint8_t opcode, std::span<const std::uint8_t> body) {
  if (opcode < 0x01 || opcode > 0x0F) return std::nullopt;
  const auto op = static_cast<Opcode>(opcode);
  In in(body, to_string(op));
  if (op == Opcode::Message) {
    Message m;
    m.channel_id = in.u16("channel_id");
    m.sequence = in.u32("sequence");
    m.log_time = in.u64("log_time");
    m.publish_time = in.u64("publish_time");
    m.data.assign(body.begin() + static_cast<std::ptrdiff_t>(in.pos()), body.end());
    return Record(std::move(m));
  }
  Record r = parse(op, in);
  if (auto* a = std::get_if<Attachment>(&r); a && a->crc != 0) {
    const std::size_t fields = in.pos() - 4;  // everything before the crc field
    if (crc32(body.first(fields)) != a->crc) throw FormatError("Attachment record: CRC does not match its data");
  }
  return r;
}

}  // namespace fsd::mcap

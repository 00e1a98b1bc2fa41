#include "common/mcap/linear_reader.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "common/mcap/codec.hpp"
#include "common/mcap/crc32.hpp"

namespace fsd::mcap {

const char* to_string(Issue::Kind k) {
  switch (k) {
    case Issue::Kind::ChunkCrc:
      return "chunk_crc";
    case Issue::Kind::ChunkDamaged:
      return "chunk_damaged";
    case Issue::Kind::BadRecord:
      return "bad_record";
    case Issue::Kind::DataCrc:
      return "data_crc";
    case Issue::Kind::Truncated:
      return "truncated";
  }
  return "?";
}

void check_magic(std::span<const std::uint8_t> file) {
  if (file.empty()) throw McapError("empty file");
  const std::size_t n = std::min<std::size_t>(file.size(), 5);
  if (std::memcmp(file.data(), kMagic.data(), n) != 0)
    throw McapError("not an MCAP file (it does not start with the MCAP magic)");
  if (file.size() < kMagic.size())
    throw McapError("not a complete MCAP file: only " + std::to_string(file.size()) + " bytes");
  const char version = static_cast<char>(file[5]);
  if (version != '0' || file[6] != '\r' || file[7] != '\n') {
    if (version > '0' && version <= '9' && file[6] == '\r' && file[7] == '\n')
      throw McapError(std::string("MCAP format version ") + version +
                      " is newer than this reader's (0): written by a newer MCAP library");
    throw McapError("not an MCAP file (bad magic)");
  }
}

LinearReader::LinearReader(std::span<const std::uint8_t> file, ReaderOptions options) : file_(file), options_(options) {
  check_magic(file_);
  data_crc_ = crc32(file_.first(kMagic.size()));
  pos_ = kMagic.size();
}

void LinearReader::report(Issue::Kind kind, std::uint64_t offset, std::string what) {
  if (options_.strict) throw McapError(what);
  issues_.push_back(Issue{kind, offset, std::move(what)});
}

void LinearReader::truncated(std::uint64_t at, const std::string& why) {
  done_ = true;
  truncated_at_ = at;
  issues_.push_back(Issue{Issue::Kind::Truncated, at, "truncated at offset " + std::to_string(at) + ": " + why});
}

bool LinearReader::open_chunk(const Chunk& chunk, std::uint64_t at) {
  ++compressions_[chunk.compression];
  bool crc_mismatch = false;
  const std::string err = decoder_.decode(chunk, options_, chunk_records_, &crc_mismatch);
  if (!err.empty()) {
    ++chunks_skipped_;
    report(crc_mismatch ? Issue::Kind::ChunkCrc : Issue::Kind::ChunkDamaged, at,
           "chunk at offset " + std::to_string(at) + ": " + err + "; skipped");
    return false;
  }
  ++chunks_read_;
  chunk_next_ = 0;
  chunk_offset_ = at;
  return true;
}

std::optional<RecordAt> LinearReader::next() {
  for (;;) {
    if (chunk_next_ < chunk_records_.size()) {
      RecordAt r{std::move(chunk_records_[chunk_next_++]), chunk_offset_, true};
      if (chunk_next_ == chunk_records_.size()) {
        chunk_records_.clear();
        chunk_next_ = 0;
      }
      return r;
    }
    if (done_) return std::nullopt;

    const std::size_t at = pos_;
    const std::size_t left = file_.size() - at;
    if (left == 0) {
      truncated(at, "the file ends without a footer");
      return std::nullopt;
    }
    if (left < kRecordPrefix) {
      truncated(at, "the file ends inside a record's opcode and length");
      return std::nullopt;
    }
    const std::uint8_t op = file_[at];
    const std::uint64_t len = load_u64(file_.data() + at + 1);
    if (len > left - kRecordPrefix) {
      const auto name = to_string(static_cast<Opcode>(op));
      truncated(at, std::string("the file ends inside a") + (name[0] == 'A' || name[0] == 'U' ? "n " : " ") + name +
                        " record of " + std::to_string(len) + " bytes");
      return std::nullopt;
    }
    const std::size_t size = kRecordPrefix + static_cast<std::size_t>(len);
    const auto whole = file_.subspan(at, size);
    const auto body = whole.subspan(kRecordPrefix);
    pos_ = at + size;

    if (op == static_cast<std::uint8_t>(Opcode::DataEnd) && !data_end_seen_) {
      data_end_seen_ = true;
      try {
        const auto r = parse_record(op, body);
        const auto stored = std::get<DataEnd>(*r).data_section_crc;
        if (options_.verify_crcs && stored != 0 && stored != data_crc_) {
          char buf[128];
          std::snprintf(buf, sizeof buf, "data section CRC mismatch (stored 0x%08x, data gives 0x%08x)", stored,
                        data_crc_);
          report(Issue::Kind::DataCrc, at, "record at offset " + std::to_string(at) + ": " + buf);
        }
        return RecordAt{*r, at, false};
      } catch (const FormatError& e) {
        report(Issue::Kind::BadRecord, at, "record at offset " + std::to_string(at) + ": " + e.what() + "; skipped");
        continue;
      }
    }
    if (!data_end_seen_) data_crc_ = crc32_update(data_crc_, whole);

    std::optional<Record> rec;
    try {
      rec = parse_record(op, body);
    } catch (const FormatError& e) {
      if (op == static_cast<std::uint8_t>(Opcode::Chunk)) {
        ++chunks_skipped_;
        report(Issue::Kind::ChunkDamaged, at, "chunk at offset " + std::to_string(at) + ": " + e.what() + "; skipped");
      } else {
        report(Issue::Kind::BadRecord, at, "record at offset " + std::to_string(at) + ": " + e.what() + "; skipped");
      }
      continue;
    }
    if (!rec) continue;  // unknown opcode: skipped, as the specification says
    if (auto* chunk = std::get_if<Chunk>(&*rec)) {
      open_chunk(*chunk, at);
      continue;
    }
    if (std::holds_alternative<Footer>(*rec)) {
      done_ = true;
      const std::size_t rest = file_.size() - pos_;
      if (rest >= kMagic.size() && std::memcmp(file_.data() + pos_, kMagic.data(), kMagic.size()) == 0) {
        complete_ = true;
      } else {
        truncated(pos_, "the file ends after the footer without the closing magic");
      }
    }
    return RecordAt{std::move(*rec), at, false};
  }
}

}  // namespace fsd::mcap

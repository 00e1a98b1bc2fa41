#include "common/mcap/summary_reader.hpp"

#include <algorithm>
#include <cstring>
#include <tuple>

#include "common/mcap/codec.hpp"
#include "common/mcap/crc32.hpp"
#include "common/mcap/linear_reader.hpp"

namespace fsd::mcap {
namespace {

constexpr std::size_t kFooterRecord = kRecordPrefix + 8 + 8 + 4;

// The record at `at`, which must lie whole inside [at, end); nullopt (with *why) when it does not.
std::optional<std::pair<std::uint8_t, std::span<const std::uint8_t>>> record_at(std::span<const std::uint8_t> file,
                                                                                std::uint64_t at, std::uint64_t end,
                                                                                std::string* why) {
  if (at > end || end > file.size() || end - at < kRecordPrefix) {
    *why = "record at offset " + std::to_string(at) + " lies outside its section";
    return std::nullopt;
  }
  const std::uint64_t len = load_u64(file.data() + at + 1);
  if (len > end - at - kRecordPrefix) {
    *why = "record at offset " + std::to_string(at) + " runs past the end of its section";
    return std::nullopt;
  }
  return std::pair{file[at], file.subspan(static_cast<std::size_t>(at + kRecordPrefix), static_cast<std::size_t>(len))};
}

}  // namespace

std::optional<Summary> read_summary(std::span<const std::uint8_t> file, const ReaderOptions& options,
                                    std::string* why) {
  std::string scratch;
  if (!why) why = &scratch;
  Summary s;
  const std::size_t min_size = kMagic.size() * 2 + kFooterRecord;
  if (file.size() < min_size ||
      std::memcmp(file.data() + file.size() - kMagic.size(), kMagic.data(), kMagic.size()) != 0) {
    *why = "no footer: the file does not end with the MCAP magic (cut off?)";
    return std::nullopt;
  }
  const std::size_t footer_at = file.size() - kMagic.size() - kFooterRecord;
  if (file[footer_at] != static_cast<std::uint8_t>(Opcode::Footer) || load_u64(file.data() + footer_at + 1) != 20) {
    *why = "no footer record before the closing magic";
    return std::nullopt;
  }
  try {
    s.footer = std::get<Footer>(*parse_record(file[footer_at], file.subspan(footer_at + kRecordPrefix, 20)));
    // The header, for its profile: the first record after the magic.
    if (auto h = record_at(file, kMagic.size(), footer_at, why);
        h && h->first == static_cast<std::uint8_t>(Opcode::Header))
      s.header = std::get<Header>(*parse_record(h->first, h->second));
  } catch (const FormatError& e) {
    *why = e.what();
    return std::nullopt;
  }
  if (s.footer.summary_start == 0) {
    *why = "the file has no summary section";
    return std::nullopt;
  }
  if (s.footer.summary_start < kMagic.size() || s.footer.summary_start > footer_at) {
    *why = "the footer's summary start " + std::to_string(s.footer.summary_start) + " lies outside the file";
    return std::nullopt;
  }
  if (options.verify_crcs && s.footer.summary_crc != 0) {
    const auto covered =
        file.subspan(static_cast<std::size_t>(s.footer.summary_start),
                     footer_at + kRecordPrefix + 16 - static_cast<std::size_t>(s.footer.summary_start));
    if (crc32(covered) != s.footer.summary_crc) {
      *why = "summary CRC mismatch";
      return std::nullopt;
    }
  }
  std::uint64_t at = s.footer.summary_start;
  try {
    while (at < footer_at) {
      const auto rec = record_at(file, at, footer_at, why);
      if (!rec) return std::nullopt;
      at += kRecordPrefix + rec->second.size();
      auto r = parse_record(rec->first, rec->second);
      if (!r) continue;
      if (auto* x = std::get_if<Schema>(&*r))
        s.schemas[x->id] = std::move(*x);
      else if (auto* c = std::get_if<Channel>(&*r))
        s.channels[c->id] = std::move(*c);
      else if (auto* st = std::get_if<Statistics>(&*r))
        s.statistics = std::move(*st);
      else if (auto* ci = std::get_if<ChunkIndex>(&*r))
        s.chunk_indexes.push_back(std::move(*ci));
      else if (auto* ai = std::get_if<AttachmentIndex>(&*r))
        s.attachment_indexes.push_back(std::move(*ai));
      else if (auto* mi = std::get_if<MetadataIndex>(&*r))
        s.metadata_indexes.push_back(std::move(*mi));
      else if (auto* so = std::get_if<SummaryOffset>(&*r))
        s.summary_offsets.push_back(*so);
    }
  } catch (const FormatError& e) {
    *why = std::string("summary record at offset ") + std::to_string(at) + ": " + e.what();
    return std::nullopt;
  }
  why->clear();  // a header that did not parse leaves no reason behind when the summary itself is fine
  return s;
}

SummaryReader::SummaryReader(std::span<const std::uint8_t> file, ReaderOptions options)
    : file_(file), options_(options) {
  check_magic(file_);
  summary_ = read_summary(file_, options_, &summary_problem_);
  // The chunk indexes stand for every message only if the statistics (when there are any) count as many chunks.
  indexed_ = summary_ && !summary_->chunk_indexes.empty() &&
             (!summary_->statistics || summary_->statistics->chunk_count == summary_->chunk_indexes.size());
}

void SummaryReader::for_each_message(const std::function<void(const Message&, const Channel&)>& visit) {
  issues_.clear();
  if (indexed_) {
    read_indexed(visit);
  } else {
    read_linear(visit);
  }
}

void SummaryReader::read_indexed(const std::function<void(const Message&, const Channel&)>& visit) {
  std::vector<const ChunkIndex*> order;
  for (const auto& ci : summary_->chunk_indexes) order.push_back(&ci);
  std::stable_sort(order.begin(), order.end(), [](const ChunkIndex* a, const ChunkIndex* b) {
    return std::tie(a->message_start_time, a->chunk_start_offset) <
           std::tie(b->message_start_time, b->chunk_start_offset);
  });
  const std::uint64_t data_end = summary_->footer.summary_start;
  std::vector<Record> records;
  std::vector<const Message*> messages;
  // The summary's channels, and those a chunk defines itself (a summary need not repeat them).
  std::map<std::uint16_t, Channel> channels = summary_->channels;
  for (const ChunkIndex* ci : order) {
    const std::uint64_t at = ci->chunk_start_offset;
    auto fail = [&](Issue::Kind kind, const std::string& what) {
      const std::string msg = "chunk at offset " + std::to_string(at) + ": " + what + "; skipped";
      if (options_.strict) throw McapError(msg);
      issues_.push_back(Issue{kind, at, msg});
    };
    std::string why;
    const auto rec = record_at(file_, at, data_end, &why);
    if (!rec || rec->first != static_cast<std::uint8_t>(Opcode::Chunk) ||
        kRecordPrefix + rec->second.size() != ci->chunk_length) {
      fail(Issue::Kind::ChunkDamaged, "the chunk index does not point at a chunk of its length");
      continue;
    }
    std::optional<Record> chunk;
    try {
      chunk = parse_record(rec->first, rec->second);
    } catch (const FormatError& e) {
      fail(Issue::Kind::ChunkDamaged, e.what());
      continue;
    }
    bool crc_mismatch = false;
    const std::string err = decoder_.decode(std::get<Chunk>(*chunk), options_, records, &crc_mismatch);
    if (!err.empty()) {
      fail(crc_mismatch ? Issue::Kind::ChunkCrc : Issue::Kind::ChunkDamaged, err);
      continue;
    }
    messages.clear();
    for (const auto& r : records) {
      if (const auto* m = std::get_if<Message>(&r)) messages.push_back(m);
      if (const auto* c = std::get_if<Channel>(&r)) channels.try_emplace(c->id, *c);
    }
    std::stable_sort(messages.begin(), messages.end(),
                     [](const Message* a, const Message* b) { return a->log_time < b->log_time; });
    for (const Message* m : messages) {
      const auto ch = channels.find(m->channel_id);
      if (ch != channels.end()) visit(*m, ch->second);
    }
  }
}

void SummaryReader::read_linear(const std::function<void(const Message&, const Channel&)>& visit) {
  LinearReader reader(file_, options_);
  // A summary that is there but not usable for indexing still names channels a damaged chunk may have held.
  std::map<std::uint16_t, Channel> channels;
  if (summary_) channels = summary_->channels;
  while (auto r = reader.next()) {
    if (auto* c = std::get_if<Channel>(&r->record)) {
      channels.try_emplace(c->id, std::move(*c));
    } else if (const auto* m = std::get_if<Message>(&r->record)) {
      const auto ch = channels.find(m->channel_id);
      if (ch != channels.end()) visit(*m, ch->second);
    }
  }
  issues_ = reader.issues();
}

}  // namespace fsd::mcap

#include "common/mcap/inspect.hpp"

#include <algorithm>

#include "common/mcap/linear_reader.hpp"
#include "common/mcap/summary_reader.hpp"

namespace fsd::mcap {

FileInfo inspect(std::span<const std::uint8_t> file) {
  FileInfo info;
  info.file_size = file.size();
  LinearReader reader(file, ReaderOptions{});
  std::map<std::uint16_t, Schema> schemas;
  std::map<std::uint16_t, ChannelInfo> channels;
  bool header_read = false, in_summary = false;
  while (auto r = reader.next()) {
    std::visit(
        [&](auto& rec) {
          using T = std::decay_t<decltype(rec)>;
          if constexpr (std::is_same_v<T, Header>) {
            if (!header_read) info.header = rec;
            header_read = true;
          } else if constexpr (std::is_same_v<T, Schema>) {
            schemas.try_emplace(rec.id, std::move(rec));
          } else if constexpr (std::is_same_v<T, Channel>) {
            ChannelInfo c{rec.id, rec.topic, rec.message_encoding, "", 0};
            if (const auto s = schemas.find(rec.schema_id); s != schemas.end()) c.schema_name = s->second.name;
            channels.try_emplace(rec.id, std::move(c));
          } else if constexpr (std::is_same_v<T, Message>) {
            ++info.messages;
            info.start_time = std::min(info.start_time.value_or(rec.log_time), rec.log_time);
            info.end_time = std::max(info.end_time.value_or(rec.log_time), rec.log_time);
            if (auto c = channels.find(rec.channel_id); c != channels.end()) ++c->second.messages;
          } else if constexpr (std::is_same_v<T, Metadata>) {
            if (!in_summary) info.metadata.push_back(std::move(rec));
          } else if constexpr (std::is_same_v<T, Attachment>) {
            if (!in_summary) info.attachments.push_back({rec.name, rec.media_type, rec.data.size(), rec.log_time});
          } else if constexpr (std::is_same_v<T, DataEnd>) {
            in_summary = true;
          }
        },
        r->record);
  }
  for (auto& [id, c] : channels) info.channels.push_back(std::move(c));
  info.chunks = reader.chunks_read();
  info.chunks_damaged = reader.chunks_skipped();
  info.chunk_compressions = reader.chunk_compressions();
  info.complete = reader.complete();
  info.truncated_at = reader.truncated_at();
  info.issues = reader.issues();
  info.summary_present = read_summary(file, ReaderOptions{}, &info.summary_problem).has_value();
  if (info.summary_present) info.summary_problem.clear();
  return info;
}

}  // namespace fsd::mcap

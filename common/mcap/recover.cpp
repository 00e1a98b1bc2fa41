#include "common/mcap/recover.hpp"

#include <map>

#include "common/mcap/linear_reader.hpp"

namespace fsd::mcap {

RecoverReport recover(std::span<const std::uint8_t> in, ByteSink& out, WriterOptions options, ReaderOptions read) {
  ReaderOptions lenient = read;
  lenient.strict = false;

  // Pass 1: every schema and channel anywhere in the file (the summary repeats them), so messages whose channel
  // record sat in a damaged chunk still find it when the summary survived.
  std::map<std::uint16_t, Schema> schemas;
  std::map<std::uint16_t, Channel> channels;
  std::optional<Header> header;
  {
    LinearReader scan(in, lenient);
    while (auto r = scan.next()) {
      if (auto* h = std::get_if<Header>(&r->record); h && !header) header = *h;
      if (auto* s = std::get_if<Schema>(&r->record); s && s->id != 0) schemas.try_emplace(s->id, std::move(*s));
      if (auto* c = std::get_if<Channel>(&r->record)) channels.try_emplace(c->id, std::move(*c));
    }
  }
  if (!header) throw NothingToRecover("no complete header record: nothing to recover");

  RecoverReport report;
  options.profile = header->profile;
  Writer writer(out, options);
  for (const auto& [id, s] : schemas) {
    writer.add_schema(s);
    ++report.schemas;
  }
  for (auto [id, c] : channels) {
    if (c.schema_id != 0 && !schemas.count(c.schema_id)) {
      c.schema_id = 0;
      ++report.channels_without_schema;
    }
    writer.add_channel(c);
    ++report.channels;
  }

  // Pass 2: the data section's messages, metadata and attachments, in file order.
  LinearReader reader(in, lenient);
  while (auto r = reader.next()) {
    if (std::holds_alternative<DataEnd>(r->record)) break;  // the summary only repeats what came before
    if (const auto* m = std::get_if<Message>(&r->record)) {
      if (!channels.count(m->channel_id)) {
        ++report.messages_without_channel;
        continue;
      }
      writer.write_message(*m);
      ++report.messages;
    } else if (const auto* md = std::get_if<Metadata>(&r->record)) {
      writer.write_metadata(md->name, md->metadata);
      ++report.metadata;
    } else if (auto* a = std::get_if<Attachment>(&r->record)) {
      writer.write_attachment(*a);
      ++report.attachments;
    }
  }
  // A file whose data end was read may still be cut off in its summary: read on to learn where.
  while (reader.next()) {}
  writer.close();
  report.chunks_read = reader.chunks_read();
  report.chunks_lost = reader.chunks_skipped();
  report.input_complete = reader.complete();
  if (reader.truncated_at()) report.bytes_lost = in.size() - *reader.truncated_at();
  report.issues = reader.issues();
  return report;
}

}  // namespace fsd::mcap

// Reads one MCAP file with @mcap/core's own readers and prints what they found as JSON, for tests that check our
// writer against an independent reader:
//   node tests/mcap/mcap_core_read.mjs FILE.mcap
// { "indexed": {header, statistics, channels, schemas, chunk_indexes, metadata, attachments, messages},
//   "stream":  {record_counts, messages} }
// Messages are [channel_id, sequence, log_time, publish_time, data as hex]; 64-bit values as decimal strings.
// Chunk CRCs are validated by both readers (McapIndexedReader.readMessages with validateCrcs, and
// McapStreamReader's default); zstd chunks are decompressed with fzstd. Exits 77 when the packages are missing.
import fs from 'node:fs';
import { mcap, fzstd } from './mcap_core.mjs';

const file = process.argv[2];
const data = new Uint8Array(fs.readFileSync(file));
const decompressHandlers = {
  zstd: (buffer, size) => fzstd.decompress(buffer, new Uint8Array(Number(size))),
};
const hex = (b) => Buffer.from(b).toString('hex');
const message = (m) => [m.channelId, m.sequence, String(m.logTime), String(m.publishTime), hex(m.data)];
const mapOf = (m) => Object.fromEntries([...m].map(([k, v]) => [String(k), String(v)]));

const readable = {
  size: async () => BigInt(data.byteLength),
  read: async (offset, size) => data.subarray(Number(offset), Number(offset + size)),
};
const reader = await mcap.McapIndexedReader.Initialize({ readable, decompressHandlers });
const indexed = {
  header: { profile: reader.header.profile, library: reader.header.library },
  data_section_crc: reader.dataSectionCrc ?? null,
  statistics: reader.statistics && {
    message_count: String(reader.statistics.messageCount),
    schema_count: reader.statistics.schemaCount,
    channel_count: reader.statistics.channelCount,
    attachment_count: reader.statistics.attachmentCount,
    metadata_count: reader.statistics.metadataCount,
    chunk_count: reader.statistics.chunkCount,
    message_start_time: String(reader.statistics.messageStartTime),
    message_end_time: String(reader.statistics.messageEndTime),
    channel_message_counts: mapOf(reader.statistics.channelMessageCounts),
  },
  channels: [...reader.channelsById.values()].map((c) => ({
    id: c.id, schema_id: c.schemaId, topic: c.topic, message_encoding: c.messageEncoding, metadata: mapOf(c.metadata),
  })),
  schemas: [...reader.schemasById.values()].map((s) => ({
    id: s.id, name: s.name, encoding: s.encoding, data: Buffer.from(s.data).toString('utf8'),
  })),
  chunk_indexes: reader.chunkIndexes.length,
  metadata: [],
  attachments: [],
  messages: [],
};
for await (const m of reader.readMetadata()) indexed.metadata.push({ name: m.name, metadata: mapOf(m.metadata) });
for await (const a of reader.readAttachments({ validateCrcs: true }))
  indexed.attachments.push({ name: a.name, media_type: a.mediaType, data: hex(a.data) });
for await (const m of reader.readMessages({ validateCrcs: true })) indexed.messages.push(message(m));

const stream = new mcap.McapStreamReader({ decompressHandlers, validateCrcs: true });
stream.append(data);
const counts = {};
const streamed = [];
for (let r; (r = stream.nextRecord()); ) {
  counts[r.type] = (counts[r.type] ?? 0) + 1;
  if (r.type === 'Message') streamed.push(message(r));
}
if (!stream.done()) throw new Error('McapStreamReader did not reach the end of the file');
console.log(JSON.stringify({ indexed, stream: { record_counts: counts, messages: streamed } }));

// Writes the .mcap file of each conformance variant (../shared/data/mcap-conformance, see its README) with
// @mcap/core, an MCAP implementation independent of ours:
//   node tests/mcap/conformance_write.mjs CONFORMANCE_DIR OUT_DIR
// Each <Base>/<Base>-<features>.json becomes OUT_DIR/<Base>/<Base>-<features>.mcap. The input records are the
// JSON's data records (schemas, channels, messages, attachments, metadata); the file is laid out as the
// variant's features say: chunked or not, with or without message indexes, summary groups, summary offsets and
// padding after each record's fields. Exits 77 when @mcap/core is not installed.
import fs from 'node:fs';
import path from 'node:path';
import { mcap, crc32, crc32Init, crc32Update, crc32Final } from './mcap_core.mjs';

const { McapRecordBuilder, McapChunkBuilder, Opcode } = mcap;
const [inDir, outDir] = process.argv.slice(2);
if (!inDir || !outDir) {
  console.error('usage: conformance_write.mjs CONFORMANCE_DIR OUT_DIR');
  process.exit(2);
}

const bytes = (list) => Uint8Array.from(list.map(Number));
const fieldsOf = (rec) => Object.fromEntries(rec.fields);

// One JSON record of the data section as the @mcap/core record it stands for.
function inputRecord(rec) {
  const f = fieldsOf(rec);
  switch (rec.type) {
    case 'Schema':
      return { type: rec.type, id: Number(f.id), name: f.name, encoding: f.encoding, data: bytes(f.data) };
    case 'Channel':
      return { type: rec.type, id: Number(f.id), schemaId: Number(f.schema_id), topic: f.topic,
               messageEncoding: f.message_encoding, metadata: new Map(Object.entries(f.metadata)) };
    case 'Message':
      return { type: rec.type, channelId: Number(f.channel_id), sequence: Number(f.sequence),
               logTime: BigInt(f.log_time), publishTime: BigInt(f.publish_time), data: bytes(f.data) };
    case 'Attachment':
      return { type: rec.type, name: f.name, logTime: BigInt(f.log_time), createTime: BigInt(f.create_time),
               mediaType: f.media_type, data: bytes(f.data) };
    case 'Metadata':
      return { type: rec.type, name: f.name, metadata: new Map(Object.entries(f.metadata)) };
    default:
      return undefined;  // header, data end and the summary are laid out below, not copied
  }
}

function writeVariant(json) {
  const features = new Set(json.meta.variant.features);
  const header = fieldsOf(json.records[0]);
  const dataEnd = json.records.findIndex((r) => r.type === 'DataEnd');
  const inputs = json.records.slice(1, dataEnd).map(inputRecord).filter(Boolean);

  const b = new McapRecordBuilder({ padRecords: features.has('pad') });
  b.writeMagic();
  b.writeHeader({ profile: header.profile, library: header.library });
  const chunk = features.has('ch') ? new McapChunkBuilder({ useMessageIndex: features.has('mx') }) : undefined;

  const stats = { messageCount: 0n, schemaCount: 0, channelCount: 0, attachmentCount: 0, metadataCount: 0,
                  chunkCount: chunk ? 1 : 0, messageStartTime: undefined, messageEndTime: undefined,
                  channelMessageCounts: new Map() };
  const metadataIndexes = [], attachmentIndexes = [], chunkIndexes = [];
  for (const r of inputs) {
    if (r.type === 'Schema') {
      stats.schemaCount++;
      chunk ? chunk.addSchema(r) : b.writeSchema(r);
    } else if (r.type === 'Channel') {
      stats.channelCount++;
      chunk ? chunk.addChannel(r) : b.writeChannel(r);
    } else if (r.type === 'Message') {
      stats.messageCount++;
      stats.channelMessageCounts.set(r.channelId, (stats.channelMessageCounts.get(r.channelId) ?? 0n) + 1n);
      if (stats.messageStartTime === undefined || r.logTime < stats.messageStartTime) stats.messageStartTime = r.logTime;
      if (stats.messageEndTime === undefined || r.logTime > stats.messageEndTime) stats.messageEndTime = r.logTime;
      chunk ? chunk.addMessage(r) : b.writeMessage(r);
    } else if (r.type === 'Attachment') {
      stats.attachmentCount++;
      const offset = BigInt(b.length);
      const length = b.writeAttachment(r);
      if (features.has('ax')) {
        attachmentIndexes.push({ offset, length, logTime: r.logTime, createTime: r.createTime,
                                 dataSize: BigInt(r.data.byteLength), name: r.name, mediaType: r.mediaType });
      }
    } else if (r.type === 'Metadata') {
      stats.metadataCount++;
      const offset = BigInt(b.length);
      const length = b.writeMetadata(r);
      if (features.has('mdx')) metadataIndexes.push({ offset, length, name: r.name });
    }
  }
  if (chunk) {
    const chunkStartOffset = BigInt(b.length);
    const size = BigInt(chunk.buffer.byteLength);
    const chunkLength = b.writeChunk({ compression: '', messageStartTime: chunk.messageStartTime,
                                       messageEndTime: chunk.messageEndTime, uncompressedCrc: crc32(chunk.buffer),
                                       uncompressedSize: size, records: chunk.buffer });
    const messageIndexOffsets = new Map();
    let messageIndexLength = 0n;
    for (const index of chunk.indices) {
      messageIndexOffsets.set(index.channelId, BigInt(b.length));
      messageIndexLength += b.writeMessageIndex(index);
    }
    if (features.has('chx')) {
      chunkIndexes.push({ compression: '', messageStartTime: chunk.messageStartTime,
                          messageEndTime: chunk.messageEndTime, uncompressedSize: size, compressedSize: size,
                          chunkStartOffset, chunkLength, messageIndexLength, messageIndexOffsets });
    }
  }
  b.writeDataEnd({ dataSectionCrc: crc32(b.buffer) });

  // The summary: groups in the order the specification's writers use, each remembered for its summary offset.
  const summaryStart = BigInt(b.length);
  const groups = [];
  const group = (opcode, writeAll) => {
    const start = BigInt(b.length);
    writeAll();
    const length = BigInt(b.length) - start;
    if (length !== 0n) groups.push({ groupOpcode: opcode, groupStart: start, groupLength: length });
  };
  group(Opcode.SCHEMA, () => {
    if (features.has('rsh')) for (const r of inputs) if (r.type === 'Schema') b.writeSchema(r);
  });
  group(Opcode.CHANNEL, () => {
    if (features.has('rch')) for (const r of inputs) if (r.type === 'Channel') b.writeChannel(r);
  });
  group(Opcode.STATISTICS, () => {
    if (features.has('st')) {
      b.writeStatistics({ ...stats, messageStartTime: stats.messageStartTime ?? 0n,
                          messageEndTime: stats.messageEndTime ?? 0n });
    }
  });
  group(Opcode.METADATA_INDEX, () => metadataIndexes.forEach((r) => b.writeMetadataIndex(r)));
  group(Opcode.ATTACHMENT_INDEX, () => attachmentIndexes.forEach((r) => b.writeAttachmentIndex(r)));
  group(Opcode.CHUNK_INDEX, () => chunkIndexes.forEach((r) => b.writeChunkIndex(r)));
  const hasSummary = BigInt(b.length) !== summaryStart;
  let summaryOffsetStart = 0n;
  if (features.has('sum')) {
    summaryOffsetStart = BigInt(b.length);
    for (const g of groups) b.writeSummaryOffset(g);
  }

  // The summary CRC: from the summary's start through the footer's summary_offset_start field.
  const footer = { summaryStart: hasSummary ? summaryStart : 0n, summaryOffsetStart };
  const footerHead = new DataView(new ArrayBuffer(1 + 8 + 8 + 8));
  footerHead.setUint8(0, Opcode.FOOTER);
  footerHead.setBigUint64(1, 20n, true);
  footerHead.setBigUint64(9, footer.summaryStart, true);
  footerHead.setBigUint64(17, footer.summaryOffsetStart, true);
  const buf = b.buffer;
  let crc = crc32Init();
  crc = crc32Update(crc, buf.subarray(Number(summaryStart)));
  crc = crc32Update(crc, new Uint8Array(footerHead.buffer));
  b.writeFooter({ ...footer, summaryCrc: crc32Final(crc) });
  b.writeMagic();
  return b.buffer;
}

let written = 0;
for (const base of fs.readdirSync(inDir).sort()) {
  const dir = path.join(inDir, base);
  if (!fs.statSync(dir).isDirectory()) continue;
  fs.mkdirSync(path.join(outDir, base), { recursive: true });
  for (const name of fs.readdirSync(dir).filter((n) => n.endsWith('.json')).sort()) {
    const json = JSON.parse(fs.readFileSync(path.join(dir, name), 'utf8'));
    fs.writeFileSync(path.join(outDir, base, name.replace(/\.json$/, '.mcap')), writeVariant(json));
    written++;
  }
}
console.log(`wrote ${written} conformance files to ${outDir}`);

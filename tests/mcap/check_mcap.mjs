// Reads an MCAP file with independent readers and prints what they found as JSON:
// the reference TypeScript reader (@mcap/core) both ways, streaming every record with
// CRC checks and seeking through the summary and chunk indexes; the data section's and
// the summary's CRC-32 recomputed (@foxglove/crc); every message decoded from its
// channel's ros2msg schema (@foxglove/rosmsg parses it, @foxglove/rosmsg2-serialization
// decodes the CDR) and required to end exactly where its bytes end. Byte fields over
// 4 KiB (images) print as {bytes, crc32}.
//   node tests/mcap/check_mcap.mjs FILE.mcap   (modules from NODE_PATH or beside it)
import { readFile } from "node:fs/promises";
import { createRequire } from "node:module";
import path from "node:path";

const require = createRequire(path.resolve(process.env.TRACKBED_NPM_DIR ?? ".", "node_modules"));
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { loadDecompressHandlers } = require("@mcap/support");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");
const { crc32 } = require("@foxglove/crc");

const bytes = new Uint8Array(await readFile(process.argv[2]));
const decompressHandlers = await loadDecompressHandlers();
const problems = [];

// Streaming: every record in file order, chunk CRCs checked.
const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
stream.append(bytes);
const streamed = {};
let record;
while ((record = stream.nextRecord()) !== undefined) {
  streamed[record.type] = (streamed[record.type] ?? 0) + 1;
}
if (!stream.done()) problems.push("the stream reader did not reach the end magic");

// Seeking: the summary, the chunk indexes and the message indexes.
const readable = {
  size: async () => BigInt(bytes.length),
  read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
};
const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
const dataCrc = crc32(bytes.subarray(0, Number(reader.dataEndOffset)));
if (reader.dataSectionCrc !== dataCrc) problems.push(`data section CRC ${reader.dataSectionCrc} != ${dataCrc}`);
const summaryEnd = bytes.length - 8 - 4;  // the Footer's CRC, then the magic
const summaryCrc = crc32(bytes.subarray(Number(reader.footer.summaryStart), summaryEnd));
if (reader.footer.summaryCrc !== summaryCrc) problems.push(`summary CRC ${reader.footer.summaryCrc} != ${summaryCrc}`);

const decoders = new Map();
for (const [id, channel] of reader.channelsById) {
  const schema = reader.schemasById.get(channel.schemaId);
  decoders.set(id, new MessageReader(parse(new TextDecoder().decode(schema.data), { ros2: true })));
}
const channels = {};
for (const [id, channel] of reader.channelsById) {
  const schema = reader.schemasById.get(channel.schemaId);
  channels[channel.topic] = {
    schema: schema.name, schemaEncoding: schema.encoding, messageEncoding: channel.messageEncoding,
    metadata: Object.fromEntries(channel.metadata), count: 0, first: null, last: null,
    lastLogTimeNs: null, sequenceOk: true,
  };
}
let previous = -1n;
for await (const m of reader.readMessages({ validateCrcs: true })) {
  const c = channels[reader.channelsById.get(m.channelId).topic];
  const decoder = decoders.get(m.channelId);
  const message = decoder.readMessage(m.data);
  if (decoder.lastReadHadTrailingBytes()) problems.push(`trailing bytes in a message on ${c.schema}`);
  if (m.logTime < previous) problems.push("messages out of time order");
  previous = m.logTime;
  if (m.sequence !== c.count) c.sequenceOk = false;
  if (c.count === 0) c.first = message;
  c.last = message;
  c.lastLogTimeNs = m.logTime.toString();
  c.count += 1;
}
const s = reader.statistics;
console.log(JSON.stringify({
  problems,
  header: reader.header,
  streamed,
  statistics: s && {
    messageCount: Number(s.messageCount), schemaCount: s.schemaCount, channelCount: s.channelCount,
    chunkCount: s.chunkCount, startNs: s.messageStartTime.toString(), endNs: s.messageEndTime.toString(),
    channelMessageCounts: Object.fromEntries([...s.channelMessageCounts].map(([k, v]) => [k, Number(v)])),
  },
  chunkIndexes: reader.chunkIndexes.length,
  channels,
}, (key, value) => (typeof value === "bigint" ? value.toString()
  // Large byte fields (images) as their length and CRC-32, small ones element by element.
  : value instanceof Uint8Array && value.length > 4096 ? { bytes: value.length, crc32: crc32(value) }
  : ArrayBuffer.isView(value) ? Array.from(value) : value), 1));

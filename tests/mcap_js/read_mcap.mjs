#!/usr/bin/env node
// An independent reader for uampc's MCAP files: Foxglove's own @mcap/core opens the
// file with its indexed reader (footer, summary and its CRC, chunk indexes, message indexes, chunk
// CRCs), decompresses chunks with @mcap/support's zstd and lz4, parses every ros2msg schema with
// @foxglove/rosmsg and decodes every CDR message with @foxglove/rosmsg2-serialization. A second
// pass reads the file from start to end with @mcap/core's stream reader, which parses every record
// (message indexes, summary, footer and trailing magic included) and must find as many messages.
//
//   node read_mcap.mjs FILE.mcap
//
// Prints one JSON line per message, {"topic", "log_time", "publish_time", "sequence", "message"},
// in log-time order, then one summary line {"summary": {...}}. 64-bit integers are printed as
// strings, typed arrays as arrays, non-finite floats as "NaN"/"Infinity"/"-Infinity". Exits 1 on
// any failure (a file or message that does not decode, a count that disagrees with the summary).
import { open } from "node:fs/promises";

import { parse } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { loadDecompressHandlers } from "@mcap/support";

// @mcap/core's IReadable over a file handle.
function fileReadable(handle, size) {
  return {
    size: async () => BigInt(size),
    read: async (offset, length) => {
      const buffer = new Uint8Array(Number(length));
      const { bytesRead } = await handle.read(buffer, 0, buffer.length, Number(offset));
      if (bytesRead !== buffer.length) throw new Error(`short read at byte ${offset}`);
      return buffer;
    },
  };
}

function toJson(value) {
  return JSON.stringify(value, (_key, v) => {
    if (typeof v === "bigint") return v.toString();
    if (typeof v === "number" && !Number.isFinite(v)) return String(v);
    if (ArrayBuffer.isView(v) && !(v instanceof DataView)) return Array.from(v);
    return v;
  });
}

// Every record of the file in order, fed in pieces; returns the number of Message records.
async function countMessagesStreaming(handle, size, decompressHandlers) {
  const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  const piece = new Uint8Array(1 << 20);
  let messages = 0n;
  for (let offset = 0; offset < size; ) {
    const { bytesRead } = await handle.read(piece, 0, piece.length, offset);
    if (bytesRead === 0) throw new Error(`short read at byte ${offset}`);
    stream.append(piece.slice(0, bytesRead));
    offset += bytesRead;
    for (let record; (record = stream.nextRecord()); ) {
      if (record.type === "Message") ++messages;
    }
  }
  if (!stream.done()) throw new Error("the stream reader did not reach the footer and trailing magic");
  return messages;
}

// One decoder per channel; refuses anything that is not a ROS 2 channel (ros2msg schema, CDR).
function makeDecoders(reader) {
  const decoders = new Map();
  for (const channel of reader.channelsById.values()) {
    const schema = reader.schemasById.get(channel.schemaId);
    if (!schema) throw new Error(`channel ${channel.topic} has no schema`);
    if (schema.encoding !== "ros2msg") throw new Error(`channel ${channel.topic}: schema encoding ${schema.encoding}`);
    if (channel.messageEncoding !== "cdr") {
      throw new Error(`channel ${channel.topic}: message encoding ${channel.messageEncoding}`);
    }
    const definitions = parse(new TextDecoder().decode(schema.data), { ros2: true });
    decoders.set(channel.id, { topic: channel.topic, type: schema.name, reader: new MessageReader(definitions) });
  }
  return decoders;
}

// Decodes one message; CDR may end in up to 3 padding bytes, which the encapsulation header's
// options (low 2 bits of its last byte) declare: more trailing bytes mean the schema is wrong.
function decode(decoder, data) {
  const message = decoder.reader.readMessage(data);
  const trailing = data.byteLength - decoder.reader.lastReadByteLength();
  const padding = data.byteLength >= 4 ? data[3] & 0x3 : 0;
  if (trailing > padding) {
    throw new Error(`${decoder.topic} (${decoder.type}): ${trailing} bytes left after decoding the message`);
  }
  return message;
}

async function main(path) {
  const handle = await open(path, "r");
  try {
    const { size } = await handle.stat();
    const decompressHandlers = await loadDecompressHandlers();
    const reader = await McapIndexedReader.Initialize({ readable: fileReadable(handle, size), decompressHandlers });
    const decoders = makeDecoders(reader);
    const perTopic = {};
    let count = 0n;
    for await (const record of reader.readMessages()) {
      const decoder = decoders.get(record.channelId);
      const message = decode(decoder, record.data);
      process.stdout.write(
        toJson({
          topic: decoder.topic,
          log_time: record.logTime,
          publish_time: record.publishTime,
          sequence: record.sequence,
          message,
        }) + "\n",
      );
      perTopic[decoder.topic] = (perTopic[decoder.topic] ?? 0) + 1;
      ++count;
    }
    const stats = reader.statistics;
    if (stats && stats.messageCount !== count) {
      throw new Error(`read ${count} messages, the file's statistics say ${stats.messageCount}`);
    }
    const streamed = await countMessagesStreaming(handle, size, decompressHandlers);
    if (streamed !== count) throw new Error(`the stream reader finds ${streamed} messages, the indexed one ${count}`);
    process.stdout.write(
      toJson({
        summary: {
          profile: reader.header.profile,
          library: reader.header.library,
          messages: count,
          chunks: reader.chunkIndexes.length,
          topics: perTopic,
        },
      }) + "\n",
    );
  } finally {
    await handle.close();
  }
}

if (process.argv.length !== 3) {
  process.stderr.write("usage: node read_mcap.mjs FILE.mcap\n");
  process.exit(2);
}
main(process.argv[2]).catch((error) => {
  process.stderr.write(`read_mcap: ${process.argv[2]}: ${error?.stack ?? error}\n`);
  process.exit(1);
});

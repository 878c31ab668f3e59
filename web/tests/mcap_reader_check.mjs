#!/usr/bin/env node
// Reads an MCAP file with @mcap/core, the reader of Foxglove's own tools, twice: by index
// (footer, summary, chunk indexes: how viewers seek) and as a stream (every record in file
// order, CRCs checked). Prints what it found as JSON; exits 1 when either reader rejects the
// file, when the two disagree, or when a "json" message does not parse.
//
//   node web/tests/mcap_reader_check.mjs FILE.mcap
//   import { checkMcap } from "./mcap_reader_check.mjs";  // the same, on bytes

import { readFile } from "node:fs/promises";
import { pathToFileURL } from "node:url";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { decompress } from "fzstd";

const decompressHandlers = {
  zstd: (buffer, decompressedSize) => {
    const out = decompress(buffer, new Uint8Array(Number(decompressedSize)));
    if (out.byteLength !== Number(decompressedSize)) {
      throw new Error(`zstd gave ${out.byteLength} bytes, the chunk claims ${decompressedSize}`);
    }
    return out;
  },
};

const num = (big) => Number(big);
const textDecoder = new TextDecoder("utf-8", { fatal: true });

function countMessage(result, channel, message) {
  result.messageCount += 1;
  result.perChannel[channel.topic] = (result.perChannel[channel.topic] ?? 0) + 1;
  if (channel.messageEncoding === "json") {
    try {
      JSON.parse(textDecoder.decode(message.data));
    } catch (error) {
      result.undecodable.push(`${channel.topic} sequence ${message.sequence}: ${error.message}`);
    }
  }
}

async function readIndexed(bytes) {
  const readable = {
    size: async () => BigInt(bytes.byteLength),
    read: async (offset, size) => bytes.subarray(num(offset), num(offset + size)),
  };
  const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
  const result = {
    profile: reader.header.profile,
    library: reader.header.library,
    schemas: [...reader.schemasById.values()].map((s) => ({
      id: s.id,
      name: s.name,
      encoding: s.encoding,
      dataBytes: s.data.byteLength,
    })),
    channels: [...reader.channelsById.values()].map((c) => ({
      id: c.id,
      schemaId: c.schemaId,
      topic: c.topic,
      messageEncoding: c.messageEncoding,
      metadata: Object.fromEntries(c.metadata),
    })),
    messageCount: 0,
    perChannel: {},
    metadata: [],
    chunkCount: reader.chunkIndexes.length,
    statistics: reader.statistics && {
      messageCount: num(reader.statistics.messageCount),
      schemaCount: reader.statistics.schemaCount,
      channelCount: reader.statistics.channelCount,
      attachmentCount: reader.statistics.attachmentCount,
      metadataCount: reader.statistics.metadataCount,
      chunkCount: reader.statistics.chunkCount,
      messageStartTime: String(reader.statistics.messageStartTime),
      messageEndTime: String(reader.statistics.messageEndTime),
      channelMessageCounts: Object.fromEntries(
        [...reader.statistics.channelMessageCounts].map(([id, n]) => [id, num(n)]),
      ),
    },
    undecodable: [],
  };
  let previousLogTime = -1n;
  const sequences = new Map();
  for await (const message of reader.readMessages()) {
    const channel = reader.channelsById.get(message.channelId);
    if (message.logTime < previousLogTime) throw new Error("indexed messages out of log-time order");
    previousLogTime = message.logTime;
    const expected = (sequences.get(message.channelId) ?? 0) + 1;
    if (message.sequence !== expected) {
      throw new Error(`${channel.topic}: sequence ${message.sequence}, expected ${expected}`);
    }
    sequences.set(message.channelId, expected);
    countMessage(result, channel, message);
  }
  for await (const metadata of reader.readMetadata()) result.metadata.push(metadata.name);
  return result;
}

function readStream(bytes) {
  const reader = new McapStreamReader({ decompressHandlers, includeChunks: true });
  reader.append(bytes);
  const channels = new Map();
  const result = { messageCount: 0, perChannel: {}, metadata: [], chunkCount: 0, undecodable: [] };
  let record;
  while ((record = reader.nextRecord())) {
    if (record.type === "Channel") channels.set(record.id, record);
    else if (record.type === "Message") countMessage(result, channels.get(record.channelId), record);
    else if (record.type === "Metadata") result.metadata.push(record.name);
    else if (record.type === "Chunk") result.chunkCount += 1;
  }
  if (!reader.done()) throw new Error(`stream reader: ${reader.bytesRemaining()} bytes unread`);
  return result;
}

// What both readers found: { ok, problems, profile, library, schemas, channels, messageCount,
// perChannel, metadata, chunkCount, statistics, undecodable, stream }. For a Node test to import.
export async function checkMcap(bytes) {
  const problems = [];
  let indexed;
  let stream;
  try {
    indexed = await readIndexed(bytes);
  } catch (error) {
    problems.push(`McapIndexedReader: ${error.message}`);
  }
  try {
    stream = readStream(bytes);
  } catch (error) {
    problems.push(`McapStreamReader: ${error.message}`);
  }
  if (indexed && stream) {
    for (const key of ["messageCount", "perChannel", "chunkCount"]) {
      if (JSON.stringify(indexed[key]) !== JSON.stringify(stream[key])) {
        problems.push(`indexed and stream readers differ in ${key}`);
      }
    }
    const sorted = (names) => JSON.stringify([...names].sort());
    if (sorted(indexed.metadata) !== sorted(stream.metadata)) {
      problems.push("indexed and stream readers differ in metadata");
    }
    if (indexed.statistics && indexed.statistics.messageCount !== indexed.messageCount) {
      problems.push(
        `statistics count ${indexed.statistics.messageCount} messages, read ${indexed.messageCount}`,
      );
    }
  }
  for (const result of [indexed, stream]) {
    if (result?.undecodable.length) problems.push(...result.undecodable.slice(0, 5));
  }
  return { ok: problems.length === 0, problems, ...indexed, stream };
}

if (process.argv[1] && import.meta.url === pathToFileURL(process.argv[1]).href) {
  const path = process.argv[2];
  if (!path) {
    console.error("usage: mcap_reader_check.mjs FILE.mcap");
    process.exit(2);
  }
  const result = await checkMcap(new Uint8Array(await readFile(path)));
  console.log(JSON.stringify(result, null, 2));
  process.exit(result.ok ? 0 : 1);
}

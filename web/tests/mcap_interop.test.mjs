// A mission's MCAP file read by readers nobody here wrote: @mcap/core's indexed reader (footer,
// summary, chunk indexes: how Foxglove seeks) and its stream reader (every record in file order),
// zstd chunks decompressed by fzstd. The counts are checked against the database (sqlite3), every
// message is decoded and validated with ajv against its channel's advertised JSON Schema, and
// Foxglove's well-known schemas are compared with @foxglove/schemas. Then the file goes back in
// with `avk import mcap`.
//
// Environment: AVK_BINARY (default build/server/avk). Needs the sqlite3 command (scripts/setup).
import { test, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { McapIndexedReader, McapStreamReader } from '@mcap/core';
import { decompress } from 'fzstd';

import { startAvkServer, stopAvkServer } from './avk_server.mjs';
import { slow } from './wait.mjs';

const require = createRequire(import.meta.url);
const AjvModule = require('ajv');
const Ajv = AjvModule.default ?? AjvModule;
const foxgloveSchemas = require('@foxglove/schemas/jsonschema');

const here = path.dirname(fileURLToPath(import.meta.url));
const repo = path.resolve(here, '../..');
const AVK = path.resolve(process.env.AVK_BINARY || path.join(repo, 'build/server/avk'));
const tmp = mkdtempSync(path.join(tmpdir(), 'avk-mcap-interop-'));
after(() => rmSync(tmp, { recursive: true, force: true }));

// A few turns on a wide region: enough for every channel, quick on the simulator.
const MISSION = {
  name: 'mcap interop',
  turn_array: { speeds_mps: [1.0], dheadings_deg: [45, 90], repeats: 2 },
  operating_region: { polygon_m: [[-100, -100], [100, -100], [100, 100], [-100, 100]], buffer_m: 25, return_point_m: [0, -70] },
};

const decompressHandlers = {
  zstd: (buffer, decompressedSize) => decompress(buffer, new Uint8Array(Number(decompressedSize))),
};
const utf8 = new TextDecoder('utf-8', { fatal: true });

function avk(args) {
  return execFileSync(AVK, args, { encoding: 'utf8', timeout: slow(120000) });
}

function sql(db, query) {
  return execFileSync('sqlite3', [db, query], { encoding: 'utf8' }).trim();
}

function dbCounts(db, mission) {
  const n = (table) => Number(sql(db, `SELECT count(*) FROM ${table} WHERE mission_id = ${mission}`));
  return { nav: n('nav_samples'), turns: n('turns'), events: n('mission_events'), conditionSets: n('condition_sets') };
}

async function readIndexed(bytes) {
  const readable = {
    size: async () => BigInt(bytes.byteLength),
    read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
  };
  const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
  const messages = [];
  for await (const m of reader.readMessages()) messages.push(m);
  const metadata = [];
  for await (const m of reader.readMetadata()) metadata.push(m);
  return { reader, messages, metadata };
}

function readStream(bytes) {
  const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  reader.append(bytes);
  const records = [];
  let r;
  while ((r = reader.nextRecord())) records.push(r);
  assert.ok(reader.done(), `the stream reader left ${reader.bytesRemaining()} bytes`);
  return records;
}

const db = path.join(tmp, 'station.db');
let missionId;
let vehicleId;

test('a simulated mission is flown into a database', { timeout: slow(180000) }, () => {
  const missionFile = path.join(tmp, 'mission.json');
  writeFileSync(missionFile, JSON.stringify(MISSION));
  avk(['mission', 'run', '--config', missionFile, '--db', db, '--sim', '--quiet']);
  missionId = Number(sql(db, 'SELECT max(id) FROM missions'));
  vehicleId = sql(db, `SELECT vehicle_id FROM missions WHERE id = ${missionId}`);
  const c = dbCounts(db, missionId);
  assert.ok(c.nav > 100 && c.turns >= 4 && c.events > 0, JSON.stringify(c));
});

test('the CLI export (zstd) reads with both @mcap/core readers and matches the database', { timeout: slow(120000) }, async () => {
  const file = path.join(tmp, 'mission.mcap');
  const out = avk(['mission', 'export', String(missionId), '--db', db, '--out', file]);
  assert.match(out, new RegExp(`wrote mission ${missionId} to .*mission\\.mcap: \\d+ bytes \\(zstd\\)`));
  const bytes = new Uint8Array(readFileSync(file));
  const counts = dbCounts(db, missionId);

  const { reader, messages, metadata } = await readIndexed(bytes);
  assert.equal(reader.header.profile, '');
  assert.match(reader.header.library, /^avk-station/);
  assert.ok(reader.chunkIndexes.length >= 1, 'chunk indexes in the summary');
  assert.ok(reader.chunkIndexes.every((c) => c.compression === 'zstd'));
  assert.ok(reader.chunkIndexes.every((c) => c.messageIndexOffsets.size > 0), 'message indexes for every chunk');
  const stats = reader.statistics;
  assert.ok(stats, 'a statistics record');
  assert.equal(Number(stats.messageCount), messages.length);
  assert.equal(stats.channelCount, reader.channelsById.size);
  assert.equal(stats.chunkCount, reader.chunkIndexes.length);

  const topics = new Map([...reader.channelsById.values()].map((c) => [c.topic, c]));
  const perTopic = (kind) => {
    const ch = topics.get(`/${vehicleId}/${kind}`);
    assert.ok(ch, `channel /${vehicleId}/${kind}`);
    return Number(stats.channelMessageCounts.get(ch.id) ?? 0n);
  };
  for (const kind of ['pose', 'tf', 'navigation']) assert.equal(perTopic(kind), counts.nav, kind);
  assert.equal(perTopic('turn'), counts.turns);
  assert.equal(perTopic('turn_record'), counts.turns);
  assert.equal(perTopic('log'), counts.events);
  assert.equal(perTopic('region'), 1);
  assert.equal(topics.has(`/${vehicleId}/location`), false, 'no location without a datum');
  assert.equal(messages.length, 3 * counts.nav + 2 * counts.turns + counts.events + 1);

  // Log-time order, sequences counting per channel.
  const sequences = new Map();
  for (let i = 0; i < messages.length; i++) {
    if (i > 0) assert.ok(messages[i - 1].logTime <= messages[i].logTime, `message ${i} out of order`);
    const next = (sequences.get(messages[i].channelId) ?? 0) + 1;
    assert.equal(messages[i].sequence, next);
    sequences.set(messages[i].channelId, next);
  }

  // Every message decodes and validates against its channel's schema; Foxglove's schemas are
  // the package's own.
  const ajv = new Ajv({ strict: false, allErrors: true });
  const validators = new Map();
  for (const s of reader.schemasById.values()) {
    assert.equal(s.encoding, 'jsonschema');
    const schema = JSON.parse(utf8.decode(s.data));
    if (s.name.startsWith('foxglove.')) {
      const known = foxgloveSchemas[s.name.slice('foxglove.'.length)];
      assert.ok(known, `@foxglove/schemas has ${s.name}`);
      assert.deepEqual(schema, known, `${s.name} is Foxglove's`);
    }
    validators.set(s.id, ajv.compile(schema));
  }
  for (const m of messages) {
    const ch = reader.channelsById.get(m.channelId);
    assert.equal(ch.messageEncoding, 'json');
    const value = JSON.parse(utf8.decode(m.data));
    const validate = validators.get(ch.schemaId);
    assert.ok(validate(value), `${ch.topic} sequence ${m.sequence}: ${ajv.errorsText(validate.errors)}`);
  }

  // The metadata records an import needs.
  const names = metadata.map((m) => m.name).sort();
  assert.deepEqual(names.filter((n) => n !== 'avk.current'), ['avk.condition_sets', 'avk.mission', 'avk.vehicle']);
  const mission = metadata.find((m) => m.name === 'avk.mission').metadata;
  assert.equal(mission.get('avk_mcap_version'), '1');
  assert.equal(Number(mission.get('id')), missionId);
  assert.equal(JSON.parse(metadata.find((m) => m.name === 'avk.condition_sets').metadata.get('json')).length, counts.conditionSets);

  // The stream reader sees the same messages in the same order.
  const records = readStream(bytes);
  const streamed = records.filter((r) => r.type === 'Message');
  assert.equal(streamed.length, messages.length);
  streamed.forEach((m, i) => {
    assert.equal(m.channelId, messages[i].channelId);
    assert.equal(m.logTime, messages[i].logTime);
  });
  assert.equal(records.filter((r) => r.type === 'Metadata').length, metadata.length);
});

test('the REST export (uncompressed) is a download the readers take, and 404/400 as documented', { timeout: slow(60000) }, async () => {
  const serve = await startAvkServer(AVK, ['serve', '--db', db, '--port', '0']);
  try {
    const res = await fetch(`${serve.base}/api/v1/missions/${missionId}/export?format=mcap&compression=none`);
    assert.equal(res.status, 200);
    assert.equal(res.headers.get('content-type'), 'application/vnd.mcap');
    assert.equal(res.headers.get('content-disposition'), `attachment; filename="mission-${missionId}.mcap"`);
    const bytes = new Uint8Array(await res.arrayBuffer());
    const { reader, messages } = await readIndexed(bytes);
    assert.ok(reader.chunkIndexes.every((c) => c.compression === ''));
    assert.equal(messages.length, Number(reader.statistics.messageCount));
    assert.equal(readStream(bytes).filter((r) => r.type === 'Message').length, messages.length);

    const missing = await fetch(`${serve.base}/api/v1/missions/999999/export?format=mcap`);
    assert.equal(missing.status, 404);
    const csv = await fetch(`${serve.base}/api/v1/missions/${missionId}/export?format=csv`);
    assert.equal(csv.status, 400);
    assert.match(await csv.text(), /format/);
  } finally {
    await stopAvkServer(serve);
  }
});

test('`avk import mcap` brings the mission into another database with the same counts', { timeout: slow(60000) }, () => {
  const file = path.join(tmp, 'mission.mcap');
  const target = path.join(tmp, 'imported.db');
  const out = avk(['import', 'mcap', file, '--db', target]);
  const id = Number(out.match(/as mission (\d+)/)[1]);
  assert.deepEqual(dbCounts(target, id), dbCounts(db, missionId));
  assert.equal(sql(target, `SELECT name, status FROM missions WHERE id = ${id}`), sql(db, `SELECT name, status FROM missions WHERE id = ${missionId}`));
});

// The Foxglove WebSocket connection tested with a client nobody here wrote: the FoxgloveClient of
// the pinned @foxglove/ws-protocol package, over the `ws` package, against a real
// `avk serve --sim` flying a short mission. Payloads are validated with ajv against the schema
// each channel advertises, and Foxglove's well-known schemas against @foxglove/schemas itself.
// Run with `node --test web/tests/foxglove_interop.test.mjs` (CTest: web_foxglove_interop).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { slow, until } from './wait.mjs';
import { startAvkServer, stopAvkServer } from './avk_server.mjs';

const require = createRequire(import.meta.url);
const { FoxgloveClient } = require('@foxglove/ws-protocol');
const WebSocket = require('ws');
const Ajv = require('ajv');
const foxgloveSchemas = require('@foxglove/schemas/jsonschema');

const here = path.dirname(fileURLToPath(import.meta.url));
const repo = path.resolve(here, '../..');
const AVK = path.resolve(process.env.AVK_BINARY || path.join(repo, 'build/server/avk'));
const VEHICLE = 'sim-usim';
const tmp = mkdtempSync(path.join(tmpdir(), 'avk-foxglove-'));
let server = null;

const MISSION = {
  name: 'foxglove interop',
  turn_array: { speeds_mps: [1.0], dheadings_deg: [60, 120] },
  operating_region: { polygon_m: [[-80, -80], [80, -80], [80, 80], [-80, 80]], buffer_m: 12, return_point_m: [0, 0] },
};

before(async () => {
  // With a datum the simulated vehicle is placed on the earth: the location channel has fixes.
  server = await startAvkServer(AVK, ['serve', '--db', path.join(tmp, 'station.db'), '--sim', '--datum', '42.358456,-71.087589', '--realtime-factor', '40', '--port', '0']);
});

after(async () => {
  await stopAvkServer(server);
  rmSync(tmp, { recursive: true, force: true });
});

/** A FoxgloveClient on a fresh connection, with what it received so far. */
function connect(pathname = '/api/v1/foxglove', options = {}) {
  const ws = new WebSocket(`ws://127.0.0.1:${server.port}${pathname}`, [FoxgloveClient.SUPPORTED_SUBPROTOCOL], options);
  const client = new FoxgloveClient({ ws });
  const got = { ws, client, serverInfo: null, channels: new Map(), statuses: [], messages: [], times: 0, closed: null, errors: [] };
  client.on('serverInfo', (i) => (got.serverInfo = i));
  client.on('advertise', (chs) => chs.forEach((c) => got.channels.set(c.id, c)));
  client.on('unadvertise', (ids) => ids.forEach((id) => got.channels.delete(id)));
  client.on('status', (s) => got.statuses.push(s));
  client.on('message', (m) => got.messages.push(m));
  client.on('time', () => got.times++);
  client.on('close', (e) => (got.closed = e));
  client.on('error', (e) => got.errors.push(e));
  return got;
}

function channelByTopic(got, suffix) {
  return [...got.channels.values()].find((c) => c.topic === `/${VEHICLE}/${suffix}`);
}

test('a FoxgloveClient receives server info, the channels and valid messages while a mission runs', { timeout: slow(240000) }, async () => {
  const got = connect();
  await until('server info and channels', () => got.serverInfo && got.channels.size >= 7, 10000, 50);
  assert.equal(got.ws.protocol, 'foxglove.websocket.v1');
  assert.ok(got.serverInfo.capabilities.includes('time'), JSON.stringify(got.serverInfo));
  assert.match(got.serverInfo.sessionId, /^[0-9a-f]{16}$/);

  // Every channel is JSON with a JSON Schema; Foxglove's well-known ones are the package's own.
  const ajv = new Ajv({ strict: false, allErrors: true });
  const validators = new Map();
  for (const ch of got.channels.values()) {
    assert.equal(ch.encoding, 'json', ch.topic);
    assert.equal(ch.schemaEncoding, 'jsonschema', ch.topic);
    const schema = JSON.parse(ch.schema);
    if (ch.schemaName.startsWith('foxglove.')) {
      const name = ch.schemaName.slice('foxglove.'.length);
      assert.deepEqual(schema, foxgloveSchemas[name], `${ch.topic}: the advertised ${ch.schemaName} is @foxglove/schemas' own`);
    }
    validators.set(ch.id, { topic: ch.topic, validate: ajv.compile(schema) });
  }
  for (const suffix of ['pose', 'tf', 'navigation', 'turn', 'region', 'log'])
    assert.ok(channelByTopic(got, suffix), `a /${VEHICLE}/${suffix} channel is advertised`);
  assert.equal(channelByTopic(got, 'pose').schemaName, 'foxglove.PoseInFrame');
  assert.equal(channelByTopic(got, 'turn').schemaName, 'foxglove.SceneUpdate');
  assert.equal(channelByTopic(got, 'log').schemaName, 'foxglove.Log');

  // The layout docs/foxglove.md offers names only what the station advertises, and its plots
  // only members of the navigation schema.
  const layout = JSON.parse(readFileSync(path.join(repo, 'docs/foxglove-layout.json'), 'utf8'));
  const topics = new Set([...got.channels.values()].map((c) => c.topic));
  const navFields = Object.keys(JSON.parse(channelByTopic(got, 'navigation').schema).properties);
  for (const [panel, config] of Object.entries(layout.configById)) {
    const named = [
      ...Object.keys(config.topics ?? {}),
      ...(config.paths ?? []).map((p) => p.value.split('.')[0]),
      ...[config.topicToRender, config.topicPath].filter(Boolean),
    ];
    for (const t of named) assert.ok(topics.has(t), `${panel} names ${t}, which is not advertised`);
    for (const p of config.paths ?? []) assert.ok(navFields.includes(p.value.split('.')[1]), `${panel}: ${p.value}`);
  }

  // Subscribe to pose and navigation first, then to the rest.
  const topicOfSub = new Map();
  const subscribe = (ch) => topicOfSub.set(got.client.subscribe(ch.id), ch);
  subscribe(channelByTopic(got, 'pose'));
  subscribe(channelByTopic(got, 'navigation'));
  await until('pose and navigation messages', () => got.messages.length >= 4, 10000, 50);
  for (const ch of got.channels.values()) if (![...topicOfSub.values()].includes(ch)) subscribe(ch);

  const res = await fetch(`${server.base}/api/v1/vehicles/${VEHICLE}/missions`, {
    method: 'POST',
    headers: { Authorization: `Bearer ${server.token}`, 'Content-Type': 'application/json' },
    body: JSON.stringify(MISSION),
  });
  const started = await res.text();
  assert.equal(res.status, 201, started);
  const missionId = JSON.parse(started).id;

  const decoded = (m) => JSON.parse(new TextDecoder().decode(m.data));
  const on = (suffix) => got.messages.filter((m) => topicOfSub.get(m.subscriptionId)?.topic === `/${VEHICLE}/${suffix}`);
  await until('the mission to finish', async () => {
    const r = await fetch(`${server.base}/api/v1/missions/${missionId}`);
    return r.ok && (await r.json()).status === 'done';
  }, 180000, 500);
  await until('a finished turn scene and the logs', () => on('turn').some((m) => decoded(m).entities.some((e) => e.metadata.some((kv) => kv.key === 'state' && kv.value === 'finished'))) && on('log').length > 0, 20000, 100);

  // Every message decodes and validates against its channel's schema.
  for (const m of got.messages) {
    const v = validators.get(topicOfSub.get(m.subscriptionId)?.id);
    assert.ok(v, `message on an unknown subscription ${m.subscriptionId}`);
    const payload = decoded(m);
    assert.ok(v.validate(payload), `${v.topic}: ${ajv.errorsText(v.validate.errors)}\n${JSON.stringify(payload).slice(0, 400)}`);
    // The binary timestamp is the station clock, the message's own timestamp where it has one.
    if (payload.timestamp) assert.equal(m.timestamp, BigInt(payload.timestamp.sec) * 1000000000n + BigInt(payload.timestamp.nsec), v.topic);
  }
  assert.ok(got.times > 0, 'time messages (capability "time") arrive');

  // The navigation carries the helm's command while the mission runs, and poses agree with it.
  const nav = on('navigation').map(decoded);
  assert.ok(nav.some((n) => n.mission_id === missionId && n.desired_heading_deg !== null && typeof n.helm_mode === 'string'), 'navigation with the mission, desired heading and helm mode');
  // The fixes lie within the region's 80 m of the datum (0.001 deg of latitude is 111 m).
  const fixes = on('location').map(decoded);
  assert.ok(fixes.length > 0, 'location fixes with the datum');
  assert.ok(fixes.every((f) => Math.abs(f.latitude - 42.358456) < 0.001 && Math.abs(f.longitude + 71.087589) < 0.0015), JSON.stringify(fixes[0]));
  // The region: its boundary loop and the buffer inside it.
  const region = decoded(on('region').at(-1));
  const lines = region.entities[0].lines;
  assert.equal(lines[0].type, 1, 'the boundary is a closed loop');
  assert.equal(lines[0].points.length, 4);
  assert.ok(lines[1].points.every((p) => Math.abs(p.x) <= 80 - 12 + 1e-6 && Math.abs(p.y) <= 80 - 12 + 1e-6), 'the buffer line lies 12 m inside');
  // A turn scene has the goal, the measured track and the instantaneous prediction; the second
  // turn also has the table's (built from the first), with its corridor.
  const scenes = on('turn').map(decoded);
  const ids = new Set(scenes.flatMap((s) => s.entities.map((e) => e.id)));
  for (const id of ['turn/goal', 'turn/measured', 'turn/instantaneous', 'turn/cell']) assert.ok(ids.has(id), `turn scenes have ${id}: ${[...ids]}`);
  assert.ok(ids.has('turn/avk'), `a turn scene with the table's prediction: ${[...ids]}`);
  // Mission events arrive as logs and as status messages.
  const logs = on('log').map(decoded);
  assert.ok(logs.some((l) => /done/.test(l.message)), `a log says the mission is done: ${logs.map((l) => l.message)}`);
  assert.ok(got.statuses.some((s) => /done/.test(s.message)), 'and a status message');
  assert.equal(got.errors.length, 0, got.errors.map(String).join('\n'));
  got.ws.close();
});

test('subscribing to an unknown channel gets an error status, and the connection stays usable', { timeout: slow(30000) }, async () => {
  const got = connect();
  await until('channels', () => got.channels.size >= 7, 10000, 50);
  got.ws.send(JSON.stringify({ op: 'subscribe', subscriptions: [{ id: 7, channelId: 4242 }] }));
  got.ws.send('not json');
  got.ws.send(JSON.stringify({ op: 'getParameters', parameterNames: [] }));
  await until('three error statuses', () => got.statuses.filter((s) => s.level === 2).length >= 3, 10000, 50);
  const errors = got.statuses.filter((s) => s.level === 2).map((s) => s.message);
  assert.match(errors[0], /unknown channel id 4242/);
  assert.match(errors[1], /JSON object with an "op"/);
  assert.match(errors[2], /unsupported operation 'getParameters'/);
  assert.equal(got.closed, null, 'the connection is still open');
  got.client.subscribe(channelByTopic(got, 'pose').id);
  await until('a pose after the errors', () => got.messages.length > 0, 10000, 50);
  got.ws.close();
});

test('the Foxglove connection keeps the stream\'s Origin rule, and the stream is unchanged', { timeout: slow(30000) }, async () => {
  const foreign = new WebSocket(`ws://127.0.0.1:${server.port}/api/v1/foxglove`, ['foxglove.websocket.v1'], { origin: 'http://evil.example' });
  const status = await new Promise((resolve) => {
    foreign.on('unexpected-response', (_req, res) => resolve(res.statusCode));
    foreign.on('open', () => resolve('open'));
    foreign.on('error', () => {});
  });
  assert.equal(status, 403);
  // Without the subprotocol the Foxglove path explains itself.
  const bare = new WebSocket(`ws://127.0.0.1:${server.port}/api/v1/foxglove`);
  const bareStatus = await new Promise((resolve) => {
    bare.on('unexpected-response', (_req, res) => resolve(res.statusCode));
    bare.on('open', () => resolve('open'));
    bare.on('error', () => {});
  });
  assert.equal(bareStatus, 400);
  // On the stream's path, the subprotocol selects the Foxglove protocol ...
  const viaStream = connect('/api/v1/stream');
  await until('server info on the stream path', () => viaStream.serverInfo, 10000, 50);
  viaStream.ws.close();
  // ... and without it the stream says hello as before.
  const plain = new WebSocket(`ws://127.0.0.1:${server.port}/api/v1/stream`);
  const hello = await new Promise((resolve, reject) => {
    plain.on('message', (d) => resolve(JSON.parse(d.toString())));
    plain.on('error', reject);
  });
  assert.equal(hello.type, 'hello');
  plain.close();
});

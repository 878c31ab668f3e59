// The live Foxglove connection's added cost: `avk serve --sim` flying the thesis' Figure 4-1
// mission at real time x K, first with no Foxglove client (baseline), then with N clients (the
// pinned @foxglove/ws-protocol FoxgloveClient over `ws`) subscribed to every channel. A benchmark,
// not a test: the figures go to docs/foxglove.md.
//
//   node web/bench/foxglove_load.mjs [--clients 20] [--factor 20] [--seconds 20]
//
// Measured per phase: the server's CPU (utime + stime from /proc/<pid>/stat) per wall second,
// how fast the station clock advanced against the wall (the realtime factor the vehicle loop
// held), messages and bytes each client received, and the delivery lag of the pose channel
// (receive wall time minus the station-clock stamp, offset to its minimum: how much later than the
// fastest delivery a message arrives). Environment: AVK_BINARY (default build/server/avk).

import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';

import { startAvkServer, stopAvkServer } from '../tests/avk_server.mjs';
import { sleep } from '../tests/wait.mjs';

const require = createRequire(import.meta.url);
const { FoxgloveClient } = require('@foxglove/ws-protocol');
const WebSocket = require('ws');

const here = path.dirname(fileURLToPath(import.meta.url));
const repo = path.resolve(here, '../..');
const AVK = path.resolve(process.env.AVK_BINARY || path.join(repo, 'build/server/avk'));
const { values } = parseArgs({
  options: { clients: { type: 'string', default: '20' }, factor: { type: 'string', default: '20' }, seconds: { type: 'string', default: '20' } },
});
const CLIENTS = Number(values.clients);
const FACTOR = Number(values.factor);
const SECONDS = Number(values.seconds);
const TICKS_PER_S = 100; // sysconf(_SC_CLK_TCK) on Linux

function cpuSeconds(pid) {
  const fields = readFileSync(`/proc/${pid}/stat`, 'utf8').split(') ')[1].split(' ');
  return (Number(fields[11]) + Number(fields[12])) / TICKS_PER_S; // utime, stime
}

async function stationClock(base) {
  const r = await fetch(`${base}/api/v1/vehicles/sim-usim`);
  const v = await r.json();
  return v.nav?.t_s ?? v.t_s;
}

async function phase(server, clients) {
  const cpu0 = cpuSeconds(server.child.pid);
  const t0 = await stationClock(server.base);
  const w0 = performance.now();
  for (const c of clients) c.reset();
  await sleep(SECONDS * 1000);
  const wall = (performance.now() - w0) / 1000;
  const t1 = await stationClock(server.base);
  const cpu = cpuSeconds(server.child.pid) - cpu0;
  const out = { clients: clients.length, wall_s: +wall.toFixed(1), server_cpu_per_wall_s: +(cpu / wall).toFixed(3), realtime_factor_held: +((t1 - t0) / wall).toFixed(1) };
  if (clients.length) {
    const msgs = clients.map((c) => c.messages);
    const bytes = clients.map((c) => c.bytes);
    const lags = clients.flatMap((c) => c.lags);
    const min = Math.min(...lags);
    const rel = lags.map((l) => l - min).sort((a, b) => a - b);
    const q = (p) => rel[Math.min(rel.length - 1, Math.floor(p * rel.length))];
    out.messages_per_client_per_s = +(msgs.reduce((a, b) => a + b, 0) / clients.length / wall).toFixed(0);
    out.kbytes_per_client_per_s = +(bytes.reduce((a, b) => a + b, 0) / clients.length / wall / 1024).toFixed(1);
    out.pose_lag_ms = { p50: +q(0.5).toFixed(1), p99: +q(0.99).toFixed(1), max: +rel.at(-1).toFixed(1) };
    out.closed = clients.filter((c) => c.closed).length;
  }
  return out;
}

function foxgloveClient(port) {
  return new Promise((resolve) => {
    const ws = new WebSocket(`ws://127.0.0.1:${port}/api/v1/foxglove`, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
    const client = new FoxgloveClient({ ws });
    const c = { ws, messages: 0, bytes: 0, lags: [], closed: false, poseSub: null, wall0: null, reset() { this.messages = 0; this.bytes = 0; this.lags = []; } };
    client.on('advertise', (channels) => {
      for (const ch of channels) {
        const id = client.subscribe(ch.id);
        if (ch.topic.endsWith('/pose')) c.poseSub = id;
      }
      resolve(c);
    });
    client.on('message', (m) => {
      c.messages++;
      c.bytes += m.data.byteLength + 13;
      // Station clock runs FACTOR times faster than the wall: compare both in wall milliseconds.
      if (m.subscriptionId === c.poseSub) c.lags.push(performance.now() - Number(m.timestamp) / 1e6 / FACTOR);
    });
    client.on('close', () => (c.closed = true));
  });
}

const tmp = mkdtempSync(path.join(tmpdir(), 'avk-foxglove-load-'));
const server = await startAvkServer(AVK, ['serve', '--db', path.join(tmp, 'station.db'), '--sim', '--realtime-factor', String(FACTOR), '--port', '0']);
try {
  const mission = JSON.parse(readFileSync(path.join(repo, 'examples/thesis-fig4-1.json'), 'utf8'));
  const res = await fetch(`${server.base}/api/v1/vehicles/sim-usim/missions`, {
    method: 'POST',
    headers: { Authorization: `Bearer ${server.token}`, 'Content-Type': 'application/json' },
    body: JSON.stringify(mission),
  });
  if (res.status !== 201) throw new Error(`mission start: ${res.status} ${await res.text()}`);
  await sleep(2000);
  const baseline = await phase(server, []);
  const clients = await Promise.all(Array.from({ length: CLIENTS }, () => foxgloveClient(server.port)));
  await sleep(1000);
  const loaded = await phase(server, clients);
  for (const c of clients) c.ws.close();
  console.log(JSON.stringify({ factor: FACTOR, baseline, loaded, added_server_cpu_per_wall_s: +(loaded.server_cpu_per_wall_s - baseline.server_cpu_per_wall_s).toFixed(3) }, null, 2));
} finally {
  await stopAvkServer(server);
  rmSync(tmp, { recursive: true, force: true });
}

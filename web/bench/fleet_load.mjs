// A station with a fleet and AIS traffic under load: `avk serve --vehicles` with 10 simulated M200
// catamarans at real time x10, each flying a small collection mission, watching 50 simulated AIS
// contacts through a real gpsd (fed over UDP by `avk traffic`). A benchmark, not a test: the
// figures go to docs/fleet-load.md.
//
//   node web/bench/fleet_load.mjs [--seconds 30] [--vehicles 10] [--contacts 50] [--factor 10]
//                                 [--skip-browser] [--json]
//
// Two windows of --seconds wall each, with a stream client (/api/v1/stream, topic nav) and a
// Foxglove client (/api/v1/foxglove, every vehicle's /<vid>/pose) connected throughout:
//   A. the clients only;
//   B. the same, with the dashboard open on the Live view in Debian's Chromium (playwright-core).
// Measured in each: per vehicle, how fast its station clock advanced against the wall (from its
// nav messages, and from GET /vehicles at the window's ends) and its nav message rate on the
// stream; the delivery lag of the stream's nav and of Foxglove's pose (receive wall time minus the
// vehicle's station-clock stamp / factor, offset per vehicle to its minimum: how much later than
// that vehicle's fastest delivery a message arrives); the CPU (utime + stime from /proc/<pid>/stat
// per wall second) of the server, gpsd, `avk traffic` and (in B) Chromium, and the server's RSS.
// After the windows, each mission's stored track over them: whether the loops made every 10 Hz
// sample, so that a sample a client missed is known to be a delivery drop. In B also the page's
// frame intervals (requestAnimationFrame), long tasks, Live plot updates, and when its own
// stream's nav messages reach its main thread (a listener added to the page's WebSocket).
//
// Environment: AVK_BINARY (default build/server/avk), AVK_CHROMIUM (default /usr/bin/chromium),
// AVK_GPSD (default /usr/sbin/gpsd).

import { spawn } from 'node:child_process';
import { createSocket } from 'node:dgram';
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { cpus, loadavg, tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';

import { apiRequest, startAvkServer, stopAvkServer, freeLoopbackPort } from '../tests/avk_server.mjs';
import { launchChromium } from '../tests/browser.mjs';
import { sleep, until } from '../tests/wait.mjs';

const require = createRequire(import.meta.url);
const { FoxgloveClient } = require('@foxglove/ws-protocol');
const WebSocket = require('ws');

const here = path.dirname(fileURLToPath(import.meta.url));
const webDir = path.resolve(here, '..');
const repo = path.resolve(webDir, '..');
const AVK = path.resolve(process.env.AVK_BINARY || path.join(repo, 'build/server/avk'));
const CHROMIUM = process.env.AVK_CHROMIUM || '/usr/bin/chromium';
const GPSD = process.env.AVK_GPSD || '/usr/sbin/gpsd';
const DATUM = { lat_deg: 42.358456, lon_deg: -71.087589 }; // examples/traffic-charles.json's
const SPACING_M = 300;
const TICKS_PER_S = 100; // sysconf(_SC_CLK_TCK) on Linux
const PAGE_SIZE = 4096;

const { values } = parseArgs({
  options: {
    seconds: { type: 'string', default: '30' },
    vehicles: { type: 'string', default: '10' },
    contacts: { type: 'string', default: '50' },
    factor: { type: 'string', default: '10' },
    'skip-browser': { type: 'boolean', default: false },
    json: { type: 'boolean', default: false },
  },
});
const SECONDS = Number(values.seconds);
const VEHICLES = Number(values.vehicles);
const CONTACTS = Number(values.contacts);
const FACTOR = Number(values.factor);
if (!(SECONDS > 0) || !(VEHICLES >= 1 && VEHICLES <= 99) || !(CONTACTS >= 1) || !(FACTOR > 0)) {
  console.error('usage: node web/bench/fleet_load.mjs [--seconds S > 0] [--vehicles 1-99] [--contacts N ≥ 1] [--factor K > 0] [--skip-browser] [--json]');
  process.exit(2);
}

// ---------------------------------------------------------------------------------------------
// The fleet, its missions and the traffic

const vid = (i) => `v${String(i + 1).padStart(2, '0')}`;
const startX = (i) => (i - (VEHICLES - 1) / 2) * SPACING_M; // centred on the datum, 300 m apart
const START_Y = -70;

function fleetFile() {
  const sim = path.join(repo, 'examples/sim-choppy.json');
  return {
    vehicles: Array.from({ length: VEHICLES }, (_, i) => ({
      id: vid(i),
      vehicle: 'catamaran:m200',
      sim_config: sim,
      seed: i + 1,
      start: { x_m: startX(i), y_m: START_Y, heading_deg: 0 },
    })),
  };
}

/** As examples/fleet-missions/*.json: a 200 m square about the vehicle, back to its start. A turn
 *  of this array takes some 18 s of station time with its ConditionSet, so enough repeats that
 *  every mission still runs at the end of the second window, whatever --seconds (25 for 30 s at
 *  x10: 150 turns, some 4 minutes of wall time). */
const REPEATS = Math.min(100, Math.max(2, Math.ceil(((2 * SECONDS + 90) * FACTOR) / 60)));
function mission(i) {
  const x = startX(i);
  return {
    name: `bench-${vid(i)}`,
    kind: 'turns',
    turn_array: { speeds_mps: [1.0, 1.5], dheadings_deg: [30, 60, 90], direction: 'alternate', repeats: REPEATS },
    condition_set: { speed_tolerance_mps: 0.1, max_yaw_rate_dps: 1.0, window: 5 },
    constant_heading: { completion_threshold_deg: 5 },
    operating_region: {
      polygon_m: [[x - 100, -100], [x + 100, -100], [x + 100, 100], [x - 100, 100]],
      buffer_m: 25,
      return_point_m: [x, START_Y],
    },
  };
}

/** CONTACTS vessels over the fleet's area (x ±(spread), y -600…600): every other one on a closed
 *  circuit of four waypoints about a point beside the fleet, the rest on straight courses across
 *  it; Class A and B alternating, distinct MMSIs, names. */
function trafficScenario() {
  const half = ((VEHICLES - 1) / 2) * SPACING_M + 200;
  const A_TYPES = [52, 60, 70, 30];
  const B_TYPES = [36, 37];
  const contacts = [];
  for (let k = 0; k < CONTACTS; k++) {
    const classA = k % 2 === 0;
    const n = String(k + 1).padStart(2, '0');
    const c = {
      mmsi: (classA ? 367100000 : 338100000) + k + 1,
      name: `${classA ? 'BENCH TUG' : 'BENCH LAUNCH'} ${n}`,
      class: classA ? 'A' : 'B',
      ship_type: classA ? A_TYPES[k % A_TYPES.length] : B_TYPES[k % B_TYPES.length],
      speed_mps: 1.0 + (k % 5) * 0.5,
    };
    const u = (k + 0.5) / CONTACTS; // spread along x
    const x = -half + u * 2 * half;
    if (k % 4 < 2) {
      // A circuit of 120 m × 80 m north or south of the fleet's line.
      const y = k % 8 < 4 ? 250 : -350;
      c.waypoints = [[x - 60, y - 40], [x + 60, y - 40], [x + 60, y + 40], [x - 60, y + 40]];
    } else {
      // Across the line from 600 m north or south, a little off the meridian.
      const north = k % 8 < 6;
      c.start = [x, north ? 600 : -600];
      c.course_deg = ((north ? 180 : 0) + ((k % 3) - 1) * 15 + 360) % 360;
      c.speed_mps = 0.5 + (k % 3) * 0.25; // slow: x10 for the run's minutes stays within a few km
    }
    contacts.push(c);
  }
  return { datum: DATUM, contacts };
}

// ---------------------------------------------------------------------------------------------
// Processes


function freeUdpPort() {
  return new Promise((resolve, reject) => {
    const s = createSocket('udp4');
    s.on('error', reject);
    s.bind(0, '127.0.0.1', () => {
      const { port } = s.address();
      s.close(() => resolve(port));
    });
  });
}

const children = []; // every process started here: killed at the end, whatever happens

/** A child process whose output is kept (the last 20 kB) and drained, so a full pipe never blocks. */
function startChild(cmd, args) {
  const child = spawn(cmd, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  const p = { child, log: '', exited: null };
  const keep = (chunk) => (p.log = (p.log + chunk.toString()).slice(-20000));
  child.stdout.on('data', keep);
  child.stderr.on('data', keep);
  child.on('exit', (code, sig) => (p.exited = { code, sig }));
  child.on('error', (e) => (p.exited = { error: e.message }));
  children.push(p);
  return p;
}

async function stopChild(p) {
  if (!p || p.exited) return;
  const exited = new Promise((r) => p.child.once('exit', r));
  p.child.kill('SIGTERM');
  if (!(await Promise.race([exited.then(() => true), sleep(5000).then(() => false)]))) {
    p.child.kill('SIGKILL');
    await Promise.race([exited, sleep(3000)]);
  }
}

let tmpDir = null; // removed at the end, or here on an interrupted run
process.on('exit', () => {
  for (const p of children) if (!p.exited) p.child.kill('SIGKILL');
  if (tmpDir) rmSync(tmpDir, { recursive: true, force: true });
});
for (const sig of ['SIGINT', 'SIGTERM']) process.on(sig, () => process.exit(130));

function cpuSeconds(pid) {
  const fields = readFileSync(`/proc/${pid}/stat`, 'utf8').split(') ')[1].split(' ');
  return (Number(fields[11]) + Number(fields[12])) / TICKS_PER_S; // utime, stime
}

/** Every process below `root` (by /proc's parent links) but those in `except`: Chromium's. */
function descendants(root, except) {
  const parent = new Map();
  for (const d of readdirSync('/proc')) {
    if (!/^\d+$/.test(d)) continue;
    try {
      parent.set(Number(d), Number(readFileSync(`/proc/${d}/stat`, 'utf8').split(') ')[1].split(' ')[1]));
    } catch {
      // gone meanwhile
    }
  }
  const out = [];
  for (const pid of parent.keys()) {
    let p = pid;
    while (p > 1 && p !== root && !except.has(p)) p = parent.get(p) ?? 0;
    if (p === root && pid !== root && !except.has(pid)) out.push(pid);
  }
  return out;
}

/** CPU seconds of processes by pid, those gone meanwhile left out. */
function cpuOf(pids) {
  const m = new Map();
  for (const pid of pids) {
    try {
      m.set(pid, cpuSeconds(pid));
    } catch {
      // gone
    }
  }
  return m;
}

function rssMiB(pid) {
  const pages = Number(readFileSync(`/proc/${pid}/statm`, 'utf8').split(' ')[1]);
  return (pages * PAGE_SIZE) / 2 ** 20;
}

// ---------------------------------------------------------------------------------------------
// Figures

function percentile(sorted, p) {
  if (sorted.length === 0) return NaN;
  const i = Math.min(sorted.length - 1, Math.max(0, Math.ceil((p / 100) * sorted.length) - 1));
  return sorted[i];
}

function dist(values) {
  const s = [...values].sort((a, b) => a - b);
  return { n: s.length, min: s[0] ?? NaN, p50: percentile(s, 50), p95: percentile(s, 95), p99: percentile(s, 99), max: s.at(-1) ?? NaN };
}

/** min / median / max over vehicles. */
function spread(values) {
  const s = [...values].sort((a, b) => a - b);
  return { min: s[0] ?? NaN, median: percentile(s, 50), max: s.at(-1) ?? NaN };
}

/** Per vehicle [recvMs, stampS] pairs → lag above that vehicle's fastest delivery, pooled; and
 *  the drift: the median lag of the window's last wall second minus that of its first (a
 *  client falling further and further behind shows a growing one). */
function lags(byVehicle) {
  const all = [];
  const first = [];
  const last = [];
  for (const samples of byVehicle.values()) {
    if (samples.length === 0) continue;
    const raw = samples.map(([recv, stamp]) => recv - (stamp * 1000) / FACTOR);
    const min = Math.min(...raw);
    const r0 = samples[0][0];
    const r1 = samples.at(-1)[0];
    samples.forEach(([recv], i) => {
      const l = raw[i] - min;
      all.push(l);
      if (recv - r0 < 1000) first.push(l);
      if (r1 - recv < 1000) last.push(l);
    });
  }
  return { ...dist(all), drift: dist(last).p50 - dist(first).p50 };
}

/** Per vehicle: station seconds per wall second over its samples (least squares), how many a wall
 *  second; and over all, the station-clock intervals between a vehicle's successive samples (a
 *  10 Hz loop's are 0.1 s: a longer one is a sample the loop or the delivery skipped). */
function rates(byVehicle, wallS) {
  const factor = [];
  const perS = [];
  const steps = [];
  for (const samples of byVehicle.values()) {
    perS.push(samples.length / wallS);
    for (let i = 1; i < samples.length; i++) steps.push(samples[i][1] - samples[i - 1][1]);
    if (samples.length < 2) continue;
    const n = samples.length;
    const mx = samples.reduce((a, [r]) => a + r, 0) / n;
    const my = samples.reduce((a, [, t]) => a + t, 0) / n;
    let sxy = 0;
    let sxx = 0;
    for (const [r, t] of samples) {
      sxy += (r - mx) * (t - my);
      sxx += (r - mx) ** 2;
    }
    factor.push((sxy / sxx) * 1000);
  }
  const skipped = steps.filter((d) => d > 0.15).length;
  return { factor: spread(factor), perS: spread(perS), vehicles: byVehicle.size, step_s: { max: Math.max(...steps), over_0_15_s: skipped, share_over_0_15_s: skipped / Math.max(1, steps.length), backwards: steps.filter((d) => d <= 0).length } };
}

// ---------------------------------------------------------------------------------------------
// Clients

function streamClient(server) {
  return new Promise((resolve, reject) => {
    const ws = new WebSocket(`ws://127.0.0.1:${server.port}/api/v1/stream`, { headers: { Authorization: `Bearer ${server.token}` } });
    const c = { ws, recording: false, nav: new Map(), closed: false, bytes: 0 };
    ws.on('open', () => ws.send(JSON.stringify({ subscribe: ['nav'] })));
    ws.on('message', (data) => {
      const now = performance.now();
      const msg = JSON.parse(data.toString());
      if (msg.type === 'subscribed') resolve(c);
      if (msg.type === 'error') reject(new Error(`stream: ${msg.message}`));
      if (msg.topic !== 'nav' || !c.recording) return;
      c.bytes += data.length;
      const v = msg.data.vehicle_id;
      if (!c.nav.has(v)) c.nav.set(v, []);
      c.nav.get(v).push([now, msg.data.t_s]);
    });
    ws.on('close', () => (c.closed = true));
    ws.on('error', reject);
  });
}

function foxgloveClient(server) {
  const ws = new WebSocket(`ws://127.0.0.1:${server.port}/api/v1/foxglove`, [FoxgloveClient.SUPPORTED_SUBPROTOCOL], {
    headers: { Authorization: `Bearer ${server.token}` },
  });
  const client = new FoxgloveClient({ ws });
  const c = { ws, recording: false, topics: new Set(), subs: new Map(), pose: new Map(), closed: false };
  client.on('advertise', (channels) => {
    for (const ch of channels) {
      c.topics.add(ch.topic);
      const m = ch.topic.match(/^\/([^/]+)\/pose$/);
      if (m) c.subs.set(client.subscribe(ch.id), m[1]);
    }
  });
  client.on('message', (m) => {
    const now = performance.now();
    const v = c.subs.get(m.subscriptionId);
    if (!c.recording || v === undefined) return;
    if (!c.pose.has(v)) c.pose.set(v, []);
    c.pose.get(v).push([now, Number(m.timestamp) / 1e9]);
  });
  client.on('close', () => (c.closed = true));
  return c;
}

// ---------------------------------------------------------------------------------------------
// The dashboard

async function openDashboard(browser, server, contacts) {
  const page = await (await browser.newContext()).newPage();
  await page.setViewportSize({ width: 1280, height: 800 });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  // A tap on the page's own stream: when each nav message reaches the page's main thread (the
  // listener runs just before the page's), recorded only inside the window.
  await page.addInitScript(() => {
    const Native = window.WebSocket;
    const tap = { rec: false, count: 0, nav: {} };
    window.__fleetBench = tap;
    window.WebSocket = class extends Native {
      constructor(url, protocols) {
        super(url, protocols);
        if (!String(url).includes('/api/v1/stream')) return;
        this.addEventListener('message', (ev) => {
          if (!tap.rec) return;
          const now = performance.now();
          tap.count++;
          const m = JSON.parse(ev.data);
          if (m.topic === 'nav') (tap.nav[m.data.vehicle_id] ??= []).push([now, m.data.t_s]);
        });
      }
    };
  });
  await page.goto(`${server.base}/?token=${server.token}&test=1#live`, { waitUntil: 'load', timeout: 60000 });
  const shown = await until(
    `the Live map to draw ${VEHICLES} vehicles and ${contacts} AIS contacts`,
    () =>
      page.evaluate(() => {
        if (!window.avkTest || !document.querySelector('#live-plot .main-svg')) return null;
        const v = window.avkTest.liveVehicles();
        const ais = document.getElementById('live-plot')?.data?.find((d) => String(d.name).startsWith('AIS'));
        return { vehicles: (v.selected ? 1 : 0) + v.others.length, ais: ais?.x?.length ?? 0 };
      }).then((s) => (s && s.vehicles >= VEHICLES && s.ais >= contacts ? s : null)),
    30000,
    500,
  ).catch(async (e) => {
    // Measure anyway, and say what was drawn.
    const s = await page.evaluate(() => {
      const v = window.avkTest?.liveVehicles();
      const ais = document.getElementById('live-plot')?.data?.find((d) => String(d.name).startsWith('AIS'));
      return { vehicles: v ? (v.selected ? 1 : 0) + v.others.length : 0, ais: ais?.x?.length ?? 0, error: e.message };
    });
    return s;
  });
  return { page, shown, errors };
}

function measureFrames(page, seconds) {
  return page.evaluate(async (s) => {
    const frames = [];
    const longTasks = [];
    let observer = null;
    const longTaskSupported = PerformanceObserver.supportedEntryTypes?.includes('longtask') ?? false;
    if (longTaskSupported) {
      observer = new PerformanceObserver((list) => {
        for (const e of list.getEntries()) longTasks.push(e.duration);
      });
      observer.observe({ type: 'longtask' });
    }
    let last = null;
    let running = true;
    const loop = (t) => {
      if (last !== null) frames.push(t - last);
      last = t;
      if (running) requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
    window.avkTest.renderTimes(true);
    const tap = window.__fleetBench;
    tap.nav = {};
    tap.count = 0;
    tap.rec = true;
    await new Promise((r) => setTimeout(r, s * 1000));
    tap.rec = false;
    running = false;
    observer?.disconnect();
    const v = window.avkTest.liveVehicles();
    const ais = document.getElementById('live-plot')?.data?.find((d) => String(d.name).startsWith('AIS'));
    return {
      frames,
      longTasks: longTaskSupported ? longTasks : null,
      renders: window.avkTest.renderTimes(),
      stream: { messages: tap.count, nav: tap.nav },
      drawn: { vehicles: (v.selected ? 1 : 0) + v.others.length, ais: ais?.x?.length ?? 0 },
    };
  }, seconds);
}

// ---------------------------------------------------------------------------------------------
// A window

async function vehicleClocks(server) {
  const vs = await apiRequest(server, '/vehicles');
  return new Map(vs.filter((v) => v.link === 'LIVE').map((v) => [v.id, { t: v.t_s, mission: v.mission_id }]));
}

async function measureWindow({ server, gpsd, traffic, stream, fox, page }) {
  const pids = { server: server.child.pid, gpsd: gpsd.child.pid, traffic: traffic.child.pid };
  stream.nav.clear();
  fox.pose.clear();
  const load0 = loadavg();
  const clocks0 = await vehicleClocks(server);
  const w0 = performance.now();
  const cpu0 = Object.fromEntries(Object.entries(pids).map(([k, pid]) => [k, cpuSeconds(pid)]));
  const ours = new Set(Object.values(pids));
  const browserCpu0 = page ? cpuOf(descendants(process.pid, ours)) : null;
  stream.recording = true;
  fox.recording = true;
  const rss = [];
  let sampling = true;
  const sampler = (async () => {
    while (sampling) {
      rss.push(rssMiB(pids.server));
      await sleep(1000);
    }
  })();
  const pageResult = page ? await measureFrames(page, SECONDS) : await sleep(SECONDS * 1000);
  stream.recording = false;
  fox.recording = false;
  const cpu1 = Object.fromEntries(Object.entries(pids).map(([k, pid]) => [k, cpuSeconds(pid)]));
  const browserCpu1 = page ? cpuOf(descendants(process.pid, ours)) : null;
  const wallS = (performance.now() - w0) / 1000;
  const clocks1 = await vehicleClocks(server);
  const wallRestS = (performance.now() - w0) / 1000; // the second GET's answer is a little later
  sampling = false;
  await sampler;
  rss.push(rssMiB(pids.server));

  const restFactor = [];
  for (const [id, c1] of clocks1) {
    const c0 = clocks0.get(id);
    if (c0) restFactor.push((c1.t - c0.t) / wallRestS);
  }
  const out = {
    wall_s: wallS,
    clock_span: new Map([...clocks1].filter(([id]) => clocks0.has(id)).map(([id, c]) => [id, [clocks0.get(id).t, c.t]])),
    load_before: load0,
    load_after: loadavg(),
    vehicles_live: clocks1.size,
    missions_running: [...clocks1.values()].filter((c) => c.mission !== null).length,
    clock_factor_rest: spread(restFactor),
    stream: { ...rates(stream.nav, wallS), lag_ms: lags(stream.nav), kbytes_per_s: stream.bytes / 1024 / wallS, closed: stream.closed },
    foxglove: { ...rates(fox.pose, wallS), lag_ms: lags(fox.pose), closed: fox.closed },
    cpu_per_wall_s: Object.fromEntries(Object.keys(pids).map((k) => [k, (cpu1[k] - cpu0[k]) / wallS])),
    // Chromium's processes (those alive at both ends; one started meanwhile counts from zero).
    browser_cpu_per_wall_s: page ? [...browserCpu1].reduce((a, [pid, c]) => a + c - (browserCpu0.get(pid) ?? 0), 0) / wallS : null,
    server_rss_mib: { end: rss.at(-1), max: Math.max(...rss) },
  };
  stream.bytes = 0;
  if (page) {
    const f = dist(pageResult.frames);
    out.frames = { ...f, fps: pageResult.frames.length / SECONDS };
    out.long_tasks = pageResult.longTasks === null ? null : { count: pageResult.longTasks.length, total_ms: pageResult.longTasks.reduce((a, b) => a + b, 0), max_ms: Math.max(0, ...pageResult.longTasks) };
    out.plot_updates = dist(pageResult.renders);
    out.drawn = pageResult.drawn;
    const nav = new Map(Object.entries(pageResult.stream.nav));
    out.page_stream = { ...rates(nav, wallS), lag_ms: lags(nav), messages_per_s: pageResult.stream.messages / wallS };
  }
  return out;
}

/** After the windows (so that reading them costs nothing inside one): each vehicle's stored track
 *  over each window's station-clock span, to tell samples the loop never made from samples a
 *  client was not sent. */
async function storedTracks(server, missionOf, phases) {
  const rows = new Map();
  for (const [v, id] of missionOf) {
    const all = [];
    let after = null;
    do {
      const page = await apiRequest(server, `/missions/${id}/nav?limit=10000${after === null ? '' : `&after=${after}`}`);
      for (const r of page.items) all.push(r.t_s);
      after = page.next;
    } while (after !== null && after !== undefined);
    rows.set(v, all);
  }
  for (const { r } of phases) {
    if (!r) continue;
    const perS = [];
    const steps = [];
    for (const [v, [t0, t1]] of r.clock_span) {
      const ts = (rows.get(v) ?? []).filter((t) => t >= t0 && t <= t1).sort((a, b) => a - b);
      // A mission that ended inside the window stored nothing after: count up to its last sample.
      if (ts.length > 1) perS.push(ts.length / (Math.min(t1, ts.at(-1) + 0.1) - t0));
      for (let i = 1; i < ts.length; i++) steps.push(ts[i] - ts[i - 1]);
    }
    const skipped = steps.filter((d) => d > 0.15).length;
    r.stored = { per_station_s: spread(perS), step_s: { max: Math.max(...steps), share_over_0_15_s: skipped / Math.max(1, steps.length) } };
    delete r.clock_span;
  }
}

// ---------------------------------------------------------------------------------------------
// The report

const f1 = (v) => (Number.isFinite(v) ? v.toFixed(1) : '—');
const f2 = (v) => (Number.isFinite(v) ? v.toFixed(2) : '—');
const f3 = (v) => (Number.isFinite(v) ? v.toFixed(3) : '—');
const mmm = (s, f = f1) => `${f(s.min)} / ${f(s.median)} / ${f(s.max)}`;
const pct = (d) => `${f1(d.p50)} / ${f1(d.p95)} / ${f1(d.p99)} / ${f1(d.max)}`;

function table(env, phases) {
  const cols = phases.map((p) => p.label);
  const rows = [];
  const row = (name, fn) => rows.push([name, ...phases.map((p) => (p.r ? fn(p.r) : '—'))]);
  row('vehicles LIVE / missions running at end', (r) => `${r.vehicles_live} / ${r.missions_running}`);
  row('clock factor, GET /vehicles (min/med/max)', (r) => mmm(r.clock_factor_rest, f2));
  row('clock factor, stream nav (min/med/max)', (r) => mmm(r.stream.factor, f2));
  row('stored track samples per station s (min/med/max)', (r) => (r.stored ? mmm(r.stored.per_station_s, f2) : '—'));
  row('stored track steps > 0.15 s (share, max s)', (r) => (r.stored ? `${(100 * r.stored.step_s.share_over_0_15_s).toFixed(1)} %, ${f2(r.stored.step_s.max)}` : '—'));
  row('stream nav msgs/s per vehicle (min/med/max)', (r) => mmm(r.stream.perS));
  row('stream nav vehicles seen', (r) => `${r.stream.vehicles}`);
  row('stream nav steps > 0.15 s station (share, max s)', (r) => `${(100 * r.stream.step_s.share_over_0_15_s).toFixed(1)} %, ${f2(r.stream.step_s.max)}`);
  row('stream nav lag ms p50/p95/p99/max', (r) => pct(r.stream.lag_ms));
  row('stream nav lag drift ms (last s − first s, p50)', (r) => f1(r.stream.lag_ms.drift));
  row('stream nav KiB/s', (r) => f1(r.stream.kbytes_per_s));
  row('clock factor, foxglove pose (min/med/max)', (r) => mmm(r.foxglove.factor, f2));
  row('foxglove pose msgs/s per vehicle (min/med/max)', (r) => mmm(r.foxglove.perS));
  row('foxglove pose vehicles seen', (r) => `${r.foxglove.vehicles}`);
  row('foxglove pose steps > 0.15 s station (share, max s)', (r) => `${(100 * r.foxglove.step_s.share_over_0_15_s).toFixed(1)} %, ${f2(r.foxglove.step_s.max)}`);
  row('foxglove pose lag ms p50/p95/p99/max', (r) => pct(r.foxglove.lag_ms));
  row('server CPU s per wall s', (r) => f3(r.cpu_per_wall_s.server));
  row('server RSS MiB end / max', (r) => `${f1(r.server_rss_mib.end)} / ${f1(r.server_rss_mib.max)}`);
  row('gpsd CPU s per wall s', (r) => f3(r.cpu_per_wall_s.gpsd));
  row('avk traffic CPU s per wall s', (r) => f3(r.cpu_per_wall_s.traffic));
  row('Chromium CPU s per wall s (all processes)', (r) => (r.browser_cpu_per_wall_s === null ? '—' : f3(r.browser_cpu_per_wall_s)));
  row('load average before → after (1 min)', (r) => `${f2(r.load_before[0])} → ${f2(r.load_after[0])}`);
  row('page: drawn vehicles / AIS contacts', (r) => (r.drawn ? `${r.drawn.vehicles} / ${r.drawn.ais}` : '—'));
  row('page: stream msgs/s (all its topics)', (r) => (r.page_stream ? f1(r.page_stream.messages_per_s) : '—'));
  row('page: stream nav msgs/s per vehicle (min/med/max)', (r) => (r.page_stream ? mmm(r.page_stream.perS) : '—'));
  row('page: stream nav lag ms p50/p95/p99/max', (r) => (r.page_stream ? pct(r.page_stream.lag_ms) : '—'));
  row('page: nav lag drift ms (last s − first s, p50)', (r) => (r.page_stream ? f1(r.page_stream.lag_ms.drift) : '—'));
  row('page: frame interval ms p50/p95/p99/max', (r) => (r.frames ? pct(r.frames) : '—'));
  row('page: frames/s', (r) => (r.frames ? f1(r.frames.fps) : '—'));
  row('page: long tasks count / total ms / max ms', (r) => (r.long_tasks ? `${r.long_tasks.count} / ${f1(r.long_tasks.total_ms)} / ${f1(r.long_tasks.max_ms)}` : r.frames ? 'not supported' : '—'));
  row('page: Live plot update ms p50/p95/max', (r) => (r.plot_updates ? `${f1(r.plot_updates.p50)} / ${f1(r.plot_updates.p95)} / ${f1(r.plot_updates.max)} (${r.plot_updates.n})` : '—'));
  const header = ['', ...cols];
  const widths = header.map((h, i) => Math.max(h.length, ...rows.map((r) => r[i].length)));
  const line = (cells) => `| ${cells.map((c, i) => c.padEnd(widths[i])).join(' | ')} |`;
  const out = [line(header), `|${widths.map((w) => '-'.repeat(w + 2)).join('|')}|`, ...rows.map(line)];
  return [
    `${env.vehicles} vehicle${env.vehicles === 1 ? '' : 's'} (catamaran:m200, sim-choppy) at x${env.factor}, ${env.contacts_heard}/${env.contacts} AIS contacts via gpsd, windows of ${SECONDS} s`,
    `machine: ${env.nproc} × ${env.cpu}; load average at start ${env.load_start.map(f2).join(' ')}; node ${process.version}${env.chromium ? `; Chromium ${env.chromium}` : ''}`,
    `Foxglove: ${env.pose_channels}/${env.vehicles} vehicles' /<vid>/pose advertised (${env.foxglove_topics} channels in all)`,
    ...out,
  ].join('\n');
}

// ---------------------------------------------------------------------------------------------

async function main() {
  if (!existsSync(AVK)) throw new Error(`the avk binary is missing: ${AVK} (build it, or set AVK_BINARY)`);
  if (!existsSync(GPSD)) throw new Error(`gpsd is missing: ${GPSD} (set AVK_GPSD)`);
  if (!values['skip-browser'] && !existsSync(CHROMIUM)) throw new Error(`Chromium is missing: ${CHROMIUM} (or pass --skip-browser)`);
  const env = { vehicles: VEHICLES, contacts: CONTACTS, factor: FACTOR, nproc: cpus().length, cpu: cpus()[0]?.model?.trim() ?? '?', load_start: loadavg() };
  const tmp = mkdtempSync(path.join(tmpdir(), 'avk-fleet-load-'));
  tmpDir = tmp;
  let server = null;
  let browser = null;
  let stream = null;
  let fox = null;
  try {
    const fleetPath = path.join(tmp, 'fleet.json');
    const scenarioPath = path.join(tmp, 'traffic.json');
    writeFileSync(fleetPath, JSON.stringify(fleetFile(), null, 1));
    writeFileSync(scenarioPath, JSON.stringify(trafficScenario(), null, 1));

    const gpsdPort = await freeLoopbackPort();
    const udpPort = await freeUdpPort();
    const gpsd = startChild(GPSD, ['-N', '-n', '-S', String(gpsdPort), `udp://127.0.0.1:${udpPort}`]);
    const traffic = startChild(AVK, ['traffic', '--scenario', scenarioPath, '--udp', `127.0.0.1:${udpPort}`, '--realtime-factor', String(FACTOR), '--interval', '2']);
    server = await startAvkServer(AVK, [
      'serve', '--db', path.join(tmp, 'station.db'), '--vehicles', fleetPath, '--realtime-factor', String(FACTOR),
      '--ais', `127.0.0.1:${gpsdPort}`, '--datum', `${DATUM.lat_deg},${DATUM.lon_deg}`, '--port', '0', '--web', webDir,
    ]);
    children.push(server); // killed on exit too
    for (const p of [gpsd, traffic]) if (p.exited) throw new Error(`${p.child.spawnfile} exited: ${JSON.stringify(p.exited)}\n${p.log}`);

    const missionOf = new Map(); // vehicle id → its mission's id
    for (let i = 0; i < VEHICLES; i++) missionOf.set(vid(i), (await apiRequest(server, `/vehicles/${vid(i)}/missions`, { method: 'POST', body: mission(i) })).id);

    let heard = 0;
    await until(`GET /traffic to list ${CONTACTS} contacts`, async () => {
      const t = await apiRequest(server, '/traffic');
      heard = t.contacts.length;
      return heard >= CONTACTS;
    }, 30000, 500).catch((e) => console.error(`warning: ${e.message}; measuring with ${heard}`));
    env.contacts_heard = heard;

    stream = await streamClient(server);
    fox = foxgloveClient(server);
    await until(`Foxglove to advertise ${VEHICLES} pose channels`, () => fox.subs.size >= VEHICLES, 20000, 200).catch((e) => console.error(`warning: ${e.message}`));
    env.pose_channels = [...fox.subs.values()].length;
    env.foxglove_topics = fox.topics.size;
    env.pose_vehicles = [...fox.subs.values()].sort();
    await sleep(2000); // the missions under way, the clients settled

    const phases = [{ label: 'A: clients only' }, { label: 'B: + dashboard' }];
    phases[0].r = await measureWindow({ server, gpsd, traffic, stream, fox });
    if (!values['skip-browser']) {
      browser = await launchChromium();
      env.chromium = browser.version();
      const { page, shown, errors } = await openDashboard(browser, server, heard);
      env.page_before = shown;
      await sleep(2000);
      phases[1].r = await measureWindow({ server, gpsd, traffic, stream, fox, page });
      env.page_errors = errors;
    }
    await storedTracks(server, missionOf, phases);
    env.missions_end = (await apiRequest(server, '/missions')).map((m) => ({ id: m.id, vehicle: m.vehicle_id, end: m.end ?? m.status ?? null, turns: m.turns }));
    for (const p of [gpsd, traffic]) if (p.exited) console.error(`warning: ${p.child.spawnfile} exited during the run: ${JSON.stringify(p.exited)}\n${p.log}`);
    console.log(table(env, phases));
    if (env.page_before?.error) console.log(`note: the page did not show everything before the window: ${env.page_before.error}`);
    if (env.page_errors?.length) console.log(`page errors: ${env.page_errors.join('; ')}`);
    if (values.json) console.log(JSON.stringify({ env, phases }, null, 2));
  } finally {
    stream?.ws.close();
    fox?.ws.close();
    await Promise.race([browser?.close(), sleep(10000)]).catch(() => {});
    await stopAvkServer(server).catch(() => {});
    for (const p of children) if (p !== server) await stopChild(p);
    rmSync(tmp, { recursive: true, force: true });
  }
}

main().catch((e) => {
  console.error(e.stack || String(e));
  process.exit(1);
});

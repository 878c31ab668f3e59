// Frame time of the Live view with a 72,000-point track (2 hours at 10 Hz) and navigation fed at
// 10 Hz: a benchmark, not a test. The browser test (web/tests/e2e.test.mjs) checks that the track
// is drawn, bounded and simplified; how fast that happens depends on the machine and its load, so
// the figures are measured here and recorded in docs/dashboard.md.
//
//   node web/bench/frame_time.mjs [--runs 3] [--seconds 5] [--window 1800]
//
// Starts a real `avk serve --sim` on a temporary database and drives Debian's Chromium with
// playwright-core, as the browser test does. Environment: AVK_BINARY (default build/server/avk),
// AVK_CHROMIUM (default /usr/bin/chromium).

import { spawn } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';

const here = path.dirname(fileURLToPath(import.meta.url));
const webDir = path.resolve(here, '..');
const repo = path.resolve(webDir, '..');
const AVK = path.resolve(process.env.AVK_BINARY || path.join(repo, 'build/server/avk'));
const CHROMIUM = process.env.AVK_CHROMIUM || '/usr/bin/chromium';

const POINTS = 72000;
const HZ = 10;

const { values } = parseArgs({ options: { runs: { type: 'string', default: '3' }, seconds: { type: 'string', default: '5' }, window: { type: 'string', default: '1800' } } });
const RUNS = Number(values.runs);
const SECONDS = Number(values.seconds);
const WINDOW_S = values.window; // the time series' window: one of the page's #ts-window choices
if (!(RUNS >= 1) || !(SECONDS > 0)) {
  console.error('usage: node web/bench/frame_time.mjs [--runs N ≥ 1] [--seconds S > 0] [--window S]');
  process.exit(2);
}

function sleep(ms) {
  return new Promise((r) => setTimeout(r, ms));
}

function startServer(tmp) {
  return new Promise((resolve, reject) => {
    const args = ['serve', '--db', path.join(tmp, 'bench.db'), '--sim', '--realtime-factor', '50', '--port', '0', '--web', webDir];
    const child = spawn(AVK, args, { stdio: ['ignore', 'pipe', 'pipe'] });
    let log = '';
    const timer = setTimeout(() => {
      child.kill('SIGKILL');
      reject(new Error(`avk serve did not print its URL within 20 s:\n${log}`));
    }, 20000);
    const onData = (chunk) => {
      log = (log + chunk.toString()).slice(-20000);
      const url = log.match(/AVK Station on (http:\/\/127\.0\.0\.1:\d+)\//);
      if (url) {
        clearTimeout(timer);
        resolve({ child, base: url[1] });
      }
    };
    child.stdout.on('data', onData);
    child.stderr.on('data', onData);
    child.on('error', (e) => {
      clearTimeout(timer);
      reject(e);
    });
  });
}

function percentile(sorted, p) {
  if (sorted.length === 0) return NaN;
  const i = Math.min(sorted.length - 1, Math.max(0, Math.ceil((p / 100) * sorted.length) - 1));
  return sorted[i];
}

function summary(values) {
  const s = [...values].sort((a, b) => a - b);
  return { n: s.length, p50: percentile(s, 50), p95: percentile(s, 95), max: s[s.length - 1] };
}

const ms = (v) => `${v.toFixed(1)} ms`;

async function measure(page) {
  return page.evaluate(
    async ({ seconds, hz }) => {
      const frames = [];
      let last = null;
      let running = true;
      const loop = (t) => {
        if (last !== null) frames.push(t - last);
        last = t;
        if (running) requestAnimationFrame(loop);
      };
      requestAnimationFrame(loop);
      window.avkTest.renderTimes(true);
      window.avkTest.seriesTimes(true);
      let updates = 0;
      const timer = setInterval(() => {
        window.avkTest.pushNav();
        updates++;
      }, 1000 / hz);
      await new Promise((r) => setTimeout(r, seconds * 1000));
      clearInterval(timer);
      running = false;
      return { frames, updates, renders: window.avkTest.renderTimes(), series: window.avkTest.seriesTimes() };
    },
    { seconds: SECONDS, hz: HZ },
  );
}

async function main() {
  if (!existsSync(AVK)) throw new Error(`the avk binary is missing: ${AVK} (build it, or set AVK_BINARY)`);
  if (!existsSync(CHROMIUM)) throw new Error(`Chromium is missing: ${CHROMIUM}`);
  const { chromium } = await import('playwright-core');
  const tmp = mkdtempSync(path.join(tmpdir(), 'avk-frame-time-'));
  let server = null;
  let browser = null;
  try {
    server = await startServer(tmp);
    browser = await chromium.launch({
      executablePath: CHROMIUM,
      headless: true,
      args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
    });
    const page = await (await browser.newContext()).newPage();
    await page.setViewportSize({ width: 1280, height: 800 });
    await page.goto(`${server.base}/?test=1#live`, { waitUntil: 'load', timeout: 20000 });
    await page.waitForFunction(() => window.avkTest && document.querySelector('#live-plot .main-svg'), null, { timeout: 20000 });
    const loaded = await page.evaluate((n) => window.avkTest.loadTrack(n), POINTS);
    if (loaded !== POINTS) throw new Error(`loaded ${loaded} points, not ${POINTS}`);
    // By default the widest time-series window: 30 minutes, 18,000 samples a trace before thinning.
    const windows = await page.$$eval('#ts-window option', (os) => os.map((o) => o.value));
    if (!windows.includes(WINDOW_S)) throw new Error(`--window ${WINDOW_S}: the page offers ${windows.join(', ')} s`);
    await page.selectOption('#ts-window', WINDOW_S);
    await sleep(1500);
    console.log(`Live view, ${POINTS}-point track and a ${WINDOW_S} s time-series window, navigation at ${HZ} Hz for ${SECONDS} s, ${RUNS} run(s); Chromium ${browser.version()}`);
    for (let run = 1; run <= RUNS; run++) {
      const r = await measure(page);
      const f = summary(r.frames);
      const u = summary(r.renders);
      const s = summary(r.series);
      console.log(
        `run ${run}: frame time p50 ${ms(f.p50)}, p95 ${ms(f.p95)}, max ${ms(f.max)} (${f.n} frames, ${(f.n / SECONDS).toFixed(0)} fps); ` +
          `plot update p50 ${ms(u.p50)}, p95 ${ms(u.p95)}, max ${ms(u.max)} (${u.n} updates for ${r.updates} nav samples); ` +
          `time series redraw p50 ${ms(s.p50)}, p95 ${ms(s.p95)}, max ${ms(s.max)} (${s.n} redraws)`,
      );
    }
  } finally {
    await Promise.race([browser?.close(), sleep(10000)]).catch(() => {});
    if (server) {
      const exited = new Promise((r) => server.child.once('exit', r));
      server.child.kill('SIGTERM');
      await Promise.race([exited, sleep(8000)]);
      server.child.kill('SIGKILL');
    }
    rmSync(tmp, { recursive: true, force: true });
  }
}

main().catch((e) => {
  console.error(e.stack || String(e));
  process.exit(1);
});

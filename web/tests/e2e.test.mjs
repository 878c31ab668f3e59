// End-to-end tests of the dashboard: a real `avk serve --sim` and Debian's Chromium driven by
// playwright-core (no browser download). Run with `node --test web/tests/` (CTest: web_e2e).
//
// Environment: AVK_BINARY (default build/server/avk), AVK_SCREENSHOTS (default
// build/web-screenshots), AVK_CHROMIUM (default /usr/bin/chromium). A missing Chromium or
// web/node_modules is a failure, not a skip: CI installs both (scripts/setup, scripts/web-deps).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, execFile } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, copyFileSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { slow, sleep, until } from './wait.mjs';
import { startAvkServer, stopAvkServer } from './avk_server.mjs';
import { showView } from './browser.mjs';
import { answerFrameText, riskText, marginText, explanationText, colregsText, candidateText } from '../js/frame.js';

const here = path.dirname(fileURLToPath(import.meta.url));
const webDir = path.resolve(here, '..');
const repo = path.resolve(webDir, '..');
const AVK = path.resolve(process.env.AVK_BINARY || path.join(repo, 'build/server/avk'));
const SHOTS = path.resolve(process.env.AVK_SCREENSHOTS || path.join(repo, 'build/web-screenshots'));
const CHROMIUM = process.env.AVK_CHROMIUM || '/usr/bin/chromium';
const DOC_SHOTS = path.join(repo, 'docs/screenshots');

const SERVER_START_MS = slow(20000);
// A 2-hour track at 10 Hz. How fast the page draws it is measured by web/bench/frame_time.mjs
// (figures in docs/dashboard.md), not here: a test must pass on a loaded machine.
const PERF_POINTS = 72000;
const PERF_UPDATES = 20;

const tmp = mkdtempSync(path.join(tmpdir(), 'avk-web-e2e-'));
let server = null; // {child, port, token, base, log}
let browser = null;
let context = null;
let page = null;
const consoleErrors = []; // {text, phase}
const pageErrors = [];
let phase = 'load';

// ---------------------------------------------------------------- helpers

function startServer(port = 0, vehicle = ['--sim', '--realtime-factor', '50'], db = 'station.db') {
  return startAvkServer(AVK, ['serve', '--db', path.join(tmp, db), ...vehicle, '--port', String(port), '--web', webDir]);
}

const stopServer = stopAvkServer;

async function api(pathname) {
  const res = await fetch(`${server.base}/api/v1${pathname}`, { signal: AbortSignal.timeout(slow(10000)) });
  assert.ok(res.ok, `GET ${pathname}: ${res.status}`);
  return res.json();
}

async function shot(name, p = page) {
  const file = path.join(SHOTS, `${name}.png`);
  await p.screenshot({ path: file, fullPage: true, timeout: slow(20000) });
  return file;
}

const goView = (view) => showView(page, view);

function runAvk(args, timeoutMs = 30000) {
  return new Promise((resolve) => {
    execFile(AVK, args, { timeout: slow(timeoutMs) }, (err, stdout, stderr) => {
      resolve({ code: err ? (typeof err.code === 'number' ? err.code : -1) : 0, stdout, stderr });
    });
  });
}

async function newPage(viewport = { width: 1280, height: 800 }) {
  const p = await context.newPage();
  await p.setViewportSize(viewport);
  p.setDefaultTimeout(slow(15000));
  p.on('console', (m) => {
    if (m.type() === 'error') consoleErrors.push({ text: m.text(), phase, url: m.location()?.url });
  });
  p.on('pageerror', (e) => pageErrors.push({ text: `${e.message}\n${e.stack ?? ''}`, phase }));
  return p;
}

// ---------------------------------------------------------------- set-up and tear-down

before(async () => {
  mkdirSync(SHOTS, { recursive: true });
  assert.ok(existsSync(AVK), `the avk binary is missing: ${AVK} (build it, or set AVK_BINARY)`);
  assert.ok(existsSync(CHROMIUM), `Chromium is missing: ${CHROMIUM} (scripts/setup installs Debian's chromium)`);
  assert.ok(
    existsSync(path.join(webDir, 'node_modules/playwright-core')) && existsSync(path.join(webDir, 'node_modules/plotly.js-dist-min/plotly.min.js')),
    'web/node_modules is missing: run scripts/web-deps (npm ci in web/)',
  );
  const { chromium } = await import('playwright-core');
  server = await startServer();
  browser = await chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    timeout: slow(30000),
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  context = await browser.newContext({ acceptDownloads: true });
  page = await newPage();
});

after(async () => {
  // The server is stopped whatever happened; the browser too, with a bound on each.
  await Promise.race([browser?.close(), sleep(10000)]).catch(() => {});
  await stopServer(server).catch(() => {});
  rmSync(tmp, { recursive: true, force: true });
});

// Last line of defence: never leave an avk serve behind, even when the runner is interrupted.
process.on('exit', () => {
  if (server && !server.exited) server.child.kill('SIGKILL');
});

// ---------------------------------------------------------------- the tests

test('the embedded example missions equal examples/', async () => {
  const { EXAMPLES } = await import(pathToFileURL(path.join(webDir, 'js/examples.js')).href);
  for (const [name, mission] of Object.entries(EXAMPLES)) {
    const original = JSON.parse(readFileSync(path.join(repo, 'examples', `${name}.json`), 'utf8'));
    assert.deepEqual(mission, original, `web/js/examples.js '${name}' differs from examples/${name}.json`);
  }
});

test('an AVK corridor is drawn as one closed band: the left boundary, then the right one reversed', async () => {
  const { corridorTrace, corridorName } = await import(pathToFileURL(path.join(webDir, 'js/plots.js')).href);
  const corridor = { share: 0.9, n_turns: 3, s_m: [0, 1, 2], half_width_m: [0, 0.5, 1], left: [[0, 0], [-0.5, 1], [-1, 2]], right: [[0, 0], [0.5, 1], [1, 2]] };
  const t = corridorTrace(corridor);
  assert.equal(t.fill, 'toself');
  assert.equal(t.visible, true);
  assert.equal(t.name, 'AVK 90 % corridor (3 turns)');
  // A straight path north with a half width growing linearly: drawn sampled along the path (its
  // width averaged over a window, which leaves a linear one as it is), from the start up the left
  // boundary x = −y/2, across the end, down the right one x = y/2, and closed.
  const pts = t.x.map((x, i) => [x, t.y[i]]);
  const near = (p, q) => Math.hypot(p[0] - q[0], p[1] - q[1]) < 1e-9;
  assert.ok(near(pts[0], [0, 0]) && near(pts.at(-1), [0, 0]), `from and back to the start: ${pts[0]}, ${pts.at(-1)}`);
  const corner = (q) => pts.findIndex((p) => near(p, q));
  assert.ok(corner([-1, 2]) > 0 && corner([1, 2]) === corner([-1, 2]) + 1, 'the end: left corner, then right corner');
  pts.forEach(([x, y], i) => {
    const onLeft = i <= corner([-1, 2]) && Math.abs(x + y / 2) < 1e-9;
    const onRight = i >= corner([1, 2]) && Math.abs(x - y / 2) < 1e-9;
    assert.ok((onLeft || onRight) && y >= -1e-9 && y <= 2 + 1e-9, `vertex ${i} (${x}, ${y}) on neither boundary`);
  });
  assert.match(t.fillcolor, /^rgba\(0, 0, 0, 0\.\d+\)$/, 'the AVK colour (black), semi-transparent');
  assert.equal(corridorName({ share: 0.8, n_turns: 1 }), 'AVK 80 % corridor (1 turn)');
  // No corridor (a single turn, an imported table without corridors): nothing drawn, no legend entry.
  for (const none of [null, undefined, { share: 0.9, n_turns: 1, left: [], right: [] }]) {
    const e = corridorTrace(none);
    assert.equal(e.visible, false);
    assert.equal(e.showlegend, false);
    assert.deepEqual(e.x, []);
  }
});

test('the page loads with no console errors, and every view opens', { timeout: slow(90000) }, async () => {
  phase = 'load';
  await page.goto(`${server.base}/?token=${server.token}&test=1#live`, { waitUntil: 'load', timeout: slow(20000) });
  await page.waitForFunction(() => document.getElementById('link-badge')?.textContent === 'LIVE', null, { timeout: slow(20000) });
  await page.waitForFunction(() => window.Plotly && document.querySelector('#live-plot .main-svg'), null, { timeout: slow(20000) });
  assert.ok(!page.url().includes('token='), `the token stays in the address bar: ${page.url()}`);
  assert.equal(await page.evaluate(() => sessionStorage.getItem('avk-token')), server.token);
  for (const v of ['replay', 'mission', 'ckt', 'compare', 'model', 'encounter', 'export', 'live']) {
    await goView(v);
    await sleep(700);
  }
  // Keyboard: the tabs are links in the tab order, and Alt+3 jumps to the Mission view (the third).
  await page.keyboard.press('Alt+3');
  await page.waitForSelector('#view-mission:not([hidden])', { timeout: slow(5000) });
  await goView('live');
  await shot('01-load-live');
  assert.deepEqual(pageErrors, [], 'uncaught errors in the page');
  assert.deepEqual(consoleErrors, [], 'console errors at load');
});

test('a bad mission shows its validation errors next to the fields', { timeout: slow(60000) }, async () => {
  phase = 'bad-mission';
  await goView('mission');
  await page.fill('#m-name', 'bad');
  await page.fill('#m-speeds', '99');
  await page.fill('#m-dheadings', '');
  await page.click('#m-start');
  const speedErr = page.locator('.field[data-pointer="/turn_array/speeds_mps"] .field-error');
  await speedErr.first().waitFor({ state: 'visible', timeout: slow(10000) });
  // The field's label, not the JSON pointer; the pointer stays in data-field.
  assert.match(await speedErr.first().textContent(), /^Speeds \(m\/s\) — item 1: must be in/);
  assert.equal(await speedErr.first().getAttribute('data-field'), '/turn_array/speeds_mps/0');
  const dpsiErr = page.locator('.field[data-pointer="/turn_array/dheadings_deg"] .field-error');
  assert.match(await dpsiErr.first().textContent(), /^Heading changes \(°\)/);
  assert.equal(await page.getAttribute('#m-speeds', 'aria-invalid'), 'true');
  await shot('02-mission-errors');
  // A field the client cannot even read is caught before sending.
  await page.fill('#m-speeds', '1.0, fast');
  await page.click('#m-start');
  await page.waitForSelector('.field[data-pointer="/turn_array/speeds_mps"] .field-error:has-text("not a number")', { timeout: slow(5000) });
  const missions = await api('/missions');
  assert.equal(missions.length, 0, 'a bad mission must not start');
});

let missionId = null;

test('starting a small mission from the Mission view makes the vehicle move in Live', { timeout: slow(90000) }, async () => {
  phase = 'mission';
  await goView('mission');
  await page.fill('#m-name', 'e2e-small');
  await page.fill('#m-speeds', '1.0, 1.5');
  await page.fill('#m-dheadings', '40, 90');
  await page.fill('#m-repeats', '2'); // two turns a cell: the CKT view has a mean, an error and error bars
  await page.fill('#m-polygon', '-150, -150\n150, -150\n150, 150\n-150, 150');
  await page.fill('#m-buffer', '25');
  await page.fill('#m-return', '0, -70');
  await page.click('#m-start');
  await page.waitForFunction(() => /Mission \d+ started/.test(document.getElementById('m-result').textContent), null, { timeout: slow(15000) });
  missionId = Number((await page.textContent('#m-result')).match(/Mission (\d+)/)[1]);
  assert.equal(await page.locator('.field-error').count(), 0, 'no field errors after a good mission');
  await shot('03-mission');

  await goView('live');
  const readXY = () => page.evaluate(() => [document.getElementById('live-x').textContent, document.getElementById('live-y').textContent]);
  const first = await readXY();
  await until('the displayed x/y to change', async () => {
    const now = await readXY();
    return (now[0] !== first[0] || now[1] !== first[1]) && now[0] !== '–' ? now : null;
  }, 30000);
  await shot('live-running');
  const cells = await page.locator('#progress-grid td').count();
  assert.equal(cells, 4, 'the turn-array grid shows 2 speeds × 2 heading changes');
  // A second page opened mid-mission reads the stored track over REST (GET /missions/{id}/nav):
  // right after it loads, its track holds the mission so far, not only what the stream sent since.
  await sleep(1500);
  const second = await newPage();
  try {
    await second.goto(`${server.base}/?test=1#live`, { waitUntil: 'load', timeout: slow(20000) });
    const history = await (
      await second.waitForFunction((id) => {
        const h = window.avkTest?.navHistory();
        return h && h.missionId === id ? h : null;
      }, missionId, { timeout: slow(20000) })
    ).jsonValue();
    const stillRunning = (await api(`/missions/${missionId}`)).status;
    assert.ok(history.rows >= 200, `only ${history.rows} stored nav rows were read (mission ${stillRunning})`);
    assert.ok(history.trackLength >= 100, `the track holds ${history.trackLength} points right after the history read`);
    assert.ok(await second.evaluate(() => window.avkTest.trackLength()) >= history.trackLength);
    await shot('live-second-page', second);
  } finally {
    await second.close();
  }
  // For the README: the finished mission, its last turn still drawn with its AVK prediction (from
  // the CKT of the turns before it). The prediction is best effort; the screenshot is taken anyway.
  await until('the mission to finish', async () => (await api(`/missions/${missionId}`)).status === 'done', 60000, 500);
  await page.waitForFunction(() => /done 4\b/.test(document.getElementById('progress-counts').textContent), null, { timeout: slow(15000) });
  await page
    .waitForFunction(() => /predictions: .*avk/.test(document.getElementById('turn-status').textContent), null, { timeout: slow(10000) })
    .catch(() => {});
  // When the last turn has its AVK prediction with a corridor, the band starts where the
  // prediction does: both are placed at the turn's start pose by the server.
  const live = await page.evaluate(() => {
    const d = document.getElementById('live-plot').data ?? [];
    const band = d.find((t) => / corridor /.test(t.name) && t.visible === true);
    const avk = d.find((t) => /^AVK \(CKT\) prediction/.test(t.name) && t.visible === true);
    return band && avk ? { band: [band.x[0], band.y[0]], avk: [avk.x[0], avk.y[0]], fill: band.fill } : null;
  });
  if (live) {
    assert.equal(live.fill, 'toself');
    assert.ok(Math.hypot(live.band[0] - live.avk[0], live.band[1] - live.avk[1]) < 1e-6, `the band starts at ${live.band}, the AVK prediction at ${live.avk}`);
  }
  await sleep(500);
  await shot('live');
});

test('the Live view shows the deviation from the prediction while a turn runs', { timeout: slow(60000) }, async () => {
  // The mission's own turns last a moment at a real-time factor of 50: what the page showed during
  // them is reported, but the check is on a synthetic turn fed through the stream's path (a page
  // of its own: its nav replaces the stream's), which runs until the test has seen the figure.
  const real = await page.evaluate(() => window.avkTest?.deviations() ?? []);
  console.log(`# deviations shown during the mission's turns: ${real.length}${real.length ? `, e.g. "${real.at(-1).text}"` : ''}`);
  const p = await newPage();
  try {
    await p.goto(`${server.base}/?test=1#live`, { waitUntil: 'load', timeout: slow(20000) });
    await p.waitForFunction(() => window.avkTest && window.avkTest.state().vehicleId && document.querySelector('#live-plot .main-svg'), null, { timeout: slow(20000) });
    assert.ok(await p.evaluate(() => window.avkTest.startTurn(90, 1.0)), 'the turn started');
    // Nav every 0.5 s of sim time until the page has asked GET /maneuvers/ongoing and shown it.
    const shown = await until('the deviation in the turn panel', async () => {
      await p.evaluate(() => window.avkTest.turnNav());
      const text = await p.textContent('#turn-deviation');
      return /^deviation /.test(text) ? text : null;
    }, 20000, 300);
    assert.match(shown, /^deviation \d+\.\d m \(((inside|outside) \d+ % corridor|(avk|instantaneous) prediction(, no corridor)?)\)$/);
    const log = await p.evaluate(() => window.avkTest.deviations());
    assert.ok(log.length > 0 && log.every((d) => d.expected.every(Number.isFinite)), JSON.stringify(log));
    // The expected position is marked on the track plot.
    const marker = await until('the expected-position marker', () =>
      p.evaluate(() => {
        const t = document.getElementById('live-plot').data?.find((d) => /^expected now/.test(d.name));
        return t && t.visible === true && t.x.length === 1 ? [t.x[0], t.y[0]] : null;
      }),
    10000, 200);
    assert.ok(marker.every(Number.isFinite), `marker at ${marker}`);
    await shot('live-deviation', p);
  } finally {
    await p.close();
  }
});

test("Live says what its predictions move against, and the operator's override is sent with them", { timeout: slow(90000) }, async () => {
  // The station has an estimate of the current by now (the small mission's), so the default is
  // over ground. Every prediction and deviation request of a synthetic turn is recorded.
  const asks = [];
  const p = await newPage();
  p.on('request', (q) => {
    const u = new URL(q.url());
    if (/\/(predict|maneuvers\/ongoing)$/.test(u.pathname)) asks.push({ path: u.pathname, params: u.searchParams });
  });
  const predicts = () => asks.filter((a) => a.path.endsWith('/predict'));
  const ongoings = () => asks.filter((a) => a.path.endsWith('/maneuvers/ongoing'));
  // What the station answers to a request the page made, as the readout should say it.
  const expectedText = async (a) => answerFrameText(await api(`${a.path.replace(/^\/api\/v1/, '')}?${a.params}`));
  // Nav until the readout shows `wanted` (the deviation's answer arrives once a second).
  const shownAs = (what, wanted) =>
    until(what, async () => {
      await p.evaluate(() => window.avkTest.turnNav());
      const text = await p.textContent('#live-pred-frame');
      return text === wanted ? text : null;
    }, 20000, 300);
  try {
    await p.goto(`${server.base}/?test=1#live`, { waitUntil: 'load', timeout: slow(20000) });
    await p.waitForFunction(() => window.avkTest && window.avkTest.state().vehicleId && document.querySelector('#live-plot .main-svg'), null, { timeout: slow(20000) });
    assert.ok(await p.evaluate(() => window.avkTest.startTurn(90, 1.0)), 'the turn started');
    await until('a prediction and a deviation asked for', async () => {
      await p.evaluate(() => window.avkTest.turnNav());
      return predicts().length > 0 && ongoings().length > 0;
    }, 20000, 300);
    // By default neither a current nor a speed reference is sent: the station's default answers.
    for (const a of asks) {
      assert.equal(a.params.get('current'), null, `${a.path}?${a.params}`);
      assert.equal(a.params.get('speed_reference'), null, `${a.path}?${a.params}`);
    }
    const byDefault = await expectedText(predicts()[0]);
    assert.match(byDefault, /^over ground · current .* · speed held over ground \(default\)$/);
    assert.equal(await expectedText(ongoings()[0]), byDefault, 'the deviation moves against the same');
    await shownAs('the default frame in the readout', byDefault);

    // The operator asks for the path through the water: every request says so, and the readout.
    asks.length = 0;
    await p.selectOption('#live-pred-current', 'none');
    await until('a prediction and a deviation asked through the water', async () => {
      await p.evaluate(() => window.avkTest.turnNav());
      return predicts().length > 0 && ongoings().some((a) => a.params.get('current') === 'none');
    }, 20000, 300);
    assert.ok(predicts().every((a) => a.params.get('current') === 'none'), predicts().map((a) => `${a.params}`).join('\n'));
    const water = await expectedText(predicts()[0]);
    assert.equal(water, 'through the water · current none asked · speed held over ground (default)');
    await shownAs('the frame through the water', water);

    // And the speed reference, with it.
    asks.length = 0;
    await p.selectOption('#live-pred-speedref', 'through_water');
    await until('a prediction asked with the speed reference', async () => {
      await p.evaluate(() => window.avkTest.turnNav());
      return predicts().length > 0 && ongoings().some((a) => a.params.get('speed_reference') === 'through_water');
    }, 20000, 300);
    assert.ok(predicts().every((a) => a.params.get('current') === 'none' && a.params.get('speed_reference') === 'through_water'));
    await shownAs('the asked speed reference', await expectedText(predicts()[0]));
    assert.match(await p.textContent('#live-pred-frame'), /speed held through the water \(asked\)$/);
    await shot('live-prediction-frame', p);
  } finally {
    await p.close();
  }
});

test('Live shows the estimated current: its value and uncertainty, and an arrow along it', { timeout: slow(60000) }, async () => {
  // The small mission that ran before gave the station an estimate (GET /vehicles/{vid}/current);
  // the simulator has no current, so it is not told apart from still water.
  const vid = (await api('/health')).vehicle_id;
  const est = await api(`/vehicles/${vid}/current`);
  assert.ok(Number.isFinite(est.speed_mps) && est.evidence >= 2, JSON.stringify(est));
  const p = await newPage();
  try {
    await p.goto(`${server.base}/?test=1#live`, { waitUntil: 'load', timeout: slow(20000) });
    await p.waitForFunction(() => window.avkTest && window.avkTest.state().vehicleId && document.querySelector('#live-plot .main-svg'), null, { timeout: slow(20000) });
    const shown = await until('the current in the readout', async () => {
      const text = await p.textContent('#live-current');
      return /m\/s toward/.test(text) ? text : null;
    }, 10000, 200);
    assert.match(shown, /^\d+\.\d\d ± \d+\.\d\d m\/s toward \d+ ± \d+°/);
    // A current from the stream: 0.3 m/s toward the east, drawn from the vehicle eastwards.
    await p.evaluate(() => window.avkTest.streamMessage('current', { vehicle_id: window.avkTest.state().vehicleId, east_mps: 0.3, north_mps: 0, speed_mps: 0.3, toward_deg: 90, speed_sd_mps: 0.01, toward_sd_deg: 2, significant: true }));
    await until('the streamed current in the readout', async () =>
      (await p.textContent('#live-current')) === '0.30 ± 0.01 m/s toward 90 ± 2°' || null, 10000, 100);
    const arrow = await until('the current arrow', () =>
      p.evaluate(() => {
        const t = document.getElementById('live-plot').data?.find((d) => /^current \(drift/.test(d.name));
        return t && t.visible === true && t.x.length === 2 ? { x: t.x, y: t.y } : null;
      }),
    10000, 200);
    assert.ok(Math.abs(arrow.x[1] - arrow.x[0] - 18) < 1e-6 && Math.abs(arrow.y[1] - arrow.y[0]) < 1e-6, JSON.stringify(arrow));
  } finally {
    await p.close();
  }
});

/** The page position (CSS px) of a point of the encounter plot's grid. */
function encounterPixel(x, y) {
  return page.evaluate(([x, y]) => {
    const e = document.getElementById('enc-plot');
    const fl = e._fullLayout;
    const r = e.getBoundingClientRect();
    return [r.left + fl.xaxis._offset + fl.xaxis.c2p(x), r.top + fl.yaxis._offset + fl.yaxis.c2p(y)];
  }, [x, y]);
}

/** The choice shown once the evaluation count has passed `after`. */
function encounterChoice(after = 0) {
  return until('an encounter evaluation', () =>
    page.evaluate((after) => {
      const e = document.getElementById('enc-chosen');
      const n = Number(e.dataset.evaluations ?? 0);
      if (n <= after || !e.dataset.dheading || /Loading/.test(e.textContent)) return null;
      return { n, dheading: e.dataset.dheading, text: e.textContent, method: document.getElementById('enc-chosen-method').textContent };
    }, after),
  20000, 100);
}

test('the Encounter view evaluates, flies the choice, and a dragged contact changes it', { timeout: slow(90000) }, async () => {
  phase = 'encounter';
  // The view was opened at load, before any turn: its answer then was the instantaneous one.
  const before = Number((await page.getAttribute('#enc-chosen', 'data-evaluations')) ?? 0);
  await goView('encounter');
  // The default encounter: a contact 30 m ahead and 30 m to starboard crossing west at 1 m/s, as
  // fast as the own vehicle: held straight, the two meet at (0, 30). The finished mission's table
  // answers at 1 m/s.
  const first = await until('an AVK evaluation', async () => {
    const c = await encounterChoice(before);
    return c.method === 'AVK (CKT):' ? c : null;
  }, 20000, 200);
  assert.notEqual(first.dheading, 'none', first.text);
  assert.notEqual(Number(first.dheading), 0, 'straight on meets the contact');
  assert.match(first.text, /^chosen: [+-]?\d+° \(CPA \d+\.\d m(, edge \d+\.\d m)?\)$/);
  assert.match(await page.textContent('#enc-chosen-inst'), /^(chosen: [+-]?\d+°|no candidate clears)/, 'the instantaneous choice beside it');
  const drawn = await page.evaluate(() => {
    const d = document.getElementById('enc-plot').data;
    return {
      fan: d.filter((t) => t.name === 'candidates').reduce((n, t) => n + t.x.filter((v) => v !== null).length, 0),
      chosen: d.find((t) => t.name === 'AVK (CKT) choice')?.x.length ?? 0,
      ray: d.find((t) => t.name === 'instantaneous ray, same Δψ')?.x.length ?? 0,
      colourBar: d.some((t) => t.marker?.showscale === true),
    };
  });
  assert.ok(drawn.fan > 73 * 2, `the fan has ${drawn.fan} points`);
  assert.ok(drawn.chosen >= 2 && drawn.ray >= 2, `chosen ${drawn.chosen} points, ray ${drawn.ray}`);
  assert.ok(drawn.colourBar, 'a colour bar in metres');

  await page.click('#enc-simulate');
  await page.waitForFunction(() => /^Flown /.test(document.getElementById('enc-sim').textContent), null, { timeout: slow(20000) });
  assert.match(await page.textContent('#enc-sim'), /actual CPA \d+\.\d m, standoff 10\.0 m (kept|violated)/);
  // The plot is redrawn on the next animation frame after the text: wait for the track itself.
  const flown = await until('the flown track drawn', () => page.evaluate(() => document.getElementById('enc-plot').data.find((t) => t.name === 'flown (simulator)').x.length), 20000);
  assert.ok(flown > 10, `the flown track has ${flown} points`);
  await shot('encounter');

  // Drag the contact to port (-30, 30): still crossing west, it now moves away from the own
  // track, so holding course clears it and the choice becomes 0°.
  // The flight just drawn may still be re-laying out the axes on a loaded machine: take the pixels
  // once two readings a moment apart agree.
  const pixels = async () => [await encounterPixel(30, 30), await encounterPixel(-30, 30)];
  let last = await pixels();
  const [from, to] = await until('the encounter axes at rest', async () => {
    const now = await pixels();
    const same = JSON.stringify(now) === JSON.stringify(last);
    last = now;
    return same ? now : null;
  }, 20000, 250);
  await page.mouse.move(from[0], from[1]);
  await page.mouse.down();
  await page.mouse.move(to[0], to[1], { steps: 15 });
  await page.mouse.up();
  const moved = Number(await page.inputValue('input[data-contact="0"][data-key="x"]'));
  // To port, near where it was dropped (a redraw under load may shift the axes by a few pixels).
  assert.ok(moved < -15 && moved > -45, `the contact's x is ${moved} after the drag`);
  const after = await until('the choice after the drag', async () => {
    const c = await encounterChoice(first.n);
    return c.dheading === '0' ? c : null;
  }, 20000, 200);
  assert.match(after.text, /^chosen: 0° /);
  assert.equal(await page.textContent('#enc-sim'), '', 'the flight of the old choice is cleared');
  await shot('encounter-dragged');
});

test("the Encounter view shows the choice's risk, margin and reason, and sends the limit, COLREGS and the frame", { timeout: slow(120000) }, async () => {
  phase = 'encounter';
  await goView('encounter');
  // Every evaluation the page asks for, with the station's answer.
  const answers = [];
  const record = async (r) => {
    if (!r.url().endsWith('/maneuvers/evaluate') || r.request().method() !== 'POST') return;
    try {
      answers.push({ body: JSON.parse(r.request().postData()), answer: await r.json() });
    } catch {
      // a failed evaluation is reported by the page
    }
  };
  page.on('response', record);
  const setValue = (sel, v) =>
    page.$eval(sel, (e, v) => {
      if (e.type === 'checkbox') e.checked = v;
      else e.value = String(v);
      e.dispatchEvent(new Event('change', { bubbles: true }));
    }, v);
  // The evaluation shown once the count has passed `after`, and the answer the page was given to
  // the question asked (`asked`: a test of the request body).
  const shown = async (after, asked) => {
    const c = await encounterChoice(after);
    const method = await page.getAttribute('#enc-chosen', 'data-method');
    const got = await until('the answer recorded', () => answers.findLast((a) => a.body.method === method && asked(a.body)) ?? null, 20000, 100);
    return { ...c, ...got };
  };
  const texts = () =>
    page.evaluate(() => ({
      risk: document.getElementById('enc-risk').textContent,
      riskValue: document.getElementById('enc-risk').dataset.risk,
      margin: document.getElementById('enc-margin').textContent,
      explanation: document.getElementById('enc-explanation').textContent,
      colregs: document.getElementById('enc-colregs-rule').hidden ? '' : document.getElementById('enc-colregs-rule').textContent,
      frame: document.getElementById('enc-frame').textContent,
    }));
  const expectShown = async ({ answer }, colregs) => {
    // The page draws the newest answer: wait for it to be this one, then compare every line.
    const t = await until('the answer shown', async () => {
      const now = await texts();
      return now.risk === riskText(answer.chosen, answer.max_risk) && now.frame === answerFrameText(answer) ? now : null;
    }, 20000, 100);
    assert.equal(t.riskValue, String(answer.chosen.risk));
    assert.equal(t.risk, riskText(answer.chosen, answer.max_risk));
    assert.equal(t.margin, marginText(answer.chosen));
    assert.equal(t.explanation, explanationText(answer.chosen));
    assert.equal(t.colregs, colregsText(answer.chosen, colregs));
    assert.equal(t.frame, answerFrameText(answer));
    return t;
  };
  try {
    // Ask again with the defaults: a head-on contact 40 m ahead, closing at 2 m/s.
    for (const [key, v] of [['x', 0], ['y', 40], ['course', 180], ['speed', 1]]) await setValue(`input[data-contact="0"][data-key="${key}"]`, v);
    const n0 = Number(await page.getAttribute('#enc-chosen', 'data-evaluations'));
    await setValue('#enc-max-risk', 5);
    let s = await shown(n0, (b) => b.contacts[0].y_m === 40 && b.contacts[0].course_deg === 180);
    assert.equal(s.body.max_risk, 0.05);
    assert.equal(s.body.colregs, false);
    assert.ok(!('current' in s.body) && !('speed_reference' in s.body), 'auto sends no frame');
    assert.equal(s.answer.frame, 'ground', 'over ground by default: the station has an estimate');
    let t = await expectShown(s, false);
    assert.match(t.risk, /^risk (\d+(\.\d)?|< 0\.1) % \((within 5\.0 %|over the 5\.0 % limit)\)$/);
    assert.match(t.frame, /^over ground · current /);
    // Each candidate's risk in its tooltip, and the choice's position band drawn.
    const tips = s.answer.candidates.filter((k) => k.path.length).map(candidateText);
    const drawn = await until('the candidates drawn with their tooltips', async () => {
      const d = await page.evaluate(() => {
        const data = document.getElementById('enc-plot').data;
        return { ends: data.find((q) => q.name === 'candidate ends')?.text ?? [], band: data.find((q) => /^position band of the choice/.test(q.name))?.x.filter((v) => v !== null).length ?? 0 };
      });
      return JSON.stringify(d.ends) === JSON.stringify(tips) ? d : null;
    }, 20000, 100);
    assert.equal(drawn.ends.length, s.answer.candidates.length);
    assert.ok(drawn.band > 0, 'the position band of the choice is drawn');

    // COLREGS: head-on, rule 14 keeps the choice to starboard.
    let n = s.n;
    await setValue('#enc-colregs', true);
    s = await shown(n, (b) => b.colregs === true);
    assert.equal(s.body.colregs, true);
    assert.equal(s.answer.chosen.colregs_rule, '14', JSON.stringify(s.answer.chosen));
    assert.ok(s.answer.chosen.dheading_deg >= 0, `rule 14 chose ${s.answer.chosen.dheading_deg}`);
    t = await expectShown(s, true);
    assert.match(t.colregs, /^COLREGS rule 14 applied \(head-on\)$/);

    // A tighter limit is sent as a probability.
    n = s.n;
    await setValue('#enc-max-risk', 1);
    s = await shown(n, (b) => b.max_risk === 0.01);
    assert.equal(s.body.max_risk, 0.01);
    await expectShown(s, true);

    // The operator's frame: through the water, then the speed reference too.
    n = s.n;
    await setValue('#enc-current', 'none');
    s = await shown(n, (b) => b.current === 'none');
    assert.equal(s.body.current, 'none');
    assert.equal(s.answer.frame, 'water');
    t = await expectShown(s, true);
    assert.match(t.frame, /^through the water · current none asked/);
    n = s.n;
    await setValue('#enc-speedref', 'through_water');
    s = await shown(n, (b) => b.speed_reference === 'through_water');
    assert.equal(s.body.speed_reference, 'through_water');
    t = await expectShown(s, true);
    assert.match(t.frame, /speed held through the water \(asked\)$/);
    await shot('encounter-risk');
  } finally {
    page.off('response', record);
    // Back to the defaults for what follows.
    await setValue('#enc-current', 'auto');
    await setValue('#enc-speedref', 'auto');
    await setValue('#enc-colregs', false);
    await setValue('#enc-max-risk', 5);
  }
});

test('a finished turn appears in the CKT view', { timeout: slow(90000) }, async () => {
  phase = 'ckt';
  await until('a stored ok turn', async () => (await api(`/turns?mission=${missionId}&status=ok&limit=1`)).items.length > 0, 60000, 500);
  await goView('ckt');
  const n = await until('a CKT cell with n ≥ 1', async () => {
    const counts = await page.$$eval('#ckt-table button[data-n]', (bs) => bs.map((b) => Number(b.dataset.n)));
    if (counts.some((c) => c >= 1)) return Math.max(...counts);
    await page.click('#ckt-refresh');
    return null;
  }, 30000, 1000);
  assert.ok(n >= 1);
  // The chosen cell's plot: turns, mean, fit, predictions.
  await page.waitForSelector('#ckt-cell-plot .main-svg', { timeout: slow(10000) });
  await page.click('#ckt-refresh');
  await until('all four cells', async () => (await page.$$('#ckt-table button[data-n]')).length >= 4, 15000, 500).catch(() => {});
  await sleep(500);
  await shot('ckt');
});

test("the CKT cell plot draws the AVK prediction's corridor for a cell of ≥ 2 turns", { timeout: slow(60000) }, async () => {
  phase = 'ckt-corridor';
  await goView('ckt');
  // Every cell of the finished mission holds two turns (repeats 2).
  const cell = await until('a CKT cell with n ≥ 2', async () => {
    const found = await page.$$eval('#ckt-table button[data-n]', (bs) =>
      bs.filter((b) => Number(b.dataset.n) >= 2).map((b) => ({ speed: Number(b.dataset.speed), dheading: Number(b.dataset.dheading), n: Number(b.dataset.n) })),
    );
    if (found.length > 0) return found[0];
    await page.click('#ckt-refresh');
    return null;
  }, 30000, 1000);
  const pred = await api(`/vehicles/sim-usim/predict?speed=${cell.speed}&dheading=${cell.dheading}&method=avk`);
  assert.ok(pred.corridor, 'the server sends a corridor for a cell of two turns');
  await page.click(`#ckt-table button[data-speed="${cell.speed}"][data-dheading="${cell.dheading}"]`);
  const band = await until('the corridor in the cell plot', () =>
    page.evaluate(({ speed, dheading }) => {
      const plot = document.getElementById('ckt-cell-plot');
      if (plot.dataset.cell !== `${speed}|${dheading}`) return null;
      const t = (plot.data ?? []).find((d) => d.fill === 'toself' && d.visible === true);
      return t ? { name: t.name, x: t.x, y: t.y } : null;
    }, cell),
  15000, 250);
  assert.equal(band.name, `AVK 90 % corridor (${pred.corridor.n_turns} turns)`);
  // The server's band as the page draws a band (js/corridor.js: the left boundary, the right one
  // reversed, closed, sampled along the path), vertex for vertex.
  const { corridorRing } = await import(pathToFileURL(path.join(webDir, 'js/corridor.js')).href);
  const ring = corridorRing(pred.corridor);
  assert.equal(band.x.length, ring.length, 'the left boundary, the right one reversed, closed');
  ring.forEach((p, i) => {
    assert.ok(Math.abs(band.x[i] - p[0]) < 1e-9 && Math.abs(band.y[i] - p[1]) < 1e-9, `vertex ${i}: (${band.x[i]}, ${band.y[i]}) vs (${p[0]}, ${p[1]})`);
  });
  assert.ok(Math.hypot(ring[0][0] - pred.corridor.left[0][0], ring[0][1] - pred.corridor.left[0][1]) < 1e-9, `it starts where the server's band does`);
  // The short-of-goal warning follows the prediction's flag.
  assert.equal(await page.isHidden('#ckt-cell-warning'), pred.short_of_goal !== true);
  await shot('ckt-corridor');
});

test('the Compare view plots held-out path distance by default, says what it scores against, floors its log axes at the GNSS noise and switches to the thesis metrics', { timeout: slow(60000) }, async () => {
  phase = 'compare-metric';
  await goView('compare');
  const cmp = await api('/vehicles/sim-usim/compare');
  assert.equal(cmp.predictive?.default_metric, 'path_m');
  assert.equal(await page.inputValue('#cmp-metric'), 'path_m', 'the fair comparison is the default');
  const speed = Math.min(...cmp.predictive.cells.map((c) => c.speed_mps));
  const id = `cmp-plot-${String(speed).replace('.', '_')}`;
  // Reads the plot of the lowest speed once it shows `metric`.
  const plotOf = (metric) =>
    until(`the ${metric} plot`, () =>
      page.evaluate(({ id, metric }) => {
        const e = document.getElementById(id);
        if (!e || e.dataset.metric !== metric || !e._fullLayout || !e.data) return null;
        return {
          yTitle: e.layout.yaxis.title.text,
          yType: e._fullLayout.yaxis.type,
          yRange: [...e._fullLayout.yaxis.range],
          basis: document.getElementById('cmp-basis').textContent,
          traces: e.data.map((t) => ({ name: t.name, x: [...t.x], y: [...t.y], value: (t.customdata ?? []).map((c) => c[3]), err: t.error_y ? [...t.error_y.array] : null })),
          median: document.getElementById('cmp-median').textContent,
          corridor: document.getElementById('cmp-corridor').textContent,
          table: document.getElementById('cmp-table').dataset.metric,
        };
      }, { id, metric }),
    15000, 250);

  const path = await plotOf('path_m');
  assert.match(path.yTitle, /distance/);
  assert.equal(path.yType, 'linear');
  assert.match(path.median, /^Median path distance \(held out\): AVK \(CKT\) \d/);
  assert.match(path.corridor, /^90 % corridor/);
  assert.equal(path.table, 'predictive');
  assert.match(path.basis, /not built from/);
  assert.match(path.basis, /leave-one-out/);
  // The plotted points and error bars are the API's held-out means and sds.
  const avk = path.traces.find((t) => t.name === 'AVK (CKT)');
  const cells = cmp.predictive.cells.filter((c) => c.speed_mps === speed && c.avk).sort((a, b) => a.dheading_deg - b.dheading_deg);
  assert.deepEqual(avk.x, cells.map((c) => c.dheading_deg));
  assert.deepEqual(avk.y, cells.map((c) => c.avk.path_m.mean));
  assert.deepEqual(avk.err, cells.map((c) => c.avk.path_m.sd ?? 0));
  assert.ok(path.traces.find((t) => t.name === 'instantaneous').y.length > 0, 'the instantaneous assumption is plotted');

  await page.selectOption('#cmp-metric', 'yx_mse_m2');
  const yx = await plotOf('yx_mse_m2');
  assert.match(yx.yTitle, /y\(x\) MSE/);
  assert.equal(yx.yType, 'log');
  assert.match(yx.median, /^Median y\(x\) MSE \(held out\)/);
  // Every cell's value (the hover's), drawn at max(value, floor): the axis starts at the GNSS noise
  // (0.01 m²), not at whatever tiny number a repeatable vehicle gives.
  const FLOOR = 0.01;
  const yxAvk = yx.traces.find((t) => t.name === 'AVK (CKT)');
  assert.deepEqual(yxAvk.value, cells.map((c) => c.avk.yx_mse_m2.mean));
  assert.deepEqual(yxAvk.y, cells.map((c) => Math.max(FLOOR, c.avk.yx_mse_m2.mean)));
  assert.ok(Math.abs(yx.yRange[0] - (Math.log10(FLOOR) - 0.05)) < 1e-9, `log axis from ${yx.yRange[0]}`);

  await page.selectOption('#cmp-metric', 'in_sample');
  const thesis = await plotOf('in_sample');
  assert.equal(thesis.yTitle, 'MSE (m², log)');
  assert.equal(thesis.yType, 'log');
  assert.match(thesis.median, /^Median MSE \(thesis, in sample\)/);
  assert.equal(thesis.table, 'in_sample');
  assert.ok(thesis.traces.every((t) => t.err === null), 'the thesis figure has no error bars');
  assert.match(thesis.basis, /built from/);
  assert.match(thesis.basis, /by construction/);
  const inSample = cmp.cells.filter((c) => c.speed_mps === speed && typeof c.avk?.mse_m2 === 'number').sort((a, b) => a.dheading_deg - b.dheading_deg);
  const thesisAvk = thesis.traces.find((t) => t.name === 'AVK (CKT)');
  assert.deepEqual(thesisAvk.value, inSample.map((c) => c.avk.mse_m2));
  assert.ok(thesisAvk.y.every((v) => v >= FLOOR), 'nothing drawn below the floor');
  assert.ok(thesis.yRange[0] >= Math.log10(FLOOR) - 0.05 - 1e-9, `log axis from ${thesis.yRange[0]}`);

  // Back to the default for the screenshots that follow.
  await page.selectOption('#cmp-metric', 'path_m');
  await plotOf('path_m');
});

test('the CKT JSON export downloads a file that `avk ckt import` accepts', { timeout: slow(60000) }, async () => {
  phase = 'export';
  await goView('export');
  const [download] = await Promise.all([page.waitForEvent('download', { timeout: slow(15000) }), page.click('#exp-ckt-json')]);
  const file = path.join(tmp, 'downloaded-ckt.json');
  await download.saveAs(file);
  assert.ok(statSync(file).size > 100, 'the CKT file is not empty');
  const r = await runAvk(['ckt', 'import', file]);
  assert.equal(r.code, 0, `avk ckt import failed: ${r.stderr}${r.stdout}`);
  assert.match(r.stdout + r.stderr, /ckt: vehicle 'sim-usim'/);

  // The turns CSV is assembled from every page in the browser.
  const [csv] = await Promise.all([page.waitForEvent('download', { timeout: slow(15000) }), page.click('#exp-turns-csv')]);
  const csvFile = path.join(tmp, 'turns.csv');
  await csv.saveAs(csvFile);
  const lines = readFileSync(csvFile, 'utf8').trim().split('\n');
  assert.match(lines[0], /^id,mission_id,/);
  assert.ok(lines.length >= 9, `turns CSV has ${lines.length - 1} rows, expected the 8 turns at least`);

  // The mission as MCAP: the file's magic at both ends, and `avk import mcap` takes it.
  await page.selectOption('#exp-mcap-mission', String(missionId));
  const [mcap] = await Promise.all([page.waitForEvent('download', { timeout: slow(15000) }), page.click('#exp-mission-mcap')]);
  const mcapFile = path.join(tmp, 'mission.mcap');
  await mcap.saveAs(mcapFile);
  const bytes = readFileSync(mcapFile);
  const magic = Buffer.from([0x89, 0x4d, 0x43, 0x41, 0x50, 0x30, 0x0d, 0x0a]);
  assert.ok(bytes.subarray(0, 8).equals(magic) && bytes.subarray(-8).equals(magic), 'the download is an MCAP file');
  const imported = await runAvk(['import', 'mcap', mcapFile, '--db', path.join(tmp, 'imported.db')]);
  assert.equal(imported.code, 0, `avk import mcap failed: ${imported.stderr}${imported.stdout}`);
  await shot('export');
});

test('the Compare and Model views draw (screenshots)', { timeout: slow(60000) }, async () => {
  phase = 'views';
  await goView('compare');
  await until('the comparison', async () => (await page.textContent('#cmp-status')).length > 0 && !/Loading/.test(await page.textContent('#cmp-status')), 15000);
  await shot('compare');
  // A model of the finished mission (POST with the token), then its identification data plot.
  const fitted = await fetch(`${server.base}/api/v1/vehicles/sim-usim/models`, {
    method: 'POST',
    headers: { Authorization: `Bearer ${server.token}`, 'Content-Type': 'application/json' },
    body: JSON.stringify({ missions: [missionId], history_s: 3 }),
    signal: AbortSignal.timeout(slow(30000)),
  });
  const fittedText = await fitted.text();
  assert.equal(fitted.status, 201, fittedText);
  const modelId = JSON.parse(fittedText).id;
  await goView('model');
  await page.waitForSelector(`#model-h-model option[value="${modelId}"]`, { state: 'attached', timeout: slow(10000) });
  await page.selectOption('#model-h-model', String(modelId));
  await page.selectOption('#model-h-mission', String(missionId));
  await page.click('#model-h-show');
  await page.waitForSelector('#model-headings .main-svg', { timeout: slow(15000) });
  const traces = await page.evaluate(() => document.getElementById('model-headings').data.map((t) => ({ name: t.name, n: t.y.filter((v) => v !== null).length })));
  assert.deepEqual(traces.map((t) => t.name), ['measured', 'desired', 'one-step', 'simulated']);
  for (const t of traces) assert.ok(t.n > 50, `trace ${t.name} has ${t.n} points`);
  assert.equal(await page.isDisabled('.plot-frame:has(#model-headings) button.png'), false, 'the PNG button is enabled');
  await sleep(300);
  await shot('model');
  await goView('mission');
  await sleep(500);
  await shot('mission');
});

test('layout: 1280×800 and a tablet, no horizontal scrolling', { timeout: slow(60000) }, async () => {
  phase = 'layout';
  for (const [name, vp] of [['desktop', { width: 1280, height: 800 }], ['tablet', { width: 820, height: 1180 }]]) {
    await page.setViewportSize(vp);
    for (const v of ['live', 'mission', 'ckt', 'compare', 'encounter']) {
      await goView(v);
      // No wait for the plots to refit: a plot still at its old size is clipped by its frame.
      const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
      assert.ok(overflow <= 1, `${name} ${v}: the page is ${overflow} px wider than the viewport`);
    }
    await goView('live');
    await sleep(400);
    await shot(`live-${name}`);
  }
  await page.setViewportSize({ width: 1280, height: 800 });
});

test('a 72,000-point track in Live stays bounded, is drawn simplified and takes every update', { timeout: slow(120000) }, async () => {
  phase = 'perf';
  const p = await newPage();
  try {
    await p.goto(`${server.base}/?test=1#live`, { waitUntil: 'load', timeout: slow(20000) });
    await p.waitForFunction(() => window.avkTest && document.querySelector('#live-plot .main-svg'), null, { timeout: slow(20000) });
    const loaded = await p.evaluate((n) => window.avkTest.loadTrack(n), PERF_POINTS);
    assert.equal(loaded, PERF_POINTS);
    // Navigation one sample at a time, each followed by the frame that draws it: what counts is
    // that every sample is taken and drawn, not how long that took (web/bench/frame_time.mjs).
    const result = await p.evaluate(async (updates) => {
      window.avkTest.renderTimes(true);
      // A full redraw (axes, labels, legend, margins) ends with plotly_afterplot; a sample that
      // leaves the view as it was needs the traces drawn again, nothing more (Plotly's transition
      // path). The simulator's own turns and mission messages still change the figure now and then.
      let fullRedraws = 0;
      let tracesOnly = 0;
      const plot = document.getElementById('live-plot');
      plot.on('plotly_afterplot', () => fullRedraws++);
      plot.on('plotly_transitioning', () => tracesOnly++);
      const lengths = [];
      for (let i = 0; i < updates; i++) {
        lengths.push(window.avkTest.pushNav());
        await new Promise((r) => requestAnimationFrame(() => r()));
      }
      await new Promise((r) => requestAnimationFrame(() => r()));
      const drawn = document.getElementById('live-plot').data.filter((t) => t.name === 'track');
      return {
        lengths,
        renders: window.avkTest.renderTimes().length,
        length: window.avkTest.trackLength(),
        capacity: window.avkTest.trackCapacity(),
        drawnPoints: drawn.reduce((n, t) => n + t.x.filter((v) => v !== null && !Number.isNaN(v)).length, 0),
        drawnTraces: drawn.length,
        tailEnd: drawn.length ? [drawn[drawn.length - 1].x.at(-1), drawn[drawn.length - 1].y.at(-1)] : null,
        readout: [document.getElementById('live-x').textContent, document.getElementById('live-y').textContent],
        fullRedraws,
        tracesOnly,
      };
    }, PERF_UPDATES);
    await shot('live-72k', p);
    console.log(`# 72,000-point track: ${result.drawnPoints} points drawn after ${PERF_UPDATES} updates (${result.renders} plot updates: ${result.fullRedraws} full, ${result.tracesOnly} of the traces only)`);
    assert.equal(result.length, PERF_POINTS, 'the live track stays bounded at its capacity');
    assert.equal(result.capacity, PERF_POINTS);
    assert.deepEqual(result.lengths, Array(PERF_UPDATES).fill(PERF_POINTS), 'every update is taken, the oldest sample dropping out');
    assert.ok(result.renders >= 1, 'the plot was redrawn for the updates');
    // The vehicle moves inside the fitted view: its samples redraw the traces, not the figure.
    assert.ok(result.tracesOnly >= 1 && result.fullRedraws < result.renders, `${result.fullRedraws} full redraws and ${result.tracesOnly} of the traces only for ${result.renders} updates`);
    assert.equal(result.drawnTraces, 2, 'the track is drawn as its simplified older part and its raw newest minute');
    assert.ok(result.drawnPoints > 100, `only ${result.drawnPoints} track points are drawn`); // 22 legs and their turns
    assert.ok(result.drawnPoints < PERF_POINTS / 4, `${result.drawnPoints} of ${PERF_POINTS} points drawn: the track was not simplified`);
    // The newest sample ends the drawn track, and the readout shows the same position.
    assert.ok(result.tailEnd && Number.isFinite(result.tailEnd[0]) && Number.isFinite(result.tailEnd[1]), `the drawn track ends at ${result.tailEnd}`);
    assert.equal(result.tailEnd[0].toFixed(1), result.readout[0], 'x of the newest sample');
    assert.equal(result.tailEnd[1].toFixed(1), result.readout[1], 'y of the newest sample');
  } finally {
    await p.close();
  }
});

// An equilateral triangle rotated by the heading was read as pointing elsewhere, so the
// vehicle is an arrow: its tip, as the browser draws it, lies along the
// heading (screen x right = east, y down = south on the equal axes).
test('the vehicle icon points along the heading at any heading', { timeout: slow(60000) }, async () => {
  phase = 'icon';
  const p = await newPage();
  try {
    await p.goto(`${server.base}/?test=1#live`, { waitUntil: 'load', timeout: slow(20000) });
    await p.waitForFunction(() => window.avkTest && document.querySelector('#live-plot .main-svg'), null, { timeout: slow(20000) });
    for (const heading of [0, 28, 55, 117, 200, 300]) {
      await p.evaluate((h) => window.avkTest.setHeading(h), heading);
      const tip = await p.evaluate(async () => {
        await new Promise((r) => requestAnimationFrame(() => r()));
        const trace = [...document.querySelectorAll('#live-plot .scatterlayer .trace')].find((g) => g.__data__?.[0]?.trace?.name === 'vehicle');
        const point = trace?.querySelector('path.point');
        if (!point) return null;
        const rotate = /rotate\(([-\d.e]+)/.exec(point.getAttribute('transform') ?? '');
        const a = ((rotate ? Number(rotate[1]) : 0) * Math.PI) / 180;
        const nums = (point.getAttribute('d').match(/-?\d*\.?\d+(e-?\d+)?/g) ?? []).map(Number);
        const v = [];
        for (let i = 0; i + 1 < nums.length; i += 2) {
          // SVG rotate(a) turns clockwise on screen (y down).
          const x = nums[i] * Math.cos(a) - nums[i + 1] * Math.sin(a);
          const y = nums[i] * Math.sin(a) + nums[i + 1] * Math.cos(a);
          if (!v.some((q) => Math.hypot(q.x - x, q.y - y) < 1e-6)) v.push({ x, y });
        }
        if (v.length !== 3) return { vertices: v.length };
        // A long isosceles arrow: its tip is the vertex opposite the shortest side, and it
        // points from the middle of that side to the tip.
        let best = null;
        for (let i = 0; i < 3; i++) {
          const [b, c] = [v[(i + 1) % 3], v[(i + 2) % 3]];
          const side = Math.hypot(b.x - c.x, b.y - c.y);
          if (!best || side < best.side) best = { side, x: v[i].x - (b.x + c.x) / 2, y: v[i].y - (b.y + c.y) / 2 };
        }
        return best;
      });
      assert.ok(tip && tip.vertices === undefined, `the vehicle marker is drawn as a triangle at heading ${heading}: ${JSON.stringify(tip)}`);
      const drawn = ((Math.atan2(tip.x, -tip.y) * 180) / Math.PI + 360) % 360;
      const off = Math.abs(((drawn - heading + 540) % 360) - 180);
      assert.ok(off < 3, `heading ${heading}: the arrow's tip points at ${drawn.toFixed(1)} deg`);
    }
  } finally {
    await p.close();
  }
});

test('without a token, a POST asks for it inline and is retried with it', { timeout: slow(60000) }, async () => {
  phase = 'token';
  const p = await newPage();
  try {
    await p.goto(`${server.base}/#mission`, { waitUntil: 'load', timeout: slow(20000) });
    await p.waitForFunction(() => document.getElementById('link-badge')?.textContent === 'LIVE', null, { timeout: slow(20000) });
    assert.equal(await p.evaluate(() => sessionStorage.getItem('avk-token')), null);
    await p.fill('#m-speeds', '99'); // invalid: once authorised, the server answers 422
    await p.click('#m-start');
    await p.waitForSelector('#token-bar:not([hidden])', { timeout: slow(10000) });
    assert.equal(await p.evaluate(() => document.activeElement?.id), 'token-input', 'the token input has the focus');
    assert.equal(await p.locator('[role="dialog"], dialog[open]').count(), 0, 'no modal dialog');
    await p.fill('#token-input', server.token);
    await p.press('#token-input', 'Enter');
    await p.waitForSelector('.field[data-pointer="/turn_array/speeds_mps"] .field-error', { timeout: slow(10000) });
    assert.ok(await p.isHidden('#token-bar'));
    assert.equal(await p.evaluate(() => sessionStorage.getItem('avk-token')), server.token);
  } finally {
    await p.close();
  }
});

test('the link badge shows DISCONNECTED when the server stops and LIVE with a new session after a restart', { timeout: slow(90000) }, async () => {
  phase = 'restart';
  await goView('live');
  const before = await page.evaluate(() => window.avkTest.state().sessionId);
  const port = server.port;
  await stopServer(server);
  await page.waitForFunction(() => document.getElementById('link-badge').textContent === 'DISCONNECTED', null, { timeout: slow(15000) });
  await shot('live-disconnected');
  // The same port, so the page's reconnection finds it (the same database, too).
  server = await until('avk serve to bind its old port again', () => startServer(port), 30000, 1000);
  await page.waitForFunction(() => document.getElementById('link-badge').textContent === 'LIVE', null, { timeout: slow(30000) });
  const afterId = await until('the new session id', async () => {
    const id = await page.evaluate(() => window.avkTest.state().sessionId);
    return id !== before ? id : null;
  }, 15000);
  assert.notEqual(afterId, before);
  // It caught up from REST: the finished mission is still the one shown.
  await until('the mission after catch-up', async () => (await page.evaluate(() => window.avkTest.state().mission)) === missionId, 15000);
});

test("the event log's levels are the ones the hello names", { timeout: slow(60000) }, async () => {
  await goView('live');
  // The dashboard keeps no list of its own: the warnings are the station's, from the hello.
  const levels = await page.evaluate(() => window.avkTest.eventLevels());
  assert.equal(levels.link, 'warning');
  assert.equal(levels.turn_aborted, 'warning');
  assert.equal(levels.returning, 'info');
  // The finished mission's log, read over REST after the restart.
  const events = await until('the mission\'s event log', async () => {
    const e = await page.evaluate(() => window.avkTest.events());
    return e.some((x) => x.kind === 'returning') ? e : null;
  }, 15000);
  for (const e of events) {
    if (e.kind in levels) assert.equal(e.level, levels[e.kind], e.kind);
  }
  const shown = await page.evaluate(() =>
    [...document.querySelectorAll('#event-log li[data-kind]')].map((li) => ({ kind: li.dataset.kind, cls: [...li.classList] })),
  );
  assert.ok(shown.length > 0, 'the event log shows the mission\'s events');
  for (const li of shown) {
    if (li.kind in levels) assert.ok(li.cls.includes(`lvl-${levels[li.kind]}`), `${li.kind}: ${li.cls}`);
  }
});

// Abort asks inline before it acts, and the cells the aborted mission never
// tried count as "not run", not as aborted.
test('Abort asks first, and an aborted mission counts the cells it never tried as not run', { timeout: slow(90000) }, async () => {
  phase = 'abort';
  const mission = JSON.parse(readFileSync(path.join(repo, 'examples/thesis-fig4-1.json'), 'utf8'));
  const res = await fetch(`${server.base}/api/v1/vehicles/sim-usim/missions`, {
    method: 'POST',
    headers: { Authorization: `Bearer ${server.token}`, 'Content-Type': 'application/json' },
    body: JSON.stringify({ ...mission, name: 'to be aborted' }),
  });
  const started = await res.text();
  assert.equal(res.status, 201, started);
  const id = JSON.parse(started).id;
  const status = async () => (await api(`/missions/${id}`)).status;
  await goView('mission');
  await until('the new mission in the control list', () => page.evaluate((v) => [...document.querySelectorAll('#m-target option')].some((o) => o.value === v), String(id)), 15000);
  await page.selectOption('#m-target', String(id));
  await until('Abort enabled', async () => !(await page.isDisabled('#m-abort')), 15000);
  // The first click only asks, naming the mission; nothing is sent.
  await page.click('#m-abort');
  assert.equal(await page.isVisible('#m-abort-confirm'), true);
  assert.match(await page.textContent('#m-abort-question'), new RegExp(`Abort mission ${id} “to be aborted”\\? .*\\d+ planned turns? will not run`));
  assert.equal(await status(), 'running');
  await page.click('#m-abort-no');
  assert.equal(await page.isVisible('#m-abort-confirm'), false);
  assert.equal(await status(), 'running', 'Keep it changes nothing');
  // Confirmed, it aborts.
  await page.click('#m-abort');
  await page.click('#m-abort-yes');
  await until('the mission aborted', async () => (await status()) === 'aborted', 15000);
  const report = await api(`/missions/${id}`);
  const neverTried = report.cells.filter((c) => (c.ok ?? 0) + (c.aborted ?? 0) + (c.rejected ?? 0) === 0).length;
  assert.ok(neverTried > 0, 'the mission was aborted before trying every cell');
  await goView('live');
  await until('the progress grid of the aborted mission', async () => (await page.locator('#progress-grid td.st-notrun').count()) === neverTried, 15000);
  assert.match(await page.textContent('#progress-counts'), new RegExp(`not run ${neverTried}`));
  await shot('live-aborted');
});

/** `avk frontseat-emulator` on a free port: resolves {child, port} once it listens. */
function startEmulator() {
  return new Promise((resolve, reject) => {
    const child = spawn(AVK, ['frontseat-emulator', '--port', '0', '--realtime-factor', '20', '--start', '0,-70,0'], { stdio: ['ignore', 'pipe', 'pipe'] });
    let log = '';
    const timer = setTimeout(() => {
      child.kill('SIGKILL');
      reject(new Error(`the emulator did not listen within ${SERVER_START_MS} ms:\n${log}`));
    }, SERVER_START_MS);
    const onData = (chunk) => {
      log = (log + chunk.toString()).slice(-20000);
      const m = log.match(/listening on 127\.0\.0\.1:(\d+)/);
      if (m) {
        clearTimeout(timer);
        resolve({ child, port: Number(m[1]) });
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

test('an M200 behind the frontseat emulator shows its battery and frontseat link in Live', { timeout: slow(60000) }, async () => {
  phase = 'm200';
  const emulator = await startEmulator();
  let m200 = null;
  const p = await newPage();
  try {
    m200 = await startServer(0, ['--m200', `127.0.0.1:${emulator.port}`, '--realtime-factor', '20'], 'm200.db');
    await p.goto(`${m200.base}/?token=${m200.token}#live`, { waitUntil: 'load', timeout: slow(20000) });
    await p.waitForFunction(() => document.getElementById('link-badge')?.textContent === 'LIVE', null, { timeout: slow(20000) });
    await p.waitForFunction(() => /^\d+\.\d\d$/.test(document.getElementById('live-battery')?.textContent ?? ''), null, { timeout: slow(20000) });
    assert.ok(await p.isVisible('#live-battery'), 'the battery is shown for a real vehicle');
    assert.match(await p.textContent('#live-frontseat'), /bad lines, \d+ disconnects/);
    assert.match(await p.textContent('#vehicle-name'), /m200/);
    await shot('live-m200', p);
  } finally {
    await p.close();
    await stopServer(m200).catch(() => {});
    emulator.child.kill('SIGTERM');
  }
});

test('the simulator shows no battery row', async () => {
  await goView('live');
  assert.ok(await page.isHidden('#live-battery'));
});

test('no unexpected console errors during the run', () => {
  // Expected: the 422s of the bad missions and the 401 without a token (Chromium logs every
  // failed fetch), and the refused connections while the server was stopped.
  const expected = (e) =>
    (e.phase === 'bad-mission' && /status of 422/.test(e.text)) ||
    (e.phase === 'token' && /status of (401|422)/.test(e.text)) ||
    (e.phase === 'restart' && /(ERR_CONNECTION_REFUSED|WebSocket connection|Failed to fetch|ERR_EMPTY_RESPONSE)/.test(e.text));
  const unexpected = consoleErrors.filter((e) => !expected(e));
  assert.deepEqual(unexpected, [], 'unexpected console errors');
  assert.deepEqual(pageErrors, [], 'uncaught errors in the page');
});

test('screenshots for the README', () => {
  for (const name of ['live', 'ckt']) {
    const src = path.join(SHOTS, `${name}.png`);
    assert.ok(existsSync(src), `no ${name} screenshot`);
    // The committed README pictures change only on request (AVK_UPDATE_DOC_SCREENSHOTS=1), so a
    // test run never leaves the checkout modified.
    if (process.env.AVK_UPDATE_DOC_SCREENSHOTS === '1') {
      mkdirSync(DOC_SHOTS, { recursive: true });
      copyFileSync(src, path.join(DOC_SHOTS, `${name}.png`));
    }
  }
});

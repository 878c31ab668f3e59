// Browser tests of a turn as the operator follows it in Live: the corridor band of a tight turn
// drawn without spikes, Live fitted to the current mission rather than the previous one's track,
// the turn panel following the server's turn state, and the deviation judged against the band at
// that time. Run with `node --test web/tests/operator_turns.test.mjs` (CTest: web_operator_turns).
//
// A simulated M200 (its navigation has noise, so its turns' corridors have width) first collects
// turns at ×50 for a table with corridors (1.0 m/s, 90° and 160°, three each); then the same
// database is served at ×1, where a turn lasts some ten seconds: long enough to open a page in
// the middle of one. Environment as e2e.test.mjs: AVK_BINARY, AVK_SCREENSHOTS, AVK_CHROMIUM,
// AVK_E2E_SLOW.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';

import { slow, until } from './wait.mjs';
import { startAvkServer, stopAvkServer, apiRequest } from './avk_server.mjs';
import { AVK, webDir, checkPrerequisites, launchChromium, openPage, showView, tearDown, killServerOnExit, screenshot } from './browser.mjs';

const tmp = mkdtempSync(path.join(tmpdir(), 'avk-web-turns-'));
let server = null;
let browser = null;
let context = null;
let vid = null;
let collected = null; // the collection mission's id
const errors = { console: [], page: [], phase: 'load' };
const DESKTOP = { width: 1280, height: 800 };
const REGION = { polygon_m: [[-100, -100], [100, -100], [100, 100], [-100, 100]], buffer_m: 25, return_point_m: [0, -70] };

function startServer(factor) {
  return startAvkServer(AVK, ['serve', '--db', path.join(tmp, 'station.db'), '--sim', '--vehicle', 'catamaran:m200', '--realtime-factor', String(factor), '--port', '0', '--web', webDir]);
}

const api = (pathname, options) => apiRequest(server, pathname, options);

/** A Live page (with the ?test=1 hooks unless `hooks` is false), once its stream is LIVE. */
async function openLive({ hooks = true, onRequest = null } = {}) {
  const p = await openPage(context, DESKTOP, errors);
  if (onRequest) p.on('request', onRequest);
  await p.goto(`${server.base}/?token=${server.token}${hooks ? '&test=1' : ''}#live`, { waitUntil: 'load', timeout: slow(20000) });
  await p.waitForFunction(() => document.getElementById('link-badge')?.textContent === 'LIVE', null, { timeout: slow(20000) });
  await p.waitForFunction(() => window.Plotly && document.querySelector('#live-plot .main-svg'), null, { timeout: slow(20000) });
  return p;
}

before(async () => {
  checkPrerequisites();
  server = await startServer(50);
  vid = (await api('/health')).vehicle_id;
  const m = await api(`/vehicles/${vid}/missions`, { method: 'POST', body: { name: 'collect', turn_array: { speeds_mps: [1.0], dheadings_deg: [90, 160], repeats: 3 }, operating_region: REGION } });
  collected = m.id;
  await until('the collection mission done', async () => (await api(`/missions/${collected}`)).status === 'done', 120000, 500);
  await stopAvkServer(server);
  server = await startServer(1);
  browser = await launchChromium();
  context = await browser.newContext({ colorScheme: 'light' });
});

after(() => tearDown({ browser, server, dir: tmp }));
killServerOnExit(() => server);

// ---------------------------------------------------------------- the corridor band

/** What is wrong with a drawn band (a closed ring: the left boundary from the path's start, the
 *  right one back): edges that cross (a fold) and spikes, where a boundary turns back outwards
 *  by more than 90° between two edges. The boundaries meet at the path's end by the ring's edge
 *  nearest to it. Within START_M of the start the band opens from a point (every turn starts at
 *  the same pose) to the width of the first metre's turns, a wedge by what it is: no spike. */
const START_M = 2;
function bandFaults(xs, ys, path) {
  const ring = xs.map((x, i) => [x, ys[i]]).filter((p, i, a) => i === 0 || Math.hypot(p[0] - a[i - 1][0], p[1] - a[i - 1][1]) > 1e-9);
  const cross = (a, b, c, d) => {
    const o = (p, q, r) => (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
    return o(c, d, a) * o(c, d, b) < 0 && o(a, b, c) * o(a, b, d) < 0;
  };
  let crossings = 0;
  for (let i = 0; i + 1 < ring.length; i++) {
    for (let j = i + 2; j + 1 < ring.length; j++) if (!(i === 0 && j + 2 === ring.length) && cross(ring[i], ring[i + 1], ring[j], ring[j + 1])) crossings++;
  }
  const end = path.at(-1);
  let cap = 0;
  let best = Infinity;
  for (let i = 0; i + 1 < ring.length; i++) {
    const d = Math.hypot((ring[i][0] + ring[i + 1][0]) / 2 - end[0], (ring[i][1] + ring[i + 1][1]) / 2 - end[1]);
    if (d < best) [best, cap] = [d, i];
  }
  const left = ring.slice(0, cap + 1);
  const right = ring.slice(cap + 1).reverse();
  const spikes = [];
  // Walking a boundary from the start, the band lies to the right of the left one and to the left
  // of the right one: a spike turns sharply towards that side.
  for (const [side, inward] of [[left, -1], [right, 1]]) {
    for (let i = 1; i + 1 < side.length; i++) {
      const a = Math.atan2(side[i][1] - side[i - 1][1], side[i][0] - side[i - 1][0]);
      let d = Math.atan2(side[i + 1][1] - side[i][1], side[i + 1][0] - side[i][0]) - a;
      d = Math.atan2(Math.sin(d), Math.cos(d));
      const fromStart = Math.hypot(side[i][0] - path[0][0], side[i][1] - path[0][1]);
      if (inward * d > Math.PI / 2 && fromStart > START_M) spikes.push(side[i].map((v) => Number(v.toFixed(2))));
    }
  }
  return { crossings, spikes };
}

test('the corridor of a 130–160° turn is drawn as a smooth band, without spikes or folds', { timeout: slow(90000) }, async () => {
  errors.phase = 'band';
  const page = await openLive({ hooks: false });
  try {
    // The CKT view's cell of 1.0 m/s, 160° (three turns): its band as drawn.
    await showView(page, 'ckt');
    const cell = '#ckt-table button[data-speed="1"][data-dheading="160"]';
    await until('the 160° cell in the table', async () => {
      if ((await page.locator(cell).count()) > 0) return true;
      await page.click('#ckt-refresh');
      return false;
    }, 20000, 1000);
    await page.click(cell);
    const drawn = await until('the corridor in the cell plot', () =>
      page.evaluate(() => {
        const plot = document.getElementById('ckt-cell-plot');
        if (plot.dataset.cell !== '1|160') return null;
        const t = (plot.data ?? []).find((d) => d.fill === 'toself' && d.visible === true);
        return t ? { x: Array.from(t.x), y: Array.from(t.y) } : null;
      }), 15000, 250);
    // As the view asks it: through the water, in the normalised frame.
    const cellPred = await api(`/vehicles/${vid}/predict?speed=1&dheading=160&method=avk&current=none`);
    assert.ok(cellPred.corridor, 'a corridor for a cell of three turns');
    const faults = bandFaults(drawn.x, drawn.y, cellPred.trajectory);
    assert.deepEqual(faults, { crossings: 0, spikes: [] }, 'the 160° cell');
    await screenshot(page, 'ckt-corridor-160');
    // Between the cells (130°, interpolated) and to port, placed at a pose as Live and Replay ask:
    // the same drawing.
    for (const dheading of [130, 145, -160]) {
      const pred = await api(`/vehicles/${vid}/predict?speed=1&dheading=${dheading}&method=avk&x=10&y=-20&heading=30`);
      assert.ok(pred.corridor, `a corridor at ${dheading}°`);
      const band = await page.evaluate(async (c) => {
        const t = (await import('/js/plots.js')).corridorTrace(c);
        return { x: Array.from(t.x), y: Array.from(t.y) };
      }, pred.corridor);
      assert.deepEqual(bandFaults(band.x, band.y, pred.trajectory), { crossings: 0, spikes: [] }, `${dheading}°`);
      // It starts where the turn does (every turn starts there), as the server's band does.
      assert.ok(Math.hypot(band.x[0] - pred.corridor.left[0][0], band.y[0] - pred.corridor.left[0][1]) < 1e-6, `the band starts at (${band.x[0]}, ${band.y[0]})`);
    }
  } finally {
    await page.close();
  }
});

// ---------------------------------------------------------------- the fitted view

test("Live fits the current mission and the vehicle; the previous mission's track is faded outside", { timeout: slow(90000) }, async () => {
  errors.phase = 'fit';
  const page = await openLive();
  try {
    // A previous mission's track that reaches 900 m south of this mission's region (a two-hour
    // survey), set aside as when a new mission starts; then a turn in this mission's region.
    await page.evaluate(() => window.avkTest.loadTrack(20000));
    const kept = await page.evaluate(() => window.avkTest.retireTrack());
    assert.ok(kept > 10, `a previous track of ${kept} points`);
    await page.evaluate(() => window.avkTest.startTurn(90, 1.0));
    for (let i = 0; i < 6; i++) await page.evaluate(() => window.avkTest.turnNav());
    const view = await until('the Live plot with the previous track and the turn', () =>
      page.evaluate(() => {
        const el = document.getElementById('live-plot');
        const l = el._fullLayout;
        const prev = el.data?.find((t) => /track \(previous\)$/.test(t.name));
        const turn = el.data?.find((t) => t.name === 'current turn');
        if (!l || !prev?.x?.length || !turn?.x?.length) return null;
        return { x: l.xaxis.range.slice(), y: l.yaxis.range.slice(), prevY: [Math.min(...prev.y), Math.max(...prev.y)], prevOpacity: prev.opacity, prevVisible: prev.visible, nav: window.avkTest.nav() };
      }), 15000);
    const inside = (r, v) => v >= r[0] && v <= r[1];
    // The region (±100 m), the turn and the vehicle are in view; the previous track reaches far
    // outside it (it is drawn, faded, there).
    for (const v of [-100, 100]) assert.ok(inside(view.x, v) && inside(view.y, v), `the region in view: ${JSON.stringify(view)}`);
    assert.ok(inside(view.x, view.nav.x_m) && inside(view.y, view.nav.y_m), `the vehicle in view: ${JSON.stringify(view)}`);
    assert.ok(view.y[0] > -200, `the view reaches ${view.y[0].toFixed(0)} m south for a previous track down to ${view.prevY[0].toFixed(0)} m: ${JSON.stringify(view)}`);
    assert.ok(view.prevY[0] < view.y[0], 'the previous track goes beyond the view');
    assert.equal(view.prevVisible, true);
    assert.ok(view.prevOpacity < 1, 'faded');
    await screenshot(page, 'live-fit-current-mission');
  } finally {
    await page.close();
  }
});

// ---------------------------------------------------------------- the turn panel

test('the turn panel leaves "Turn running" when the server says the turn ended', { timeout: slow(90000) }, async () => {
  errors.phase = 'panel';
  const page = await openLive();
  const status = () => page.textContent('#turn-status');
  try {
    // A turn of the mission shown that the page was told started (the stream's path), whose end
    // never reaches it.
    await page.evaluate((id) => window.avkTest.startTurn(90, 1.0, id), collected);
    await until('Turn running', async () => /^Turn running/.test(await status()), 10000, 100);
    // The stream's mission message has no running cell: the station's runner has ended it.
    const cells = (await api(`/missions/${collected}`)).cells;
    assert.ok(cells.length > 0 && cells.every((c) => !c.running));
    await page.evaluate(([id, c]) => window.avkTest.streamMessage('mission', { mission_id: id, state: 'done', helm_mode: null, cells: c }), [collected, cells]);
    await until('the panel to follow the mission message', async () => /^No turn running/.test(await status()), 10000, 100);
    assert.equal(await page.textContent('#turn-deviation'), '–');
    // Again, and this time the page reads the station over REST (as after a reconnection or a gap
    // in the stream): its report has no turn under way.
    await page.evaluate((id) => window.avkTest.startTurn(90, 1.0, id), collected);
    await until('Turn running again', async () => /^Turn running/.test(await status()), 10000, 100);
    await page.evaluate(() => window.avkTest.catchUp());
    await until('the panel to follow the report', async () => /^No turn running/.test(await status()), 15000, 100);
    assert.equal((await page.evaluate(() => window.avkTest.shownTurn()))?.running ?? false, false);
  } finally {
    await page.close();
  }
});

test("a small offset at a turn's start is inside the band at that time, a large one outside", { timeout: slow(90000) }, async () => {
  errors.phase = 'deviation';
  const answers = [];
  const page = await openLive();
  page.on('response', async (r) => {
    if (!r.url().includes('/maneuvers/ongoing?')) return;
    try {
      answers.push({ q: new URL(r.url()).searchParams, a: await r.json() });
    } catch {
      // a page closing
    }
  });
  try {
    // The table covers 1.0 m/s and its 90° cell has three turns: AVK with a corridor.
    await page.evaluate(() => window.avkTest.startTurn(90, 1.0));
    const shown = async (re) => until(`a deviation ${re}`, async () => {
      const t = await page.textContent('#turn-deviation');
      return re.test(t) ? t : null;
    }, 20000, 100);
    // 0.3 m to the side as the turn is commanded: GNSS noise. The corridor's half width there is
    // 0 m (every turn starts at the same pose), the band at that time is not, and the server's
    // verdict (inside_corridor) is the band's.
    await page.evaluate(() => window.avkTest.turnNavAt(0, 0.3, 0));
    const small = await shown(/^deviation 0\.3 m/);
    assert.equal(small, 'deviation 0.3 m (inside 90 % corridor)');
    // The page may show the answer before this listener has read its body: wait for it here too.
    const asked = await until('the deviation asked 0.3 m off', () => answers.find((x) => Math.abs(Number(x.q.get('mx')) - 0.3) < 1e-9), 20000, 100);
    assert.equal(asked.q.get('method'), 'avk');
    assert.ok(asked.a.half_width_m === 0 && asked.a.band_now.inside === true && asked.a.inside_corridor === true, `the half width at the start: ${asked.a.half_width_m} m; the band then: ${JSON.stringify(asked.a.band_now)}`);
    assert.match(await page.getAttribute('#turn-deviation', 'title'), /judged against the 90 % band 0\.0 s into the turn: /);
    // 3 m to the side a moment later: outside (the distance is to where the prediction, placed
    // over ground, has the vehicle then).
    await page.evaluate(() => window.avkTest.turnNavAt(0.1, 3, 0));
    const far = await until('the deviation asked 3 m off', () => answers.find((x) => Math.abs(Number(x.q.get('mx')) - 3) < 1e-9), 20000, 100);
    assert.equal(far.a.band_now.inside, false, JSON.stringify(far.a.band_now));
    const wanted = `deviation ${far.a.deviation_m.toFixed(1)} m (outside 90 % corridor)`;
    await until(`"${wanted}"`, async () => (await page.textContent('#turn-deviation')) === wanted, 20000, 100);
  } finally {
    await page.close();
  }
});

test('a page opened mid-turn judges the turn by the table from its first question', { timeout: slow(300000) }, async () => {
  errors.phase = 'mid-turn';
  const m = await api(`/vehicles/${vid}/missions`, { method: 'POST', body: { name: 'mid-turn', turn_array: { speeds_mps: [1.0], dheadings_deg: [90], repeats: 4 }, operating_region: REGION } });
  try {
    // A turn lasts some ten seconds here: open the page while one runs, again at the next turn if
    // that one ended before the page had read it.
    let seen = null;
    for (let attempt = 0; attempt < 4 && !seen; attempt++) {
      const rt = await until('a turn under way', async () => (await api(`/missions/${m.id}`)).running_turn, 120000, 250);
      const asks = [];
      const page = await openLive({ hooks: false, onRequest: (q) => q.url().includes('/maneuvers/ongoing?') && asks.push(new URL(q.url()).searchParams) });
      try {
        const adopted = await until('the page to show the turn or its end', () =>
          page.evaluate(() => {
            const s = document.getElementById('turn-status').textContent;
            return /^Turn running|^No turn running\. Last turn/.test(s) ? s : null;
          }), 20000, 100);
        if (!/^Turn running/.test(adopted)) continue; // it ended meanwhile: the next one
        const mine = await until('the deviation asked for this turn', () => {
          const q = asks.filter((a) => Math.abs(Number(a.get('x')) - rt.x_m) < 1e-6 && Math.abs(Number(a.get('y')) - rt.y_m) < 1e-6);
          return q.length ? q : null;
        }, 20000, 100);
        seen = mine.map((q) => q.get('method'));
        await screenshot(page, 'live-opened-mid-turn');
      } finally {
        await page.close();
      }
    }
    assert.ok(seen, 'a page opened while a turn ran');
    // The table covers 1.0 m/s: its first question is AVK's, not the instantaneous ray's (asked
    // before the page had read the table, it showed 10–12 m for a moment).
    assert.deepEqual([...new Set(seen)], ['avk'], JSON.stringify(seen));
  } finally {
    await api(`/missions/${m.id}/abort`, { method: 'POST' }).catch(() => {});
  }
});

test('no unexpected console errors', () => {
  assert.deepEqual(errors.console, [], 'console errors');
  assert.deepEqual(errors.page, [], 'uncaught errors in the page');
});

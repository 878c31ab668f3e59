// Live and Replay in the browser against a real `avk serve --sim` at real time (×1, so a turn
// lasts long enough to open a page in the middle of it), with a datum:
// - a page opened mid-turn draws the turn under way from the server's state, with its
//   predictions, the close-up's legend, the time series with the turn's start marked, the
//   latitude/longitude readout, the lat/lon grid and the scale bar;
// - a page opened after the mission shows its last turn (not "No turn yet");
// - Replay plays a stored mission back from its stored navigation and scrubs through it.
// Every wait is for a condition (web/tests/wait.mjs); nothing measures time.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';

import { slow, until } from './wait.mjs';
import { startAvkServer } from './avk_server.mjs';
import { AVK, webDir, launchBrowser, goView, screenshot, tearDown, killServerOnExit } from './browser.mjs';
import { localGrid, formatLatLon } from '../js/geo.js';

const DATUM = { lat_deg: 42.358456, lon_deg: -71.087589 };
const MISSION = {
  name: 'mid-turn',
  turn_array: { speeds_mps: [1.0], dheadings_deg: [150, 120], repeats: 2 },
  operating_region: { polygon_m: [[-100, -100], [100, -100], [100, 100], [-100, 100]], buffer_m: 25, return_point_m: [0, -70] },
};

const tmp = mkdtempSync(path.join(tmpdir(), 'avk-web-live-'));
let server = null;
let b = null; // {browser, context, newPage, errors}
let missionId = null;

async function api(pathname, init = {}) {
  const res = await fetch(`${server.base}/api/v1${pathname}`, {
    ...init,
    headers: { Authorization: `Bearer ${server.token}`, 'Content-Type': 'application/json', ...(init.headers ?? {}) },
    signal: AbortSignal.timeout(slow(10000)),
  });
  const text = await res.text();
  assert.ok(res.ok, `${init.method ?? 'GET'} ${pathname}: ${res.status} ${text}`);
  return text ? JSON.parse(text) : null;
}

async function openLive(onRequest = null) {
  const page = await b.newPage();
  if (onRequest) page.on('request', onRequest);
  await page.goto(`${server.base}/?test=1#live`);
  await until('the page synced', () => page.evaluate(() => window.avkTest?.state().vehicleId ?? null), 20000);
  return page;
}

before(async () => {
  b = await launchBrowser();
  server = await startAvkServer(AVK, ['serve', '--db', path.join(tmp, 'station.db'), '--sim', '--realtime-factor', '1', '--datum', `${DATUM.lat_deg},${DATUM.lon_deg}`, '--port', '0', '--web', webDir]);
  missionId = (await api('/vehicles/sim-usim/missions', { method: 'POST', body: JSON.stringify(MISSION) })).id;
});

after(() => tearDown({ browser: b?.browser, server, dir: tmp }));
killServerOnExit(() => server);

test('the report names the turn under way, and a page opened mid-turn draws it with its predictions', { timeout: slow(240000) }, async () => {
  // A page is opened while a turn runs; if that turn ends before the page has read the station,
  // the next turn is tried (four in the mission).
  let shown = null;
  let rt = null;
  let page = null;
  for (let attempt = 0; attempt < 4 && !shown; attempt++) {
    rt = await until(
      'a turn under way',
      async () => {
        const m = await api(`/missions/${missionId}`);
        return m.running_turn && (!rt || m.running_turn.t_s !== rt.t_s) ? m.running_turn : null;
      },
      120000,
      100,
    );
    // The report's turn as commanded: the goal is the start heading plus the signed change.
    assert.ok([150, 120].includes(Math.abs(rt.dheading_deg)), JSON.stringify(rt));
    assert.ok(Math.abs((((rt.heading_deg + rt.dheading_deg - rt.goal_heading_deg) % 360) + 540) % 360 - 180) < 1e-6, JSON.stringify(rt));
    await page?.close();
    page = await openLive();
    const seen = await until(
      'the page to show that turn, or the turn to end',
      async () => {
        const s = await page.evaluate(() => window.avkTest.shownTurn());
        if (s?.running && Math.abs(s.start.t - rt.t_s) < 1e-6) return { s };
        const m = await api(`/missions/${missionId}`);
        return m.running_turn?.t_s === rt.t_s ? null : { ended: true };
      },
      30000,
      100,
    );
    if (seen.s) shown = seen.s;
  }
  assert.ok(shown, 'a page opened mid-turn showed the turn under way');
  assert.deepEqual(shown.start, { t: rt.t_s, x: rt.x_m, y: rt.y_m, heading: rt.heading_deg });
  assert.equal(shown.dheading, rt.dheading_deg);
  assert.equal(shown.goalHeading, rt.goal_heading_deg);
  const panel = await page.evaluate(() => ({
    status: document.getElementById('turn-status').textContent,
    dpsi: document.getElementById('turn-cmd-dpsi').textContent,
    goal: document.getElementById('turn-cmd-goal').textContent,
  }));
  assert.match(panel.status, /^Turn running \(attempt \d\)/);
  assert.equal(Number(panel.dpsi), Math.round(rt.dheading_deg));
  assert.equal(Number(panel.goal), Number(rt.goal_heading_deg.toFixed(1)));

  // The instantaneous prediction at the turn's start pose, in the track plot and the close-up; the
  // close-up has a legend naming what it draws.
  const drawn = await until(
    'the prediction drawn',
    () =>
      page.evaluate(() => {
        const live = document.getElementById('live-plot');
        const close = document.getElementById('turn-plot');
        const inst = live.data?.find((t) => t.name === 'instantaneous prediction');
        if (!inst?.x?.length || !close._fullLayout) return null;
        const goal = live.data.find((t) => t.name === 'commanded goal heading');
        return {
          inst: [inst.x[0], inst.y[0]],
          goal: [goal.x[0], goal.y[0], goal.x[1], goal.y[1]],
          legend: close._fullLayout.showlegend,
          names: close.data.filter((t) => t.showlegend !== false && t.visible !== false && t.visible !== 'legendonly').map((t) => t.name),
        };
      }),
    30000,
  );
  assert.ok(Math.hypot(drawn.inst[0] - rt.x_m, drawn.inst[1] - rt.y_m) < 1e-6, 'the prediction starts at the turn start');
  const goalDir = (Math.atan2(drawn.goal[2] - drawn.goal[0], drawn.goal[3] - drawn.goal[1]) * 180) / Math.PI;
  assert.ok(Math.abs((((goalDir - rt.goal_heading_deg) % 360) + 540) % 360 - 180) < 1e-6, `goal ray along ${goalDir}`);
  assert.equal(drawn.legend, true, 'the close-up has a legend');
  for (const name of ['turn so far', 'instantaneous prediction', 'goal heading']) assert.ok(drawn.names.includes(name), `close-up legend lacks ${name}: ${drawn.names}`);

  // The time series: the stored history was read, and the turn's start is marked. The mark can be
  // drawn before the history has arrived (a new mark redraws at once), so the wait is for both.
  const series = await until(
    'the time series with the stored history and the turn marked',
    () =>
      page.evaluate((t0) => {
        const s = window.avkTest.series();
        const el = document.getElementById('live-series');
        const shapes = el._fullLayout?.shapes ?? [];
        if (s.length <= 10) return null;
        if (!s.marks.some((m) => Math.abs(m.t - t0) < 1e-6) || !shapes.some((sh) => Math.abs(sh.x0 - t0) < 1e-6)) return null;
        return { s, traces: el.data.map((t) => t.name) };
      }, rt.t_s),
    20000,
  );
  assert.ok(series.s.length > 10, `series of ${series.s.length} samples`);
  assert.deepEqual(series.traces, ['heading (°)', 'desired heading (°)', 'speed (m/s)', 'desired speed (m/s)', 'yaw rate (°/s)']);

  // Latitude and longitude through the datum, as geo.js (tested against GeographicLib) gives them.
  const ll = await page.evaluate(() => window.avkTest.latLon());
  assert.deepEqual(ll.datum, DATUM);
  assert.equal(ll.text, formatLatLon(localGrid(DATUM).toLatLon(ll.nav.x_m, ll.nav.y_m)));
  assert.match(ll.shown, /^\d+\.\d{6}° N, \d+\.\d{6}° W$/);

  // A dotted lat/lon grid over the region: each line one round latitude or longitude.
  const grat = await until('the lat/lon grid', () =>
    page.evaluate(() => {
      const t = document.getElementById('live-plot').data?.find((d) => /^lat\/lon grid/.test(d.name));
      return t?.visible === true ? { name: t.name, x: Array.from(t.x), y: Array.from(t.y) } : null;
    }), 10000);
  const step = Number(/\(([\d.e-]+)°\)/.exec(grat.name)?.[1]);
  assert.ok(step > 0, grat.name);
  const lines = [[]];
  grat.x.forEach((x, i) => (Number.isFinite(x) ? lines.at(-1).push(localGrid(DATUM).toLatLon(x, grat.y[i])) : lines.push([])));
  const round = (v) => Math.abs(v / step - Math.round(v / step)) < 1e-6;
  const gridLines = lines.filter((l) => l.length >= 2);
  assert.ok(gridLines.length >= 2, `${gridLines.length} grid lines`);
  for (const l of gridLines) {
    const constant = (k) => l.every((p) => Math.abs(p[k] - l[0][k]) < 1e-9) && round(l[0][k]);
    assert.ok(constant('lat') || constant('lon'), `a grid line of neither round latitude nor longitude: ${JSON.stringify(l.slice(0, 3))}`);
  }

  // A round scale bar a fifth of the plot wide at most, its pixels the plot's metres.
  const bar = await page.evaluate(() => {
    const el = document.getElementById('live-plot');
    const sb = el.parentElement.querySelector('.scale-bar');
    const xa = el._fullLayout.xaxis;
    return { m: Number(sb?.dataset.metres), px: Number(sb?.dataset.px), label: sb?.textContent, mPerPx: Math.abs(xa.range[1] - xa.range[0]) / xa._length, width: xa._length };
  });
  const mantissa = bar.m / 10 ** Math.floor(Math.log10(bar.m));
  assert.ok([1, 2, 5].some((v) => Math.abs(mantissa - v) < 1e-9), `scale ${bar.m}`);
  assert.ok(Math.abs(bar.px - bar.m / bar.mPerPx) < 0.5 && bar.px <= bar.width * 0.2 + 0.5, JSON.stringify(bar));
  assert.match(bar.label, /^\d+(\.\d+)? k?m$/);

  await screenshot(page, 'live-mid-turn');
  await page.close();
});

test('a page opened after the mission shows its last turn, not "No turn yet"', { timeout: slow(240000) }, async () => {
  // Two turns stored, then the mission is aborted (a third is likely under way: an aborted turn).
  await until('two stored turns', async () => (await api(`/missions/${missionId}`)).turn_list.length >= 2, 150000, 500);
  await api(`/missions/${missionId}/abort`, { method: 'POST' });
  await until('the mission aborted', async () => (await api(`/missions/${missionId}`)).status === 'aborted', 30000);
  const m = await api(`/missions/${missionId}`);
  const last = m.turn_list.at(-1);
  assert.ok(last, 'the mission stored turns');
  const predictAsks = [];
  const page = await openLive((q) => {
    if (q.url().includes('/predict?')) predictAsks.push(new URL(q.url()).searchParams);
  });
  const shown = await until('the last turn drawn', () => page.evaluate(() => window.avkTest.shownTurn()), 20000);
  assert.equal(shown.running, false);
  assert.equal(shown.ended, true);
  assert.equal(shown.dheading, last.goal_dheading_deg);
  const closeUp = await until(
    'the close-up of the last turn',
    () => page.evaluate(() => {
      const el = document.getElementById('turn-plot');
      return el._fullLayout && !el.classList.contains('plot-empty') ? el.data.map((t) => t.name) : null;
    }),
    20000,
  );
  assert.ok(closeUp.some((n) => /^turn \(/.test(n)), `close-up: ${closeUp}`);
  assert.match(await page.textContent('#turn-status'), /Last turn: /);
  // The mission's wasted conditioning episodes, counted as the report counts them.
  const episodes = m.condition_set.episodes;
  const wasted = `${episodes.interrupted ?? 0} interrupted, ${episodes.timeout ?? 0} timed out`;
  await until(`"${wasted}" shown`, async () => (await page.textContent('#live-cst')).includes(wasted), 20000);
  // The stored turn is drawn only against predictions that never saw it: the table and model are
  // asked without it (here the instantaneous turn alone may be all there is).
  await until('its predictions asked for', () => predictAsks.some((q) => q.get('method') === 'instantaneous'), 20000);
  for (const q of predictAsks) {
    if (q.get('method') !== 'instantaneous') assert.equal(q.get('without_turn'), String(last.id), `asked ${q}`);
  }
  await page.close();
});

test('Replay plays a stored mission back and scrubs through it', { timeout: slow(120000) }, async () => {
  const m = await api(`/missions/${missionId}`);
  const rows = [];
  for (let after; ; ) {
    const pageOf = await api(`/missions/${missionId}/nav?limit=10000${after ? `&after=${after}` : ''}`);
    rows.push(...pageOf.items);
    if (pageOf.next === null || pageOf.next === undefined) break;
    after = pageOf.next;
  }
  const events = (await api(`/missions/${missionId}/events?limit=1000`)).items;
  const page = await openLive();
  await goView(page, 'replay');
  await until('the mission in the picker', () => page.evaluate((id) => [...document.querySelectorAll('#rp-mission option')].some((o) => o.value === String(id)), missionId), 15000);
  await page.selectOption('#rp-mission', String(missionId));
  await page.click('#rp-load');
  const loaded = await until('the mission loaded', () => page.evaluate(() => (window.avkTest.replay().t0 !== undefined ? window.avkTest.replay() : null)), 30000);
  assert.equal(loaded.id, missionId);
  assert.equal(loaded.t0, rows[0].t_s);
  assert.equal(loaded.t1, rows.at(-1).t_s);

  // The middle of the first turn: the vehicle where the stored samples around it put it.
  const turn = m.turn_list[0];
  const tMid = (turn.start_time_s + turn.end_time_s) / 2;
  // From here on the predictions asked for are the replayed turn's (Live asked for its own at load).
  const predictAsks = [];
  page.on('request', (q) => {
    if (q.url().includes('/predict?')) predictAsks.push(new URL(q.url()).searchParams);
  });
  await page.evaluate((t) => window.avkTest.replaySeek(t), tMid);
  const j = rows.findIndex((r) => r.t_s > tMid);
  const a = rows[j - 1];
  const c = rows[j];
  const f = (tMid - a.t_s) / (c.t_s - a.t_s);
  const expected = [a.x_m + f * (c.x_m - a.x_m), a.y_m + f * (c.y_m - a.y_m)];
  const at = await until(
    'the replayed moment drawn',
    () =>
      page.evaluate((t) => {
        const el = document.getElementById('rp-plot');
        const v = el.data?.find((q) => q.name === 'vehicle');
        const inst = el.data?.find((q) => q.name === 'instantaneous prediction');
        const series = document.getElementById('rp-series')._fullLayout;
        if (!v || Math.abs(window.avkTest.replay().t - t) > 1e-9 || !inst?.x?.length) return null;
        return {
          vehicle: [v.x[0], v.y[0]],
          turn: document.getElementById('rp-turn').textContent,
          events: document.querySelectorAll('#rp-events li:not(.muted)').length,
          cursor: series?.shapes?.some((s) => Math.abs(s.x0 - t) < 1e-9 && s.line.color === '#000000'),
          inst: [inst.x[0], inst.y[0]],
        };
      }, tMid),
    30000,
  );
  assert.ok(Math.hypot(at.vehicle[0] - expected[0], at.vehicle[1] - expected[1]) < 1e-6, `vehicle ${at.vehicle} vs ${expected}`);
  // Numbered as Live numbers it: the ok turns done of the plan ("Turn 1/4"), or an attempt at one.
  const planned = m.cells.reduce((n, c) => n + (c.planned ?? 1), 0);
  assert.match(at.turn, new RegExp(`^${turn.status === 'ok' ? 'Turn' : 'Attempt at turn'} 1/${planned} under way`));
  // A replayed turn is shown only against predictions that never saw its mission: this vehicle
  // has no other mission and no model, so only the instantaneous turn is asked for, and the panel
  // says why the others are missing.
  assert.match(at.turn, /Predictions are made without this mission's turns; no AVK table or yaw model without them\./);
  assert.ok(predictAsks.length > 0, 'a prediction was asked for');
  assert.deepEqual([...new Set(predictAsks.map((q) => q.get('method')))], ['instantaneous']);
  assert.equal(at.events, Math.min(100, events.filter((e) => e.t_s <= tMid).length));
  assert.equal(at.cursor, true, 'the time series marks the replayed moment');
  // The prediction placed at the turn's start, the stored sample at its commanding time.
  const s = rows.findIndex((r) => r.t_s >= turn.start_time_s);
  assert.ok(Math.hypot(at.inst[0] - rows[s].x_m, at.inst[1] - rows[s].y_m) < 0.5, `prediction from ${at.inst}`);

  await screenshot(page, 'replay');

  // The slider moves the moment; Play runs it forward at the chosen speed.
  await page.$eval('#rp-slider', (el, v) => {
    el.value = String(v);
    el.dispatchEvent(new Event('input', { bubbles: true }));
  }, rows[0].t_s + 5);
  assert.ok(Math.abs((await page.evaluate(() => window.avkTest.replay().t)) - (rows[0].t_s + 5)) < 0.11);
  // At 2× the rest of the mission takes longer than the test needs to see it move and pause it.
  await page.selectOption('#rp-speed', '2');
  await page.click('#rp-play');
  assert.equal(await page.getAttribute('#rp-play', 'aria-pressed'), 'true');
  await until('the replay to advance', () => page.evaluate((t) => window.avkTest.replay().t > t + 0.5, rows[0].t_s + 5), 20000);
  await page.click('#rp-play');
  const paused = await page.evaluate(() => window.avkTest.replay());
  assert.equal(paused.playing, false);
  assert.ok(paused.t < paused.t1, 'paused before the end');
  await page.close();
});

test('no console errors', () => {
  assert.deepEqual(b.errors, []);
});

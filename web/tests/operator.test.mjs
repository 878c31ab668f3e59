// Browser tests of what an operator on the shore reads and does (times, the banner, the event
// log, field errors, a new mission's track, the turn table, alarms, keyboard shortcuts, the dark
// theme): a real `avk serve --sim` at a low real-time factor (×10, so
// a mission is seen running) and Debian's Chromium through playwright-core. Run with
// `node --test web/tests/operator.test.mjs` (CTest: web_operator).
//
// Environment as e2e.test.mjs: AVK_BINARY, AVK_SCREENSHOTS, AVK_CHROMIUM, AVK_E2E_SLOW; with
// AVK_UPDATE_DOC_SCREENSHOTS=1 the alarm screenshot is copied to docs/screenshots/.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { copyFileSync, mkdirSync, mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

import { slow, until } from './wait.mjs';
import { startAvkServer, apiRequest } from './avk_server.mjs';
import { AVK, SHOTS, DOC_SHOTS, webDir, repo, checkPrerequisites, launchChromium, openPage, showView, tearDown, killServerOnExit } from './browser.mjs';

const FACTOR = '10';
const tmp = mkdtempSync(path.join(tmpdir(), 'avk-web-operator-'));
let server = null;
let browser = null;
let context = null;
let page = null;
const errors = { console: [], page: [], phase: 'load' };
const TABLET = { width: 768, height: 1024 };
const DESKTOP = { width: 1280, height: 800 };

function startServer(port = 0) {
  return startAvkServer(AVK, ['serve', '--db', path.join(tmp, 'station.db'), '--sim', '--realtime-factor', FACTOR, '--port', String(port), '--web', webDir]);
}

const api = (pathname, options) => apiRequest(server, pathname, options);

async function shot(name) {
  const file = path.join(SHOTS, `${name}.png`);
  await page.screenshot({ path: file, fullPage: false, timeout: slow(20000) });
  return file;
}

const hook = (name, ...args) => page.evaluate(([n, a]) => window.avkTest[n](...a), [name, args]);

before(async () => {
  mkdirSync(SHOTS, { recursive: true });
  checkPrerequisites();
  server = await startServer();
  browser = await launchChromium();
  context = await browser.newContext({ colorScheme: 'light' });
  page = await openPage(context, TABLET, errors);
  await page.goto(`${server.base}/?token=${server.token}&test=1#live`, { waitUntil: 'load', timeout: slow(20000) });
  await page.waitForFunction(() => document.getElementById('link-badge')?.textContent === 'LIVE', null, { timeout: slow(20000) });
  await page.waitForFunction(() => window.Plotly && document.querySelector('#live-plot .main-svg'), null, { timeout: slow(20000) });
});

after(() => tearDown({ browser, server, dir: tmp }));
killServerOnExit(() => server);

// ---------------------------------------------------------------- the modules on their own

test('the event log merges one happening into one entry, names kinds in words and counts repeats', async () => {
  const { logEntries, phrase } = await import(pathToFileURL(path.join(webDir, 'js/eventlog.js')).href);
  assert.equal(phrase('mission_detached'), 'Mission left the vehicle');
  assert.equal(phrase('turn_aborted'), 'Turn aborted');
  assert.equal(phrase('some_new_kind'), 'some new kind', 'an unknown kind reads as its name with spaces');
  assert.equal(phrase('link', 'navigation STALE: all stop until it is back'), 'Navigation lost');
  const reason = 'aborted by the operator';
  const events = [
    // A pause: the stored event, its stream status, and the state change.
    { t: 10, kind: 'pause', level: 'info', message: 'paused by the operator', logged: true },
    { t: 10, kind: 'pause', level: 'info', message: 'paused by the operator' },
    { t: 10, kind: 'mission_paused', level: 'info', message: 'paused by the operator' },
    // An abort: the turn under way, the stop, the state change, the mission leaving the vehicle.
    { t: 20, kind: 'turn_aborted', level: 'warning', message: `1.0 m/s 40°: ${reason}; re-queued` },
    { t: 20, kind: 'aborted', level: 'warning', message: reason },
    { t: 20, kind: 'mission_aborted', level: 'info', message: reason },
    { t: 20.2, kind: 'mission_detached', level: 'info', message: 'mission 1 aborted' },
  ];
  const log = logEntries(events, []);
  assert.deepEqual(log.map((e) => e.canon), ['pause', 'aborted'], JSON.stringify(log));
  assert.equal(log[1].severity, 'warning');
  // The same condition again and again: one line, ×n.
  const flapping = [1, 2, 3].map((t) => ({ t, kind: 'condition_set_timeout', level: 'warning', message: 'conditions not set in 120 s' }));
  const collapsed = logEntries(flapping, []);
  assert.equal(collapsed.length, 1);
  assert.equal(collapsed[0].count, 3);
  // A stop the operator did not ask for is an error; a finished turn is placed by its time.
  const mixed = logEntries([{ t: 5, kind: 'returning', level: 'info', message: 'x' }, { t: 50, kind: 'halted', level: 'warning', message: 'left the region' }], [{ t: 30, kind: 'turn_finished', level: 'info', message: 'turn 1/4' }]);
  assert.deepEqual(mixed.map((e) => [e.kind, e.severity]), [['returning', 'info'], ['turn_finished', 'ok'], ['halted', 'error']]);
  // Containment entered again within the same second, a little further on: the same words with
  // other numbers are one entry ×2, not two entries; a second later it is news again.
  const buffer = (t, x) => ({ t, kind: 'containment', level: 'warning', message: `entered the buffer zone at (${x}, 3.0) m: heading for the interior` });
  const near = logEntries([buffer(100.1, '120.0'), buffer(100.7, '120.4'), buffer(101.6, '121.3')], []);
  assert.deepEqual(near.map((e) => [e.count, e.message]), [[2, buffer(0, '120.0').message], [1, buffer(0, '121.3').message]], JSON.stringify(near));
  assert.deepEqual(near[0].variants, [buffer(0, '120.4').message]);
  // Other words (during a turn) are not merged, however close.
  const other = logEntries([buffer(100.1, '120.0'), { ...buffer(100.2, '120.1'), message: 'entered the buffer zone during a turn at (120.1, 3.0) m: heading for the interior' }], []);
  assert.equal(other.length, 2);
});

test('a turn has one number in every view: the ok turns done of the plan', async () => {
  const { storedTurnLabel, plannedTurns } = await import(pathToFileURL(path.join(webDir, 'js/turnlabel.js')).href);
  const rows = [{ status: 'ok' }, { status: 'aborted' }, { status: 'rejected' }, { status: 'ok' }, { status: 'ok' }];
  const planned = plannedTurns([{ planned: 2 }, { planned: 2 }, {}]);
  assert.equal(planned, 5);
  assert.deepEqual(rows.map((r) => storedTurnLabel(rows, r, planned)), ['turn 1/5', 'attempt at turn 2/5', 'attempt at turn 2/5', 'turn 2/5', 'turn 3/5']);
});

test('the station clock maps to wall time by /health, and only for missions of this session', async () => {
  const clock = await import(pathToFileURL(path.join(webDir, 'js/clock.js')).href);
  const nowMs = Date.now();
  clock.setClockMapping({ utc_ms: nowMs, clock_s: 1000, realtime_factor: 10 });
  // 100 s of station clock before now at ×10 is 10 s of wall time before.
  assert.equal(clock.wallMs(900), nowMs - 10_000);
  assert.equal(clock.fmtElapsed(3725), '1:02:05');
  assert.equal(clock.fmtElapsed(65), '01:05');
  const created = new Date(nowMs - 20_000).toISOString();
  assert.ok(clock.inSession({ started_s: 800, created_utc: created }), 'started 20 s ago by both clocks');
  const old = { started_s: 800, created_utc: '2020-01-01T00:00:00.000Z' };
  assert.ok(!clock.inSession(old), 'a mission of an earlier session');
  assert.ok(!clock.inSession({ started_s: 1500, created_utc: created }), 'started after this session\'s now: another clock');
  assert.ok(!clock.inSession({ started_s: 990, created_utc: new Date(nowMs - 5_000).toISOString() }), 'created 4 s before the time its start maps to: the station was down meanwhile');
  // With the session's start clock from the server the answer is exact, whatever created_utc says.
  clock.setClockMapping({ utc_ms: nowMs, clock_s: 1000, realtime_factor: 10, session_start_clock_s: 700 });
  assert.ok(clock.inSession({ started_s: 800, created_utc: '2020-01-01T00:00:00.000Z' }), 'started after this session began');
  assert.ok(!clock.inSession({ started_s: 650, created_utc: created }), 'started before this session began');
  clock.setClockMapping({ utc_ms: nowMs, clock_s: 1000, realtime_factor: 10 });
  const l = clock.timeLabel(860, old);
  assert.equal(l.wall, false);
  assert.equal(l.text, 'T+01:00', 'an earlier session: the time since the mission started');
  assert.match(l.title, /station clock 860\.0 s/);
  assert.match(l.title, /2020-01-01/);
  // Its start and end were stored in wall-clock time: shown as such, in any session.
  const stored = { ...old, ended_s: 1400, started_utc: '2020-01-01T00:00:05.000Z', ended_utc: '2020-01-01T00:01:05.000Z' };
  const s0 = clock.timeLabel(800, stored);
  assert.equal(s0.wall, true);
  assert.equal(s0.text, clock.fmtLocal(Date.parse('2020-01-01T00:00:05.000Z')));
  assert.match(s0.title, /2020-01-01 00:00:05\.0 UTC · station clock 800\.0 s .*earlier server session/);
  assert.equal(clock.timeLabel(1400, stored).text, clock.fmtLocal(Date.parse('2020-01-01T00:01:05.000Z')));
  assert.equal(clock.timeLabel(860, stored).text, 'T+01:00', 'other times of it: still the elapsed time');
  const now = clock.timeLabel(1000, null);
  assert.equal(now.wall, true);
  assert.match(now.text, /^\d\d:\d\d:\d\d$/);
  assert.match(now.title, /UTC · station clock 1000\.0 s/);
  // A mission's elapsed time by the wall clock: from its stored start to the server's now while it
  // runs (67 s after the start, whatever the station clock's ×10 says), else to its stored end.
  clock.setClockMapping({ utc_ms: Date.now(), clock_s: 1000, realtime_factor: 10 });
  // The server's now is given, not read: the answer may not depend on how long the test takes.
  const serverNow = Date.parse('2020-01-01T00:10:00.000Z');
  const live = { live: true, started_s: 330, started_utc: new Date(serverNow - 67_000).toISOString(), created_utc: created };
  assert.equal(clock.missionWallElapsed(live, serverNow), 67);
  assert.equal(clock.missionElapsed(live, 1000), 670, 'the station clock ran ×10 meanwhile');
  assert.equal(clock.missionWallElapsed(stored), 60, 'an ended mission: its stored end less its stored start');
  assert.equal(clock.missionWallElapsed({ ...old, started_utc: null }), null, 'no wall-clock start known');
  const { meanSd } = await import(pathToFileURL(path.join(webDir, 'js/format.js')).href);
  assert.equal(meanSd({ mean: 2, sd: 0 }, 1, ' s', 1), '2.0 s', 'a mean of one value has no ± 0.0');
  assert.equal(meanSd({ mean: 2, sd: 0.5 }, 1, ' s', 3), '2.0 ± 0.5 s');
});

test('the store link: the spool bar says how many writes wait, the engine shows for PostgreSQL only', async () => {
  const { storeNotice, pollsHealth } = await import(pathToFileURL(path.join(webDir, 'js/storelink.js')).href);
  const pg = { engine: 'postgresql', state: 'connected', spooled: 0, spool: '/var/lib/avk/station.spool', last_error: null };
  assert.deepEqual(storeNotice({ engine: 'sqlite', state: 'connected', spooled: 0, spool: null, last_error: null }), { engine: null, spooling: false, text: '', title: '' });
  assert.deepEqual(storeNotice(undefined), { engine: null, spooling: false, text: '', title: '' }, 'an older server says nothing of its store');
  assert.deepEqual(storeNotice(pg), { engine: 'PostgreSQL', spooling: false, text: '', title: '' });
  const out = storeNotice({ ...pg, state: 'spooling', spooled: 42, last_error: 'connection refused' });
  assert.equal(out.spooling, true);
  assert.equal(out.text, 'Database unreachable — recording into the local spool (42 writes waiting); they are written when the server is back');
  assert.equal(out.title, 'Last error: connection refused\nSpool: /var/lib/avk/station.spool');
  assert.match(storeNotice({ ...pg, state: 'spooling', spooled: 1 }).text, /\(1 write waiting\)/);
  assert.match(storeNotice({ ...pg, state: 'spooling', spooled: null }).text, /\(writes waiting\)/);
  assert.equal(storeNotice({ ...pg, state: 'spooling' }).title.split('\n')[0], 'The database server cannot be reached');
  assert.deepEqual([pollsHealth(pg), pollsHealth({ engine: 'sqlite', state: 'connected' }), pollsHealth(undefined)], [true, false, false]);
});

// ---------------------------------------------------------------- the page

test('Live shows wall-clock time with UTC and the station clock on hover', { timeout: slow(60000) }, async () => {
  errors.phase = 'clock';
  const mapping = await until('the clock mapping from /health', () => hook('clock'), 15000);
  assert.equal(mapping.factor, Number(FACTOR));
  const wall = await until('the wall-clock readout', async () => {
    const w = await page.evaluate(() => ({ text: document.getElementById('live-wall').textContent, title: document.getElementById('live-wall').title }));
    return /^\d\d:\d\d:\d\d$/.test(w.text) ? w : null;
  }, 15000);
  assert.match(wall.title, /\d{4}-\d\d-\d\d \d\d:\d\d:\d\d\.\d UTC · station clock \d+\.\d s/);
  // The wall clock shown is the server's now, within a minute (the machine's clock and the
  // server's are the same here; this is not a timing check, only that the mapping is not off by
  // the station clock).
  const shownUtc = Date.parse(wall.title.slice(0, 19).replace(' ', 'T') + 'Z');
  assert.ok(Math.abs(shownUtc - Date.now()) < 60000, `${wall.title} vs ${new Date().toISOString()}`);
  assert.match(await page.textContent('#live-t'), /^\d+\.\d$/, 'the station clock stays in the readout');
});

test('a bad mission names the field by its label, not a JSON pointer', { timeout: slow(60000) }, async () => {
  errors.phase = 'bad-mission';
  await showView(page, 'mission');
  await page.fill('#m-name', 'bad');
  await page.fill('#m-speeds', '99');
  await page.fill('#m-polygon', '-100, -100\n100, -100');
  await page.click('#m-start');
  const speedErr = page.locator('.field[data-pointer="/turn_array/speeds_mps"] .field-error').first();
  await speedErr.waitFor({ state: 'visible', timeout: slow(10000) });
  const text = await speedErr.textContent();
  assert.match(text, /^Speeds \(m\/s\) — item 1: must be in/);
  assert.doesNotMatch(text, /\/turn_array/);
  assert.equal(await speedErr.getAttribute('data-field'), '/turn_array/speeds_mps/0', 'the pointer is kept for the file writer');
  const all = await page.locator('.field-error, #m-general-errors li').allTextContents();
  assert.ok(all.length >= 2, JSON.stringify(all));
  for (const t of all) assert.doesNotMatch(t, /^\//, `a message starts with a pointer: ${t}`);
  await page.fill('#m-speeds', '1.0, fast');
  await page.click('#m-start');
  await page.waitForSelector('.field-error:has-text("Speeds (m/s) — item 2: “fast” is not a number")', { timeout: slow(5000) });
});

let missionA = null;
const N_TURNS = 8;

test('a running mission: the state banner above the fold on a tablet, Start disabled and why', { timeout: slow(90000) }, async () => {
  errors.phase = 'mission';
  await showView(page, 'mission');
  await page.fill('#m-name', 'operator-a');
  await page.fill('#m-speeds', '1.0, 1.5');
  await page.fill('#m-dheadings', '40, 90');
  await page.fill('#m-repeats', '2');
  await page.fill('#m-polygon', '-150, -150\n150, -150\n150, 150\n-150, 150');
  await page.fill('#m-buffer', '25');
  await page.fill('#m-return', '0, -70');
  await page.click('#m-start');
  await page.waitForFunction(() => /Mission \d+ started/.test(document.getElementById('m-result').textContent), null, { timeout: slow(15000) });
  missionA = Number((await page.textContent('#m-result')).match(/Mission (\d+)/)[1]);
  // Disabled while the request is under way, then because the mission holds the vehicle.
  const title = await until('Start disabled while the mission runs, saying why', async () => {
    const t = await page.getAttribute('#m-start', 'title');
    return (await page.isDisabled('#m-start')) && /is (running|created)/.test(t) ? t : null;
  }, 15000);
  assert.match(title, new RegExp(`Mission ${missionA} “operator-a” is (running|created): one mission at a time`));

  await showView(page, 'live');
  const banner = await until('the running banner', () =>
    page.evaluate(() => {
      const b = document.getElementById('mission-banner');
      return b.dataset.state === 'running' && /\d\d:\d\d/.test(document.getElementById('mb-elapsed').textContent)
        ? { text: b.textContent, cls: b.className, rect: b.getBoundingClientRect().toJSON(), turns: document.getElementById('mb-turns').textContent }
        : null;
    }), 20000);
  assert.match(banner.text, /RUNNING/);
  assert.match(banner.text, new RegExp(`mission ${missionA} “operator-a”`));
  assert.match(banner.turns, new RegExp(`^\\d+ of ${N_TURNS}$`));
  assert.ok(banner.cls.includes('ms-running'));
  assert.ok(banner.rect.top >= 0 && banner.rect.bottom <= TABLET.height, `the banner is above the fold: ${JSON.stringify(banner.rect)}`);
  // Elapsed time runs.
  const e0 = await page.textContent('#mb-elapsed');
  await until('the elapsed time to advance', async () => (await page.textContent('#mb-elapsed')) !== e0, 15000);
  // It is the wall-clock time since the start, and says so (it showed the station clock, ×10
  // here: "elapsed 11:04" 67 s after a start); the station clock's is beside it, labelled.
  const startMs = Date.parse((await api(`/missions/${missionA}`)).started_utc);
  await until('5 s of wall-clock time since the start', async () => Date.now() - startMs > 5000, 20000, 200);
  const from = (Date.now() - startMs) / 1000;
  const shown = await page.evaluate(() => {
    const t = (id) => document.getElementById(id)?.textContent ?? null;
    return { wall: t('mb-elapsed'), clock: t('mb-elapsed-clock'), station: t('mb-station-elapsed'), stationClock: t('mb-station-clock'), stationShown: document.getElementById('mb-station')?.hidden === false };
  });
  const to = (Date.now() - startMs) / 1000;
  const secs = (text) => text.split(':').reduce((a, v) => a * 60 + Number(v), 0);
  // The banner is redrawn every second: it may lag the moment it is read, never lead it.
  assert.ok(secs(shown.wall) <= to + 1 && secs(shown.wall) >= from - 10, `elapsed ${shown.wall} read ${from.toFixed(1)}–${to.toFixed(1)} s of wall-clock time after the start`);
  assert.equal(shown.clock, 'wall clock');
  assert.ok(shown.stationShown, 'the station clock beside it');
  assert.equal(shown.stationClock, `station clock ×${FACTOR}`);
  assert.ok(secs(shown.station) > secs(shown.wall), `the station clock runs ×${FACTOR}: ${JSON.stringify(shown)}`);
  await shot('operator-running-tablet');
});

test('finished turns are listed with advance and transfer, times as local wall time', { timeout: slow(120000) }, async () => {
  errors.phase = 'mission';
  await showView(page, 'live');
  const li = await until('a finished turn in the event log', () =>
    page.evaluate(() => {
      const e = document.querySelector('#event-log li[data-kind="turn_finished"]');
      return e ? { text: e.textContent, cls: e.className, time: e.querySelector('time')?.textContent, title: e.querySelector('time')?.title } : null;
    }), 90000, 500);
  assert.match(li.text, /Turn finished/);
  assert.match(li.text, /turn \d\/8: \d\.\d\d m\/s, Δψ [+-]?\d+°, advance -?\d+\.\d m, transfer -?\d+\.\d m/);
  // Numbered one way, newest first: k/8 … 1/8.
  const numbers = await page.evaluate(() => [...document.querySelectorAll('#event-log li[data-kind="turn_finished"] .msg')].map((e) => Number(e.textContent.match(/^turn (\d+)\//)[1])));
  assert.deepEqual(numbers, numbers.map((_, i) => numbers.length - i), JSON.stringify(numbers));
  assert.ok(li.cls.includes('sev-ok'));
  assert.match(li.time, /^\d\d:\d\d:\d\d$/);
  assert.match(li.title, /UTC · station clock \d+\.\d s · mission T\+\d\d:\d\d/);
});

test('pause and abort are one entry each, with their severity in words', { timeout: slow(90000) }, async () => {
  errors.phase = 'mission';
  await api(`/missions/${missionA}/pause`, { method: 'POST' });
  await until('the paused banner', () => page.evaluate(() => document.getElementById('mission-banner').dataset.state === 'paused'), 15000);
  assert.match(await page.textContent('#mb-state'), /PAUSED/);
  await until('the pause in the log', async () => (await hook('eventLog')).some((e) => e.kind === 'pause' || e.kind === 'mission_paused'), 10000);
  await api(`/missions/${missionA}/resume`, { method: 'POST' });
  await until('running again', () => page.evaluate(() => document.getElementById('mission-banner').dataset.state === 'running'), 15000);
  await api(`/missions/${missionA}/abort`, { method: 'POST' });
  await until('the aborted banner', () => page.evaluate(() => document.getElementById('mission-banner').dataset.state === 'aborted'), 15000);
  // The stream's status messages, then the stored log read again: still one entry each.
  await until('the abort in the log', async () => (await hook('eventLog')).some((e) => e.kind === 'aborted' || e.kind === 'mission_aborted'), 10000);
  // The mission leaving the vehicle follows the abort on the stream.
  await until('mission_detached from the stream', async () => (await hook('events')).some((e) => e.kind === 'mission_detached'), 15000);
  const log = await hook('eventLog');
  const count = (kinds) => log.filter((e) => kinds.includes(e.kind)).length;
  assert.equal(count(['aborted', 'mission_aborted']), 1, JSON.stringify(log));
  assert.equal(count(['mission_detached']), 0, `the mission leaving the vehicle is part of the abort: ${JSON.stringify(log)}`);
  assert.equal(count(['pause', 'mission_paused']), 1, JSON.stringify(log));
  const abortLi = await page.evaluate(() => {
    const e = document.querySelector('#event-log li[data-kind="aborted"], #event-log li[data-kind="mission_aborted"]');
    return { cls: e.className, sev: e.querySelector('.sev').textContent, kind: e.querySelector('.kind').textContent, border: getComputedStyle(e).borderLeftWidth };
  });
  assert.equal(abortLi.kind, 'Mission aborted');
  assert.match(abortLi.sev, /warning/);
  assert.ok(abortLi.cls.includes('sev-warning'));
  assert.ok(parseFloat(abortLi.border) >= 5, `a coloured left border: ${abortLi.border}`);
  for (const k of await page.locator('#event-log .kind').allTextContents()) assert.doesNotMatch(k, /_/, `an internal name in the log: ${k}`);
  await until('Start enabled again', async () => !(await page.isDisabled('#m-start')), 15000);
});

test('Live and Replay give a turn of mission A the same number', { timeout: slow(90000) }, async () => {
  errors.phase = 'mission';
  const a = await api(`/missions/${missionA}`);
  const okRows = a.turn_list.filter((r) => r.status === 'ok');
  assert.ok(okRows.length >= 1, `mission A has a finished turn: ${JSON.stringify(a.turn_list.map((r) => r.status))}`);
  // Live's event log: "turn k/8: …" for the k-th finished turn.
  await showView(page, 'live');
  const live = await until("mission A's finished turns in the Live log", () =>
    page.evaluate(() => {
      const msgs = [...document.querySelectorAll('#event-log li[data-kind="turn_finished"] .msg')].map((e) => e.textContent).reverse();
      return msgs.length ? msgs : null;
    }), 15000);
  assert.equal(live.length, okRows.length, JSON.stringify(live));
  // Replay, at the middle of each stored turn: the same number for an ok turn, and an attempt
  // that did not count named as an attempt at the next one.
  await showView(page, 'replay');
  try {
    await replayNumbers(a, live);
  } finally {
    await showView(page, 'live'); // the next tests read Live
  }
});

async function replayNumbers(a, live) {
  await until('mission A in the picker', () => page.evaluate((id) => [...document.querySelectorAll('#rp-mission option')].some((o) => o.value === String(id)), missionA), 15000);
  await page.selectOption('#rp-mission', String(missionA));
  await page.click('#rp-load');
  await until('mission A loaded', () => page.evaluate((id) => window.avkTest.replay().id === id && !window.avkTest.replay().loading, missionA), 30000);
  let ok = 0;
  for (const r of a.turn_list) {
    const t = (r.start_time_s + r.end_time_s) / 2;
    const text = await until(`the replayed turn at ${t}`, () =>
      page.evaluate((tm) => {
        window.avkTest.replaySeek(tm);
        // Drawn at the next frame: the time readout names the moment once it is.
        if (!document.getElementById('rp-time').textContent.includes(`${tm.toFixed(1)} s`)) return null;
        const s = document.getElementById('rp-turn').textContent;
        return / under way/.test(s) ? s : null;
      }, t), 10000);
    if (r.status === 'ok') {
      ok++;
      assert.ok(text.startsWith(`Turn ${ok}/${N_TURNS} under way`), `Replay: ${text}`);
      assert.ok(live[ok - 1].startsWith(`turn ${ok}/${N_TURNS}:`), `Live: ${live[ok - 1]}`);
    } else {
      assert.ok(text.startsWith(`Attempt at turn ${ok + 1}/${N_TURNS} under way`), `Replay: ${text}`);
    }
  }
}

let missionB = null;

test("a new mission draws its own track; the previous one's is faded grey", { timeout: slow(90000) }, async () => {
  errors.phase = 'mission';
  const before = await page.evaluate(() => window.avkTest.trackLength());
  assert.ok(before > 10, `mission ${missionA} left a track of ${before} points`);
  const mission = JSON.parse(readFileSync(path.join(repo, 'examples/thesis-fig4-1.json'), 'utf8'));
  missionB = (await api('/vehicles/sim-usim/missions', { method: 'POST', body: { ...mission, name: 'operator-b' } })).id;
  await until('the new mission in Live', async () => (await hook('mission'))?.id === missionB, 15000);
  const prev = await until('the previous track', () => hook('previousTrack'), 10000);
  assert.equal(prev.missionId, missionA);
  assert.ok(prev.points > 1);
  const traces = await until('the previous track drawn', () =>
    page.evaluate(() => {
      const d = document.getElementById('live-plot').data ?? [];
      const old = d.find((t) => /track \(previous\)$/.test(t.name));
      const cur = d.filter((t) => t.name === 'track');
      return old && old.x.length > 1 ? { old: { name: old.name, color: old.line.color, opacity: old.opacity, n: old.x.length }, cur: cur.map((t) => t.line.color) } : null;
    }), 15000);
  assert.match(traces.old.name, new RegExp(`mission ${missionA} track`));
  assert.equal(traces.old.color, '#8a8f98', 'grey');
  assert.ok(traces.old.opacity < 1, 'faded');
  assert.ok(traces.cur.every((c) => c === '#0072B2'), `the new track in the track colour: ${traces.cur}`);
  assert.ok(!traces.cur.includes(traces.old.color));
  await shot('operator-new-mission');
});

test('between turns the turn table shows no commanded turn', { timeout: slow(90000) }, async () => {
  errors.phase = 'mission';
  await showView(page, 'live');
  const seen = await until('a moment between turns with a desired heading', () =>
    page.evaluate(() => {
      const t = (id) => document.getElementById(id).textContent;
      if (t('live-mode') === 'TURNING' || t('live-dheading') === '–' || !/No turn running/.test(t('turn-status'))) return null;
      return { goal: t('turn-cmd-goal'), dpsi: t('turn-cmd-dpsi'), speed: t('turn-cmd-speed'), mode: t('live-mode'), desired: t('live-dheading') };
    }), 30000, 100);
  assert.deepEqual([seen.goal, seen.dpsi, seen.speed], ['–', '–', '–'], JSON.stringify(seen));
});

test('the Model view gives history in seconds; the CKT n colour bar has whole-number ticks', { timeout: slow(60000) }, async () => {
  errors.phase = 'views';
  const text = await page.evaluate(async () => (await import('/js/model.js')).historyText({ history: 100, rate_hz: 10 }));
  assert.equal(text, '10.0 s (100 samples)');
  await showView(page, 'model');
  await page.waitForSelector('#models-table th', { timeout: slow(10000) });
  const heads = await page.locator('#models-table th').allTextContents();
  assert.ok(heads.includes('history (s)'), JSON.stringify(heads));
  assert.equal(await page.textContent('label[for="model-history"]'), 'History (s)');
  await until('a stored ok turn', async () => (await api('/turns?status=ok&limit=1')).items.length > 0, 60000, 500);
  await showView(page, 'ckt');
  await page.selectOption('#ckt-metric', 'n');
  await page.click('#ckt-refresh');
  const bar = await until('the heat map', () =>
    page.evaluate(() => {
      const t = document.getElementById('ckt-heatmap').data?.[0];
      return t?.type === 'heatmap' ? t.colorbar : null;
    }), 20000);
  assert.equal(bar.tickformat, 'd');
  assert.ok(Number.isInteger(bar.dtick) && bar.dtick >= 1, JSON.stringify(bar));
});

test('the missions table stays inside its panel at 1280×800 and 768×1024, every time labelled with its clock', { timeout: slow(60000) }, async () => {
  errors.phase = 'layout';
  const clock = await import(pathToFileURL(path.join(webDir, 'js/clock.js')).href);
  for (const vp of [DESKTOP, TABLET]) {
    await page.setViewportSize(vp);
    await showView(page, 'mission');
    await page.waitForSelector('#missions-table tbody tr', { timeout: slow(10000) });
    const m = await page.evaluate(() => {
      const wrap = document.querySelector('#missions-table').closest('.table-wrap');
      const panel = wrap.closest('.panel').getBoundingClientRect();
      const w = wrap.getBoundingClientRect();
      const wide = [...document.querySelectorAll('body *')]
        .filter((e) => e.offsetParent !== null && e.getBoundingClientRect().right > window.innerWidth + 1)
        .slice(0, 8)
        .map((e) => `${e.tagName.toLowerCase()}#${e.id}.${e.getAttribute('class') ?? ''} ${Math.round(e.getBoundingClientRect().right)}`);
      return { page: document.documentElement.scrollWidth - window.innerWidth, panelRight: panel.right, wrapRight: w.right, inner: window.innerWidth, scrolls: getComputedStyle(wrap).overflowX, over: wrap.scrollWidth - wrap.clientWidth, wide };
    });
    assert.ok(m.page <= 1, `${vp.width}: the page is ${m.page} px wider than the viewport: ${m.wide.join(', ')}`);
    assert.ok(m.panelRight <= m.inner && m.wrapRight <= m.panelRight + 0.5, `${vp.width}: ${JSON.stringify(m)}`);
    assert.ok(m.over <= 0 || m.scrolls === 'auto', `${vp.width}: a wider table scrolls inside its panel: ${JSON.stringify(m)}`);
    // Plotly refits a plot some time after the resize: it must get there, and until then it is
    // clipped by its own frame (checked above: the page never widens).
    await until(`${vp.width}: the region plot fits its panel`, () =>
      page.evaluate(() => {
        const el = document.getElementById('mission-region-plot');
        const svg = el.querySelector('svg.main-svg');
        return svg !== null && svg.getBoundingClientRect().right <= el.closest('.panel').getBoundingClientRect().right + 0.5;
      }), 10000, 100);
    const started = await page.locator('#missions-table tbody tr time').first().getAttribute('title');
    assert.match(started, /UTC · station clock/, 'the start in wall-clock time, UTC and station clock on hover');
  }
  // Every time in the table says its clock: the start, and the duration by the wall clock and by
  // the station clock (×10 here), both for the aborted mission A.
  const heads = await page.locator('#missions-table th').allTextContents();
  for (const h of ['started (local time)', 'duration (wall clock)', 'duration (station clock)']) assert.ok(heads.includes(h), `${h} in ${JSON.stringify(heads)}`);
  const a = (await api('/missions')).find((m) => m.id === missionA);
  const row = await page.evaluate((id) => {
    const tr = [...document.querySelectorAll('#missions-table tbody tr')].find((r) => r.cells[0].textContent === String(id));
    const heads = [...document.querySelectorAll('#missions-table th')].map((h) => h.textContent);
    return Object.fromEntries(heads.map((h, i) => [h, tr.cells[i].textContent]));
  }, missionA);
  assert.equal(row['duration (wall clock)'], clock.fmtElapsed((Date.parse(a.ended_utc) - Date.parse(a.started_utc)) / 1000), JSON.stringify({ row, a }));
  assert.equal(row['duration (station clock)'], clock.fmtElapsed(a.ended_s - a.started_s), JSON.stringify({ row, a }));
  assert.match(await page.textContent('#view-live .clock-note'), /local wall clock/);
  await page.setViewportSize(TABLET);
});

/** Acknowledges with `act` and waits until every alarm that was shown is gone from the bar. The
 *  running mission may raise a real alarm (containment, a link stale on a loaded machine) at any
 *  moment, also just after the acknowledgement: such a new one may stay, and the bar then lists
 *  exactly the alarms still unacknowledged. */
async function acknowledged(act) {
  const shown = new Set((await hook('alarms')).active.map((a) => a.id));
  assert.ok(shown.size > 0, 'an alarm to acknowledge');
  await act();
  await until('the acknowledged alarms gone from the bar', async () => {
    const s = await hook('alarms');
    if (s.active.some((a) => shown.has(a.id))) return null;
    const bar = await page.evaluate(() => {
      const b = document.getElementById('alarm-bar');
      return { hidden: b.hidden, kinds: [...b.querySelectorAll('li')].map((li) => li.dataset.kind) };
    });
    const kinds = s.active.map((a) => a.kind);
    return bar.hidden === (kinds.length === 0) && JSON.stringify(bar.kinds) === JSON.stringify(kinds) ? s : null;
  }, 5000);
}

test('alarms: shown until acknowledged, beeping unless muted, listed in the event log', { timeout: slow(60000) }, async () => {
  errors.phase = 'alarms';
  await showView(page, 'live');
  // The running mission may have raised a real containment alarm by now: start from none.
  await page.evaluate(() => document.getElementById('alarm-ack').click());
  const before = (await hook('alarms')).raised.length;
  const alarmsInLog = await page.locator('#event-log li.sev-alarm').count();
  await page.click('#mb-state'); // a user gesture: the browser lets the page play sound from now on
  await page.evaluate(() => window.avkTest.streamMessage('status', { kind: 'containment', level: 'warning', message: 'in the buffer at (120.0, 3.0) m: heading for the interior' }));
  await page.waitForSelector('#alarm-bar:not([hidden])', { timeout: slow(5000) });
  assert.match(await page.textContent('#alarm-bar'), /Containment/);
  const a = await until('a beep', async () => {
    const s = await hook('alarms');
    return s.beeps > 0 ? s : null;
  }, 10000);
  assert.ok(a.active.some((x) => x.kind === 'containment'), JSON.stringify(a));
  await page.waitForSelector('#event-log li.sev-alarm', { timeout: slow(5000) });
  assert.match(await page.textContent('#event-log li.sev-alarm'), /ALARM.*Containment: /);
  await shot('alarm');
  if (process.env.AVK_UPDATE_DOC_SCREENSHOTS === '1') {
    mkdirSync(DOC_SHOTS, { recursive: true });
    copyFileSync(path.join(SHOTS, 'alarm.png'), path.join(DOC_SHOTS, 'alarm.png'));
  }
  // The alarm stays: another message of the kind does not add a second one, and it needs the
  // acknowledgement (a: the keyboard).
  await acknowledged(() => page.keyboard.press('a'));

  // Muted: an alarm is shown and logged, and makes no sound.
  await page.keyboard.press('m');
  assert.equal(await page.getAttribute('#mute-toggle', 'aria-pressed'), 'true');
  const beeps = (await hook('alarms')).beeps;
  // The frontseat's failsafe, from the vehicle's nav.
  await page.evaluate(() => window.avkTest.streamNav({ frontseat: { battery_v: 12.1, failsafe: 'no_command', bad_lines: 0, disconnects: 0 } }));
  await page.waitForSelector('#alarm-bar:not([hidden]) li[data-kind="failsafe"]', { timeout: slow(5000) });
  assert.match(await page.textContent('#alarm-bar'), /Frontseat failsafe.*no_command/);
  // A mission halted, as the stream says it.
  await page.evaluate(() => window.avkTest.streamMessage('status', { kind: 'mission_halted', level: 'info', message: 'left the operating region' }));
  await page.waitForSelector('#alarm-bar li[data-kind="halted"]', { timeout: slow(5000) });
  assert.equal((await hook('alarms')).beeps, beeps, 'no sound while muted');
  await acknowledged(() => page.click('#alarm-ack'));
  const raised = (await hook('alarms')).raised.slice(before);
  for (const k of ['containment', 'failsafe', 'halted']) assert.ok(raised.includes(k), `${k} raised: ${raised}`);
  assert.ok((await page.locator('#event-log li.sev-alarm').count()) >= alarmsInLog + 3, 'each alarm is in the event log');
  await page.keyboard.press('m');
  assert.equal(await page.getAttribute('#mute-toggle', 'aria-pressed'), 'false');
});

test('a station spooling while its PostgreSQL server is away: a bar says so until it is connected again', { timeout: slow(60000) }, async () => {
  errors.phase = 'store';
  // This station stores into SQLite: nothing of the store shows.
  const real = await api('/health');
  assert.deepEqual([real.store?.engine, real.store?.state], ['sqlite', 'connected'], JSON.stringify(real));
  assert.ok(await page.isHidden('#store-bar'));
  assert.ok(await page.isHidden('#store-engine'));
  // An outage cannot be made here: the page is given /health answers of a PostgreSQL station that
  // spools, then of one connected again (the real answer with another `store`).
  let store = { engine: 'postgresql', state: 'spooling', spooled: 17, spool: path.join(tmp, 'station.spool'), last_error: 'could not connect to server: Connection refused' };
  const p = await openPage(context, DESKTOP, errors);
  try {
    await p.route('**/api/v1/health', async (route) => {
      try {
        const res = await route.fetch();
        await route.fulfill({ response: res, json: { ...(await res.json()), store } });
      } catch {
        // the page closed meanwhile
      }
    });
    await p.goto(`${server.base}/#live`, { waitUntil: 'load', timeout: slow(20000) });
    await p.waitForSelector('#store-bar:not([hidden])', { timeout: slow(10000) });
    assert.equal(await p.textContent('#store-text'), 'Database unreachable — recording into the local spool (17 writes waiting); they are written when the server is back');
    assert.match(await p.getAttribute('#store-bar', 'title'), /Last error: could not connect to server: Connection refused\nSpool: .*station\.spool/);
    assert.equal(await p.textContent('#store-engine'), 'db: PostgreSQL ⚠ spooling');
    // The page reads /health again by itself: the count follows.
    store = { ...store, spooled: 1 };
    await p.waitForFunction(() => /\(1 write waiting\)/.test(document.getElementById('store-text').textContent), null, { timeout: slow(10000) });
    await showView(p, 'mission');
    assert.ok(await p.isVisible('#store-bar'), 'the bar stays in every view');
    // The server back, the spool replayed: the bar goes, the engine stays in the header.
    store = { ...store, state: 'connected', spooled: 0, last_error: null };
    await p.waitForSelector('#store-bar', { state: 'hidden', timeout: slow(10000) });
    assert.equal(await p.textContent('#store-engine'), 'db: PostgreSQL');
    assert.ok(await p.isVisible('#store-engine'));
  } finally {
    await p.close();
  }
});

test('keyboard shortcuts: ? lists them, digits switch views, not while typing', { timeout: slow(60000) }, async () => {
  errors.phase = 'keys';
  await showView(page, 'live');
  await page.evaluate(() => document.activeElement?.blur());
  await page.keyboard.press('?');
  await page.waitForSelector('#help-overlay:not([hidden])', { timeout: slow(5000) });
  const keys = await page.locator('#help-keys dt').allTextContents();
  for (const k of ['1 … 8', 'f', 'a', 't', '?', 'Esc']) assert.ok(keys.includes(k), `${k} in ${JSON.stringify(keys)}`);
  await page.keyboard.press('Escape');
  await page.waitForSelector('#help-overlay[hidden]', { state: 'attached', timeout: slow(5000) });
  await page.keyboard.press('3');
  await page.waitForSelector('#view-mission:not([hidden])', { timeout: slow(5000) });
  await page.focus('#m-name');
  await page.keyboard.press('3');
  assert.ok(await page.isVisible('#view-mission'), 'typing a digit in a field does not switch the view');
  assert.match(await page.inputValue('#m-name'), /3$/);
  await page.evaluate(() => document.activeElement?.blur());
  await page.keyboard.press('1');
  await page.waitForSelector('#view-live:not([hidden])', { timeout: slow(5000) });
  await page.keyboard.press('f'); // fit: the plot is redrawn with a new uirevision
  await until('the fitted plot', () => page.evaluate(() => document.getElementById('live-plot').layout?.uirevision > 1), 5000);
});

test('the dark theme: toggled by button or t, remembered, the plots follow, the system preference by default', { timeout: slow(60000) }, async () => {
  errors.phase = 'theme';
  await showView(page, 'live');
  assert.equal(await page.evaluate(() => document.documentElement.dataset.theme), 'light');
  await page.evaluate(() => document.activeElement?.blur());
  await page.keyboard.press('t');
  assert.equal(await page.evaluate(() => document.documentElement.dataset.theme), 'dark');
  const dark = await until('the plot in dark colours', () =>
    page.evaluate(() => {
      const l = document.getElementById('live-plot')._fullLayout;
      const bg = getComputedStyle(document.body).backgroundColor;
      return l && l.paper_bgcolor !== '#ffffff' && l.paper_bgcolor !== 'rgb(255, 255, 255)' ? { paper: l.paper_bgcolor, body: bg, region: document.getElementById('live-plot').data.find((t) => t.name === 'region').line.color } : null;
    }), 10000);
  assert.notEqual(dark.body, 'rgb(246, 247, 249)');
  assert.notEqual(dark.region, '#000000', 'what is black on white is light on dark');
  // The scale bar's label must read on the dark plot: its ink against its backing laid
  // over the plot's paper, WCAG's contrast ratio (4.5:1 for small text).
  const bar = await until('the scale bar in dark colours', () =>
    page.evaluate(() => {
      const label = document.querySelector('#live-plot')?.parentElement.querySelector('.scale-bar-label');
      if (!label?.textContent) return null;
      const cs = getComputedStyle(label);
      return { ink: cs.color, backing: cs.backgroundColor, paper: document.getElementById('live-plot')._fullLayout.paper_bgcolor, text: label.textContent };
    }), 10000);
  const rgba = (c) => {
    if (c.startsWith('#')) return [1, 3, 5].map((i) => parseInt(c.slice(i, i + 2), 16)).concat(1);
    const v = c.match(/[\d.]+/g).map(Number);
    return v.length === 3 ? [...v, 1] : v;
  };
  const over = (top, under) => top.slice(0, 3).map((v, i) => v * top[3] + under[i] * (1 - top[3]));
  const lum = (rgb) => {
    const [r, g, b] = rgb.map((v) => v / 255).map((v) => (v <= 0.03928 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4));
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
  };
  const backing = over(rgba(bar.backing), rgba(bar.paper));
  const ink = over(rgba(bar.ink), backing);
  const [hi, lo] = [lum(ink), lum(backing)].sort((p, q) => q - p);
  const contrast = (hi + 0.05) / (lo + 0.05);
  assert.ok(contrast >= 4.5, `scale bar "${bar.text}": contrast ${contrast.toFixed(2)}:1 (${JSON.stringify(bar)})`);
  await shot('operator-dark');
  await page.reload({ waitUntil: 'load' });
  await page.waitForFunction(() => document.getElementById('link-badge')?.textContent === 'LIVE', null, { timeout: slow(20000) });
  assert.equal(await page.evaluate(() => document.documentElement.dataset.theme), 'dark', 'remembered');
  await page.click('#theme-toggle');
  assert.equal(await page.evaluate(() => document.documentElement.dataset.theme), 'light');
  assert.equal(await page.evaluate(() => localStorage.getItem('avk-theme')), 'light');
  // A browser that prefers dark, with nothing chosen yet.
  const ctx = await browser.newContext({ colorScheme: 'dark' });
  try {
    const p = await openPage(ctx, DESKTOP, errors);
    await p.goto(`${server.base}/#live`, { waitUntil: 'load', timeout: slow(20000) });
    await p.waitForFunction(() => document.documentElement.dataset.theme === 'dark', null, { timeout: slow(10000) });
  } finally {
    await ctx.close();
  }
});

test('the link lost while a mission runs is an alarm; after a restart an older mission shows its stored start in wall-clock time', { timeout: slow(120000) }, async () => {
  errors.phase = 'restart';
  await showView(page, 'live');
  await page.click('#mb-state');
  // Mission B may have ended by now (at ×10 its 18 turns take minutes): then another one runs.
  if ((await api(`/missions/${missionB}`)).status !== 'running') {
    const mission = JSON.parse(readFileSync(path.join(repo, 'examples/thesis-fig4-1.json'), 'utf8'));
    await api('/vehicles/sim-usim/missions', { method: 'POST', body: { ...mission, name: 'operator-c' } });
  }
  await until('a mission running in the banner', () => page.evaluate(() => document.getElementById('mission-banner').dataset.state === 'running'), 15000);
  const port = server.port;
  const linkAlarm = () => page.evaluate(() => document.querySelector('#alarm-bar:not([hidden]) li[data-kind="link"]')?.textContent ?? '');
  // On a loaded machine the navigation may go stale before the station is gone, and the bar then
  // shows "Link stale" first: here it does so on purpose (the page stops taking the stream's nav).
  await page.evaluate(() => document.getElementById('alarm-ack').click()); // start from none
  await page.evaluate(() => window.avkTest.holdNav());
  await until('the link stale alarm', async () => /Link stale/.test(await linkAlarm()), 20000, 100);
  // The station gone without a word (a crash, the network): a station stopped in order interrupts
  // its mission first, and the page says so instead.
  const gone = new Promise((r) => server.child.once('exit', r));
  server.child.kill('SIGKILL');
  await gone;
  await page.evaluate(() => window.avkTest.releaseNav());
  // The state this test checks, whatever alarm showed first: the bar says the link is lost.
  const lost = await until('the link lost alarm', async () => {
    const text = await linkAlarm();
    return /Link lost/.test(text) ? text : null;
  }, 20000, 100);
  assert.doesNotMatch(lost, /Link stale/, 'the stale alarm gave its place to the lost one');
  assert.equal((await hook('alarms')).active.filter((a) => a.kind === 'link').length, 1, 'one link alarm in the bar');
  await page.click('#alarm-ack');
  server = await until('avk serve to bind its old port again', () => startServer(port), 30000, 1000);
  await page.waitForFunction(() => document.getElementById('link-badge').textContent === 'LIVE', null, { timeout: slow(30000) });
  // The mission was running when the station went away: interrupted.
  await until('the interrupted banner', () => page.evaluate(() => document.getElementById('mission-banner').dataset.state === 'interrupted'), 30000);
  // The restart closed it at its last recorded time, so its elapsed time is known (it showed "–").
  assert.match(await page.textContent('#mb-elapsed'), /^\d+:\d\d(:\d\d)?$/, 'the elapsed time of the interrupted mission');
  await showView(page, 'mission');
  const row = await until('mission A in the table', () =>
    page.evaluate((id) => {
      const tr = [...document.querySelectorAll('#missions-table tbody tr')].find((r) => r.cells[0].textContent === String(id));
      const t = tr?.querySelector('time');
      return t ? { text: t.textContent, title: t.title } : null;
    }, missionA), 15000);
  const why = JSON.stringify({ clock: await hook('clock'), now: new Date().toISOString(), a: (await api('/missions')).find((m) => m.id === missionA) });
  // Its start was stored in wall-clock time: local time, UTC on hover, though another session ran it.
  const a = (await api('/missions')).find((m) => m.id === missionA);
  assert.match(row.text, /^\d\d:\d\d:\d\d$|^\d{4}-\d\d-\d\d \d\d:\d\d:\d\d$/, `the stored start of a mission of an earlier session: ${row.text} ${why}`);
  assert.ok(row.title.startsWith(a.started_utc.replace('T', ' ').slice(0, 19)), `${row.title} vs ${a.started_utc}`);
  assert.match(row.title, /earlier server session/);
  assert.match(row.title, /station clock \d+\.\d s/);
});

test('no unexpected console errors', () => {
  const expected = (e) =>
    (e.phase === 'bad-mission' && /status of 422/.test(e.text)) ||
    // The station killed: refused connections, and a request under way at that moment cut.
    (e.phase === 'restart' && /(ERR_CONNECTION_REFUSED|ERR_CONNECTION_RESET|WebSocket connection|Failed to fetch|ERR_EMPTY_RESPONSE)/.test(e.text));
  assert.deepEqual(errors.console.filter((e) => !expected(e)), [], 'unexpected console errors');
  assert.deepEqual(errors.page, [], 'uncaught errors in the page');
});

// The fleet in the dashboard and the commands that keep a boat safe: a real `avk serve --sim` and
// Debian's Chromium through playwright-core. Other vehicles are fed through the page's stream path
// (the ?test=1 hooks): the Live map draws each with its id and helm mode, fits them in, and their
// moves redraw the traces only; events say which vehicle they are about and the log filters to
// the selected one. Hold, Go to (a point picked on the map), Return and Stop are asked in the page
// first (a cancel sends nothing), sent with the token, and their answer or the station's error is
// shown; without the token they are off. A vehicle the station knows from a stored mission only
// (a catamaran's mission run before `avk serve` starts) is chosen in the list: every view switches
// to it as a fresh load with it would, the address keeps it over a reload, and the header's
// selector brings the station's own vehicle back. Last, the README's fleet (`avk serve --vehicles
// examples/fleet.json`) with the three collection missions running at once: all listed under their
// missions and drawn with their ids, another chosen switches the views, and a command goes to the
// vehicle chosen only. Run with `node --test web/tests/fleet.test.mjs` (CTest: web_fleet).
//
// Environment as e2e.test.mjs: AVK_BINARY, AVK_SCREENSHOTS, AVK_CHROMIUM, AVK_E2E_SLOW.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';

import { slow, until } from './wait.mjs';
import { startAvkServer, stopAvkServer, apiRequest } from './avk_server.mjs';
import { AVK, webDir, launchBrowser, tearDown, killServerOnExit, showView, screenshot } from './browser.mjs';

const tmp = mkdtempSync(path.join(tmpdir(), 'avk-web-fleet-'));
let server = null;
let b = null;
let page = null;
let vid = null;
let stored = null; // the vehicle of the stored mission: known to the station, not connected
let storedMission = null;

// A small mission of another vehicle (a simulated catamaran), run before the station starts.
const MISSION = {
  name: 'catamaran-small',
  turn_array: { speeds_mps: [1.0], dheadings_deg: [90], repeats: 2 },
  operating_region: { polygon_m: [[-100, -100], [100, -100], [100, 100], [-100, 100]], buffer_m: 25, return_point_m: [0, -70] },
};

const api = (pathname, options) => apiRequest(server, pathname, options);
const hook = (name, ...args) => page.evaluate(([n, a]) => window.avkTest[n](...a), [name, args]);

before(async () => {
  b = await launchBrowser();
  const db = path.join(tmp, 'station.db');
  writeFileSync(path.join(tmp, 'mission.json'), JSON.stringify(MISSION));
  execFileSync(AVK, ['mission', 'run', '--config', path.join(tmp, 'mission.json'), '--db', db, '--sim', '--vehicle', 'catamaran', '--quiet'], { stdio: 'ignore', timeout: slow(30000) });
  server = await startAvkServer(AVK, ['serve', '--db', db, '--sim', '--port', '0', '--web', webDir]);
  vid = (await api('/health')).vehicle_id;
  stored = (await api('/vehicles')).find((v) => v.id !== vid && v.link === 'DISCONNECTED')?.id;
  assert.ok(stored, 'the catamaran of the stored mission is known to the station');
  storedMission = (await api('/missions')).find((m) => m.vehicle_id === stored)?.id;
  assert.ok(storedMission, 'its mission is stored');
  page = await b.newPage();
  await page.goto(`${server.base}/?token=${server.token}&test=1#live`, { waitUntil: 'load', timeout: slow(20000) });
  await page.waitForFunction(() => window.avkTest?.state().vehicleId && document.querySelector('#live-plot .main-svg'), null, { timeout: slow(20000) });
});

after(() => tearDown({ browser: b?.browser, server, dir: tmp }));
killServerOnExit(() => server);

/** The vehicle list as shown: [{id, link, mode, pressed, text}]. */
const fleetList = (p = page) =>
  p.$$eval('#fleet-list li[data-vehicle]', (lis) =>
    lis.map((li) => ({ id: li.dataset.vehicle, link: li.dataset.link, mode: li.dataset.mode, command: li.dataset.command, pressed: li.querySelector('button').getAttribute('aria-pressed'), text: li.textContent })),
  );

test('the station\'s vehicle is listed with its link; without the token the commands are off and say why', async () => {
  await until('the vehicle listed as LIVE', async () => (await fleetList()).some((v) => v.id === vid && v.link === 'LIVE' && v.pressed === 'true'), 20000);
  const other = (await fleetList()).find((v) => v.id === stored);
  assert.equal(other?.link, 'DISCONNECTED', 'the stored mission\'s vehicle is listed, not connected');
  assert.equal(other.pressed, 'false');
  // A page of its own without the token (sessionStorage is the tab's): reads work on loopback,
  // the commands do not.
  const p = await b.newPage();
  try {
    await p.goto(`${server.base}/#live`, { waitUntil: 'load', timeout: slow(20000) });
    await until('the vehicle listed', async () => (await fleetList(p)).some((v) => v.id === vid), 20000);
    for (const id of ['cmd-hold', 'cmd-goto', 'cmd-return', 'cmd-stop']) {
      assert.equal(await p.isDisabled(`#${id}`), true, `${id} is off without the token`);
      assert.match(await p.getAttribute(`#${id}`, 'title'), /control token/);
    }
    assert.equal(await p.isVisible('#cmd-token-note'), true, 'the panel says the token is needed');
  } finally {
    await p.close();
  }
  for (const id of ['cmd-hold', 'cmd-goto', 'cmd-return', 'cmd-stop']) assert.equal(await page.isDisabled(`#${id}`), false, `${id} is on with the token`);
});

test('other vehicles are drawn with their ids and helm modes, fitted in, and their moves redraw the traces only', async () => {
  await hook('holdNav'); // the simulator's own nav no longer moves the figure: what moves it is ours
  await hook('fleetNav', 'bravo', 40, 30, 90);
  await hook('fleetHelm', 'bravo', 'HOLDING', { kind: 'hold', x_m: 40, y_m: 30, radius_m: 5, speed_mps: null, distance_m: 0.4 });
  await hook('fleetNav', 'charlie', -60, -50, 180);
  const drawn = await until('three vehicles on the Live map', async () => {
    const d = await hook('liveVehicles');
    return d.selected && d.others.length === 2 ? d : null;
  }, 20000);
  assert.equal(drawn.selected.text, vid, 'the selected vehicle is named on a fleet');
  const byText = Object.fromEntries(drawn.others.map((o) => [o.text, o]));
  assert.deepEqual(Object.keys(byText).sort(), ['bravo · HOLDING', 'charlie · idle']);
  assert.deepEqual([byText['bravo · HOLDING'].x, byText['bravo · HOLDING'].y, byText['bravo · HOLDING'].angle], [40, 30, 90]);
  assert.deepEqual([byText['charlie · idle'].x, byText['charlie · idle'].y, byText['charlie · idle'].angle], [-60, -50, 180]);
  // In the fitted view (after Fit view: the fit may hold what it had only while it still fits).
  await page.click('#live-fit');
  const range = await until('the view fitted to the fleet', () =>
    page.evaluate(() => {
      const fl = document.getElementById('live-plot')._fullLayout;
      const [x0, x1] = fl.xaxis.range;
      const [y0, y1] = fl.yaxis.range;
      return x0 < -60 && x1 > 40 && y0 < -50 && y1 > 30 ? { x: [x0, x1], y: [y0, y1] } : null;
    }), 10000);
  assert.ok(range.x[1] - range.x[0] < 1000, `a view ${range.x} wide is not fitted to the fleet`);
  // The list has them all (the station's own first), the selected one pressed, bravo with its mode
  // and command; the stored mission's vehicle is listed but not drawn.
  const list = await until('the four vehicles listed', async () => {
    const l = await fleetList();
    return l.length === 4 ? l : null;
  }, 10000);
  assert.deepEqual(list.map((v) => [v.id, v.pressed]), [[vid, 'true'], ['bravo', 'false'], ['charlie', 'false'], [stored, 'false']]);
  const bravo = list.find((v) => v.id === 'bravo');
  assert.equal(bravo.mode, 'HOLDING');
  assert.match(bravo.text, /hold at \(40\.0, 30\.0\) r 5 m/);
  assert.equal(await page.isVisible('#vehicle-select'), true, 'the header selector shows on a fleet');

  // Another vehicle moving inside the view: the traces are drawn again, not the figure.
  const result = await page.evaluate(async () => {
    const plot = document.getElementById('live-plot');
    window.avkTest.renderTimes(true);
    let fullRedraws = 0;
    let tracesOnly = 0;
    plot.on('plotly_afterplot', () => fullRedraws++);
    plot.on('plotly_transitioning', () => tracesOnly++);
    const frame = () => new Promise((r) => requestAnimationFrame(() => r()));
    await frame();
    await frame();
    window.avkTest.renderTimes(true);
    fullRedraws = 0;
    tracesOnly = 0;
    // Another vehicle is redrawn at most every 250 ms (web/js/fleet.js): each move waits for it.
    const pause = () => new Promise((r) => setTimeout(r, 300));
    for (let i = 1; i <= 30; i++) {
      window.avkTest.fleetNav('bravo', 40 + i * 0.3, 30, 90 + i);
      if (i % 3 === 0) await pause();
      await frame();
    }
    await pause();
    await frame();
    const d = window.avkTest.liveVehicles();
    return { renders: window.avkTest.renderTimes().length, fullRedraws, tracesOnly, bravo: d.others.find((o) => o.text.startsWith('bravo')), trail: d.trail };
  });
  assert.ok(result.renders >= 8, `${result.renders} plot updates for 30 moves in 10 pauses`);
  assert.ok(result.tracesOnly >= result.renders - 2, `${result.fullRedraws} full redraws and ${result.tracesOnly} of the traces only for ${result.renders} updates`);
  assert.ok(result.fullRedraws <= 2, `${result.fullRedraws} full redraws for ${result.renders} updates`);
  assert.equal(result.bravo.x.toFixed(1), '49.0', 'the newest position is drawn');
  assert.equal(result.bravo.angle, 120, 'and the newest heading');
  assert.ok(result.trail >= 5, `bravo's trail has ${result.trail} points`);
  await screenshot(page, 'fleet-live');
});

test('events say which vehicle they are about, and the log filters to the selected one', async () => {
  const watch = 'bravo and charlie: closest approach 3.2 m in 20 s, below the 10 m standoff';
  await hook('streamMessage', 'status', { kind: 'collision_watch', level: 'warning', message: watch, vehicle_id: 'bravo' });
  await hook('streamMessage', 'status', { kind: 'vehicle_left', level: 'warning', message: 'charlie: navigation lost', vehicle_id: 'charlie' });
  await hook('streamMessage', 'status', { kind: 'vehicle_command', level: 'info', message: `${vid}: hold`, vehicle_id: vid });
  const log = await until('the three events in the log', async () => {
    const l = await hook('eventLog');
    return ['collision_watch', 'vehicle_left', 'vehicle_command'].every((k) => l.some((e) => e.kind === k)) ? l : null;
  }, 10000);
  assert.equal(log.find((e) => e.kind === 'collision_watch').vehicle, 'bravo');
  assert.equal(log.find((e) => e.kind === 'vehicle_left').vehicle, 'charlie');
  // Shown with its vehicle, and alarmed: a collision watch and a vehicle lost are not to be missed.
  await until('the vehicle shown with the event', () => page.evaluate(() => document.querySelector('#event-log li[data-kind="collision_watch"] .veh')?.textContent === 'bravo'), 10000);
  const alarms = await hook('alarms');
  assert.ok(alarms.active.some((a) => a.kind === 'collision'), JSON.stringify(alarms));
  assert.ok(alarms.active.some((a) => a.kind === 'vehicle_left'), JSON.stringify(alarms));
  const shownKinds = () => page.$$eval('#event-log li[data-kind]', (lis) => lis.map((li) => [li.dataset.kind, li.dataset.vehicle ?? null]));
  const all = await shownKinds();
  assert.ok(all.some(([k]) => k === 'vehicle_left'), 'charlie\'s event listed before filtering');
  // Only the selected vehicle's (and the station's): charlie's link is not this vehicle's.
  await page.check('#event-filter');
  assert.equal(await page.textContent('#event-filter-vehicle'), vid);
  const mine = await until('the log filtered', async () => {
    const k = await shownKinds();
    return k.some(([kind]) => kind === 'vehicle_command') && !k.some(([kind]) => kind === 'vehicle_left') ? k : null;
  }, 10000);
  assert.ok(mine.every(([, v]) => v === null || v === vid), JSON.stringify(mine));
  assert.ok(!mine.some(([k]) => k === 'collision_watch'), 'a collision watch of two other vehicles is not this one\'s');
  await page.uncheck('#event-filter');
  await until('the log unfiltered', async () => (await shownKinds()).some(([k]) => k === 'vehicle_left'), 10000);
  await page.click('#alarm-ack');
});

// ---------------------------------------------------------------- commands

/** POSTs the page sends to /vehicles/{vid}/<command>, counted as they go. */
const sent = [];
function recordCommands() {
  page.on('request', (r) => {
    const m = r.url().match(/\/api\/v1\/vehicles\/[^/]+\/(hold|go-to|return|stop)$/);
    if (m && r.method() === 'POST') sent.push({ command: m[1], body: r.postData() });
  });
}

const helmMode = async () => (await api(`/vehicles/${vid}`)).helm_mode;

test('Stop asks first, naming the vehicle; cancelled, nothing is sent', async () => {
  recordCommands();
  await page.click('#cmd-stop');
  await page.waitForSelector('#cmd-confirm:not([hidden])');
  assert.equal(await page.textContent('#cmd-question'), `Stop ${vid}: all stop, it will drift.`);
  assert.equal(await page.textContent('#cmd-yes'), `Stop ${vid}`);
  await page.click('#cmd-no');
  assert.equal(await page.isHidden('#cmd-confirm'), true);
  assert.equal(await page.getAttribute('#cmd-result', 'data-state'), 'cancelled');
  // Hold goes out next: had the cancelled Stop been sent, it would be before it.
  await page.click('#cmd-hold');
  await page.waitForSelector('#cmd-confirm:not([hidden])');
  assert.match(await page.textContent('#cmd-question'), new RegExp(`^Hold ${vid}: it keeps station where it is now, within 5 m\\.`));
  await page.click('#cmd-yes');
  await until('the Hold sent', () => sent.length > 0, 10000);
  assert.deepEqual(sent.map((s) => s.command), ['hold'], 'the cancelled Stop was never sent');
  assert.deepEqual(JSON.parse(sent[0].body), {});
});

test('Hold: the answer is shown, and the helm topic brings HOLDING to the vehicle panel and the list', async () => {
  await until('the Hold answered', async () => (await page.getAttribute('#cmd-result', 'data-state')) === 'ok', 10000);
  assert.match(await page.textContent('#cmd-result'), new RegExp(`^${vid}: Hold taken: HOLDING, hold at \\(`));
  assert.equal(await helmMode(), 'HOLDING');
  await hook('releaseNav');
  await until('HOLDING in the panel and the list', async () => {
    const now = await page.textContent('#cmd-current');
    const item = (await fleetList()).find((v) => v.id === vid);
    return now.startsWith('HOLDING · hold at') && item?.mode === 'HOLDING' && item.command === 'hold';
  }, 10000);
  assert.equal(await page.textContent('#live-mode'), 'HOLDING');
  // Its point, with the hold radius, on the map.
  const cmd = await page.evaluate(() => document.getElementById('live-plot').data.find((t) => String(t.name).startsWith('command:'))?.name);
  assert.equal(cmd, 'command: hold point');
});

test('Go to: a point picked on the map, confirmed, sent; the vehicle transits to it', async () => {
  await showView(page, 'live');
  await page.click('#cmd-pick');
  assert.equal(await page.getAttribute('#cmd-pick', 'aria-pressed'), 'true');
  // A point inside the plot area: where it lies on the grid is what the axes say at the moment of
  // the press. The press is sent in the same task as the axes are read: the view refits to the
  // moving vehicle between two tasks, so a mouse click sent afterwards may land on other axes.
  const target = await page.evaluate(() => {
    const plot = document.getElementById('live-plot');
    plot.scrollIntoView({ block: 'center' });
    const fl = plot._fullLayout;
    const r = plot.getBoundingClientRect();
    // A mouse event's clientX and clientY are whole pixels: the point is where the rounded press
    // lands, which on a wide view of the fleet is tenths of a metre from the unrounded one.
    const cx = Math.round(r.left + fl.xaxis._offset + fl.xaxis._length * 0.7);
    const cy = Math.round(r.top + fl.yaxis._offset + fl.yaxis._length * 0.3);
    const at = { x: fl.xaxis.p2c(cx - r.left - fl.xaxis._offset), y: fl.yaxis.p2c(cy - r.top - fl.yaxis._offset) };
    const under = document.elementFromPoint(cx, cy) ?? plot;
    under.dispatchEvent(new MouseEvent('mousedown', { clientX: cx, clientY: cy, button: 0, bubbles: true, cancelable: true }));
    return at;
  });
  const x = Number(await page.inputValue('#cmd-x'));
  const y = Number(await page.inputValue('#cmd-y'));
  assert.ok(Math.abs(x - target.x) < 0.1 && Math.abs(y - target.y) < 0.1, `picked (${x}, ${y}), clicked (${target.x}, ${target.y})`);
  assert.equal(await page.getAttribute('#cmd-pick', 'aria-pressed'), 'false');
  // Drawn as a cross beside the hold point until it is sent.
  await until('the picked point drawn', () => page.evaluate(([px, py]) => document.getElementById('live-plot').data.some((t) => t.name === 'command: hold point' && t.x.some((v, i) => Math.abs(v - (px - 3)) < 1e-9 && Math.abs(t.y[i] - (py - 3)) < 1e-9)), [x, y]), 10000);
  await page.fill('#cmd-speed', '1.2');
  await page.click('#cmd-goto');
  await page.waitForSelector('#cmd-confirm:not([hidden])');
  assert.equal(await page.textContent('#cmd-question'), `Go to: ${vid} goes to (${x.toFixed(1)}, ${y.toFixed(1)}) at 1.2 m/s, then holds there within 5 m.`);
  await page.click('#cmd-yes');
  await until('the Go to answered', async () => (await page.getAttribute('#cmd-result', 'data-state')) === 'ok', 10000);
  assert.deepEqual(JSON.parse(sent.at(-1).body), { x_m: x, y_m: y, speed_mps: 1.2 });
  const v = await api(`/vehicles/${vid}`);
  assert.equal(v.command.kind, 'go_to');
  assert.deepEqual([v.command.x_m, v.command.y_m, v.command.speed_mps], [x, y, 1.2]);
  await until('go to in the panel', async () => /^(TRANSITING|HOLDING) · go to \(/.test(await page.textContent('#cmd-current')), 10000);
});

test('Return with no mission run and a bad radius: the station\'s error is shown', async () => {
  await page.fill('#cmd-speed', '');
  await page.click('#cmd-return');
  await page.waitForSelector('#cmd-confirm:not([hidden])');
  await page.click('#cmd-yes');
  await until('the Return refused', async () => (await page.getAttribute('#cmd-result', 'data-state')) === 'error', 10000);
  assert.match(await page.textContent('#cmd-result'), new RegExp(`^${vid}: Return refused: no mission has run on vehicle '${vid}' since the station started`));
  await page.fill('#cmd-radius', '0');
  await page.click('#cmd-hold');
  await page.waitForSelector('#cmd-confirm:not([hidden])');
  await page.click('#cmd-yes');
  await until('the Hold refused', async () => /Hold refused: .*radius_m.*must be more than 0/.test(await page.textContent('#cmd-result')), 10000);
  assert.equal(await page.getAttribute('#cmd-result', 'data-state'), 'error');
  assert.equal((await api(`/vehicles/${vid}`)).command.kind, 'go_to', 'nothing changed on the vehicle');
  await page.fill('#cmd-radius', '');
  // Go to without a point: said in the page, nothing asked or sent.
  const before = sent.length;
  await page.fill('#cmd-x', '');
  await page.click('#cmd-goto');
  assert.match(await page.textContent('#cmd-result'), /Go to: Go to needs the point/);
  assert.equal(await page.isHidden('#cmd-confirm'), true);
  assert.equal(sent.length, before);
});

test('Stop, confirmed: all stop, STOPPED on the vehicle and in the page', async () => {
  await page.click('#cmd-stop');
  await page.waitForSelector('#cmd-confirm:not([hidden])');
  await page.click('#cmd-yes');
  await until('the Stop answered', async () => (await page.getAttribute('#cmd-result', 'data-state')) === 'ok', 10000);
  assert.equal(sent.at(-1).command, 'stop');
  assert.equal(await helmMode(), 'STOPPED');
  await until('STOPPED in the panel', async () => (await page.textContent('#cmd-current')) === 'STOPPED · all stop', 10000);
  // The refusals asked for above are logged by the browser as failed loads; nothing else is.
  assert.deepEqual(b.errors.filter((e) => !/the server responded with a status of (409|422)/.test(e)), [], 'no console errors or exceptions');
});

// ---------------------------------------------------------------- choosing another vehicle

test('choosing another vehicle switches every view to it, the address keeps it, and the selector brings the first back', async () => {
  await showView(page, 'live');
  await page.click(`#fleet-list li[data-vehicle="${stored}"] button`);
  const st = await until('the stored vehicle shown', async () => {
    const s = await hook('state');
    return s.vehicleId === stored && s.mission === storedMission ? s : null;
  }, 20000);
  assert.ok(st.okTurns >= 1, `its turns counted (${st.okTurns}), not the station's`);
  assert.equal(new URL(page.url()).searchParams.get('vehicle'), stored, 'the choice is in the address');
  assert.ok((await page.textContent('#vehicle-name')).startsWith(`${stored} (`), 'the header names it');
  assert.equal(await page.getAttribute(`#fleet-list li[data-vehicle="${stored}"] button`, 'aria-pressed'), 'true');
  // Its mission's stored track is read, and the station's own vehicle is drawn as another.
  await until('its stored track read', async () => (await hook('trackLength')) > 10, 20000);
  const drawn = await until('the station\'s vehicle drawn as another', async () => {
    const d = await hook('liveVehicles');
    return d.others.some((o) => o.text.startsWith(`${vid} · `)) ? d : null;
  }, 10000);
  assert.equal(drawn.selected, null, 'a vehicle with no live navigation has no marker');
  await screenshot(page, 'fleet-stored-vehicle');
  // Not connected: no commands for it, and the panel says why.
  assert.equal(await page.isDisabled('#cmd-hold'), true);
  assert.match(await page.getAttribute('#cmd-stop', 'title'), /not connected/);
  assert.equal(await page.textContent('#event-filter-vehicle'), stored);
  // The Mission view starts on it; the CKT view is its table.
  await showView(page, 'mission');
  assert.equal(await page.textContent('#m-start'), `Start mission on ${stored}`);
  await showView(page, 'ckt');
  await until('its CKT', async () => (await page.textContent('#ckt-status')).startsWith(`${stored}: 1 speeds × 1 heading changes, 2 turns`), 20000);

  // A reload keeps it (the address), as a fresh load with it.
  await page.reload({ waitUntil: 'load' });
  await until('the stored vehicle shown after a reload', async () => {
    const s = await page.evaluate(() => window.avkTest?.state());
    return s?.vehicleId === stored && s.mission === storedMission;
  }, 20000);

  // The header's selector brings the station's own back: no mission, no turns.
  await page.selectOption('#vehicle-select', vid);
  await until('the station\'s vehicle shown again', async () => {
    const s = await hook('state');
    return s.vehicleId === vid && s.mission === null;
  }, 20000);
  assert.equal(new URL(page.url()).searchParams.get('vehicle'), vid);
  await until('its CKT: none', async () => /No turns yet/.test(await page.textContent('#ckt-status')), 20000);
  await showView(page, 'live');
  await until('its marker back', async () => (await hook('liveVehicles')).selected?.x !== undefined, 20000);
  assert.equal(await page.isDisabled('#cmd-hold'), false, 'commands are on for a connected vehicle');
  assert.deepEqual(b.errors.filter((e) => !/the server responded with a status of (409|422)/.test(e)), [], 'no console errors or exceptions');
});

// ---------------------------------------------------------------- a station of three vehicles

// The README's fleet: examples/fleet.json (three simulated M200s 300 m apart) with each one's
// collection mission from examples/fleet-missions/, all running at once (in real time: each takes
// minutes, so all three are still running when the test ends).
const FLEET_FILE = path.join(webDir, '..', 'examples', 'fleet.json');
const FLEET_IDS = JSON.parse(readFileSync(FLEET_FILE, 'utf8')).vehicles.map((v) => v.id);
const fleetMission = (id) => JSON.parse(readFileSync(path.join(webDir, '..', 'examples', 'fleet-missions', `${id}.json`), 'utf8'));

test('a station of three vehicles running their missions at once: all listed and drawn with their ids; another chosen switches the views and takes the commands', { timeout: slow(180000) }, async () => {
  const s3 = await startAvkServer(AVK, ['serve', '--db', path.join(tmp, 'fleet.db'), '--vehicles', FLEET_FILE, '--realtime-factor', '1', '--port', '0', '--web', webDir]);
  const p = await b.newPage();
  const call = (pathname, options) => apiRequest(s3, pathname, options);
  const on3 = (name, ...args) => p.evaluate(([n, a]) => window.avkTest[n](...a), [name, args]);
  const idOf = (label) => label.split(' · ')[0];
  try {
    const ids = (await call('/health')).vehicles;
    assert.deepEqual(ids, FLEET_IDS);
    const missionOf = {};
    for (const id of ids) missionOf[id] = (await call(`/vehicles/${encodeURIComponent(id)}/missions`, { method: 'POST', body: fleetMission(id) })).id;
    await p.goto(`${s3.base}/?token=${s3.token}&test=1#live`, { waitUntil: 'load', timeout: slow(20000) });
    const listed = await until('the three vehicles listed LIVE, each under its own mission', async () => {
      const l = await fleetList(p);
      return l.length === 3 && l.every((v) => v.link === 'LIVE' && v.text.includes(`mission ${missionOf[v.id]}`)) ? l : null;
    }, 60000);
    assert.deepEqual(listed.map((v) => v.id), ids, 'in the station\'s order');
    for (const id of ids) assert.equal((await call(`/missions/${missionOf[id]}`)).vehicle_id, id);
    const first = (await on3('state')).vehicleId;
    assert.equal(first, (await call('/health')).vehicle_id, 'the station\'s own shown first');
    await until('the first vehicle\'s mission shown', async () => (await on3('state')).mission === missionOf[first], 20000);
    const othersOf = (shown) => ids.filter((id) => id !== shown).sort();
    // Three markers where the station places them: the selected one named over its own, the
    // other two with their id and helm mode.
    const drawn = await until('three vehicle markers', async () => {
      const d = await on3('liveVehicles');
      return d.selected && d.others.length === 2 ? d : null;
    }, 30000);
    assert.equal(drawn.selected.text, first);
    assert.deepEqual(drawn.others.map((o) => idOf(o.text)).sort(), othersOf(first));
    for (const o of drawn.others) {
      const v = await call(`/vehicles/${encodeURIComponent(idOf(o.text))}`);
      // Moving: drawn within a few seconds' travel of where the station has it.
      assert.ok(Math.hypot(o.x - v.nav.x_m, o.y - v.nav.y_m) < 30, `${v.id} drawn at (${o.x}, ${o.y}), the station has (${v.nav.x_m}, ${v.nav.y_m})`);
    }
    await screenshot(p, 'fleet-three');

    // Another one chosen in the list: every view is of it, its mission the one shown.
    const second = ids.find((id) => id !== first);
    await p.click(`#fleet-list li[data-vehicle="${second}"] button`);
    await until('the second vehicle shown', async () => (await on3('state')).vehicleId === second, 20000);
    assert.equal(new URL(p.url()).searchParams.get('vehicle'), second);
    const now = await until('its marker the selected one', async () => {
      const d = await on3('liveVehicles');
      return d.selected?.text === second && d.others.length === 2 ? d : null;
    }, 20000);
    assert.deepEqual(now.others.map((o) => idOf(o.text)).sort(), othersOf(second));
    await until('its mission shown', async () => (await on3('state')).mission === missionOf[second], 20000);
    await showView(p, 'mission');
    assert.equal(await p.textContent('#m-start'), `Start mission on ${second}`);
    await showView(p, 'live');
    assert.equal(await p.textContent('#cmd-vehicle'), `· ${second}`);
    // A command goes to it, and to it only: the other two go on with their missions.
    await p.click('#cmd-hold');
    await p.waitForSelector('#cmd-confirm:not([hidden])');
    assert.match(await p.textContent('#cmd-question'), new RegExp(`^Hold ${second}: `));
    await p.click('#cmd-yes');
    await until('the Hold answered', async () => (await p.getAttribute('#cmd-result', 'data-state')) === 'ok', 20000);
    assert.equal((await call(`/vehicles/${encodeURIComponent(second)}`)).command?.kind, 'hold');
    for (const id of othersOf(second)) {
      const v = await call(`/vehicles/${encodeURIComponent(id)}`);
      assert.equal(v.command, null, `${id} was not told to hold`);
      assert.equal(v.mission_id, missionOf[id], `${id} still runs its mission`);
    }
    // The header's selector: back to the first, its own mission shown.
    await p.selectOption('#vehicle-select', first);
    await until('the first vehicle shown, with its mission', async () => {
      const st = await on3('state');
      return st.vehicleId === first && st.mission === missionOf[first];
    }, 20000);
    assert.deepEqual(b.errors.filter((e) => !/the server responded with a status of (409|422)/.test(e)), [], 'no console errors or exceptions');
  } finally {
    await p.close().catch(() => {});
    await stopAvkServer(s3);
  }
});

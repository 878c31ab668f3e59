// Data out: a mission's track (CSV) and event log (CSV and JSON) downloaded from the
// Export view, each checked row by row against the REST JSON. Its own `avk serve --sim` and
// Debian's Chromium through playwright-core, as in e2e.test.mjs. Run with
// `node --test web/tests/export_data.test.mjs` (CTest: web_export_data).
//
// Environment: AVK_BINARY (default build/server/avk), AVK_CHROMIUM (default /usr/bin/chromium).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { slow, sleep, until } from './wait.mjs';
import { startAvkServer, stopAvkServer } from './avk_server.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const webDir = path.resolve(here, '..');
const repo = path.resolve(webDir, '..');
const AVK = path.resolve(process.env.AVK_BINARY || path.join(repo, 'build/server/avk'));
const CHROMIUM = process.env.AVK_CHROMIUM || '/usr/bin/chromium';

const tmp = mkdtempSync(path.join(tmpdir(), 'avk-web-export-'));
let server = null;
let browser = null;
let page = null;
let missionId = null;
const pageErrors = [];

/** GET /api/v1<path> as JSON (loopback: no token needed for a read). */
async function api(pathname) {
  const res = await fetch(`${server.base}/api/v1${pathname}`, { headers: { Accept: 'application/json' }, signal: AbortSignal.timeout(slow(10000)) });
  assert.ok(res.ok, `GET ${pathname}: ${res.status}`);
  return res.json();
}

/** Every item of a keyset collection, read over REST as a client would. */
async function allItems(pathname, limit) {
  const out = [];
  let after = null;
  for (;;) {
    const page = await api(`${pathname}?limit=${limit}${after === null ? '' : `&after=${after}`}`);
    out.push(...page.items);
    if (page.next === null) return out;
    after = page.next;
  }
}

/** RFC 4180: rows of cells, quoted cells unquoted (a message may hold commas and quotes). */
function parseCsv(text) {
  const rows = [];
  let row = [];
  let cell = '';
  let quoted = false;
  for (let i = 0; i < text.length; i++) {
    const c = text[i];
    if (quoted) {
      if (c === '"' && text[i + 1] === '"') {
        cell += '"';
        i++;
      } else if (c === '"') quoted = false;
      else cell += c;
    } else if (c === '"') quoted = true;
    else if (c === ',') {
      row.push(cell);
      cell = '';
    } else if (c === '\n') {
      row.push(cell);
      rows.push(row);
      row = [];
      cell = '';
    } else if (c !== '\r') cell += c;
  }
  if (cell.length > 0 || row.length > 0) rows.push([...row, cell]);
  return rows;
}

/** Clicks an Export button and returns the downloaded file's name and text. */
async function download(button) {
  const [d] = await Promise.all([page.waitForEvent('download', { timeout: slow(30000) }), page.click(button)]);
  const file = path.join(tmp, d.suggestedFilename());
  await d.saveAs(file);
  return { name: d.suggestedFilename(), text: readFileSync(file, 'utf8') };
}

/** A CSV cell against the JSON value it stands for: a number read back exactly, null as empty. */
function sameValue(cell, value, what) {
  if (value === null) assert.equal(cell, '', `${what}: null is an empty cell`);
  else if (typeof value === 'number') assert.equal(Number(cell), value, `${what}: ${cell} vs ${value}`);
  else assert.equal(cell, String(value), what);
}

before(async () => {
  assert.ok(existsSync(AVK), `the avk binary is missing: ${AVK} (build it, or set AVK_BINARY)`);
  assert.ok(existsSync(CHROMIUM), `Chromium is missing: ${CHROMIUM} (scripts/setup installs Debian's chromium)`);
  assert.ok(existsSync(path.join(webDir, 'node_modules/playwright-core')), 'web/node_modules is missing: run scripts/web-deps (npm ci in web/)');
  const { chromium } = await import('playwright-core');
  server = await startAvkServer(AVK, ['serve', '--db', path.join(tmp, 'station.db'), '--sim', '--realtime-factor', '50', '--port', '0', '--web', webDir]);
  browser = await chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    timeout: slow(30000),
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  const context = await browser.newContext({ acceptDownloads: true });
  page = await context.newPage();
  page.setDefaultTimeout(slow(15000));
  page.on('pageerror', (e) => pageErrors.push(e.message));
});

after(async () => {
  await Promise.race([browser?.close(), sleep(10000)]).catch(() => {});
  await stopAvkServer(server).catch(() => {});
  rmSync(tmp, { recursive: true, force: true });
});

process.on('exit', () => {
  if (server && !server.exited) server.child.kill('SIGKILL');
});

test('a small mission runs to its end', { timeout: slow(120000) }, async () => {
  const mission = {
    name: 'export-data',
    turn_array: { speeds_mps: [1.0], dheadings_deg: [40, 90], repeats: 1 },
    operating_region: { polygon_m: [[-150, -150], [150, -150], [150, 150], [-150, 150]], buffer_m: 25, return_point_m: [0, -70] },
  };
  const res = await fetch(`${server.base}/api/v1/vehicles/sim-usim/missions`, {
    method: 'POST',
    headers: { Authorization: `Bearer ${server.token}`, 'Content-Type': 'application/json' },
    body: JSON.stringify(mission),
    signal: AbortSignal.timeout(slow(10000)),
  });
  const text = await res.text();
  assert.equal(res.status, 201, text);
  missionId = JSON.parse(text).id;
  await until(`mission ${missionId} done`, async () => (await api(`/missions/${missionId}`)).status === 'done', 90000, 500);
});

test('the Export view downloads the mission track as CSV: every stored sample, as REST has it', { timeout: slow(90000) }, async () => {
  assert.ok(missionId, 'the mission ran');
  await page.goto(`${server.base}/?token=${server.token}#export`, { waitUntil: 'load', timeout: slow(20000) });
  await page.waitForSelector(`#exp-mcap-mission option[value="${missionId}"]`, { state: 'attached', timeout: slow(15000) });
  await page.selectOption('#exp-mcap-mission', String(missionId));
  const { name, text } = await download('#exp-track-csv');
  assert.equal(name, `mission-${missionId}-track.csv`);
  const rows = parseCsv(text);
  const columns = ['t_s', 'x_m', 'y_m', 'heading_deg', 'speed_mps', 'desired_heading_deg', 'desired_speed_mps', 'helm_mode'];
  assert.deepEqual(rows[0], columns, 'the header names the columns with their units');
  const nav = await allItems(`/missions/${missionId}/nav`, 10000);
  assert.ok(nav.length > 100, `the mission stored its track (${nav.length} samples)`);
  assert.equal(rows.length - 1, nav.length, 'one row per stored sample');
  for (let i = 0; i < nav.length; i++) {
    assert.equal(rows[i + 1].length, columns.length, `row ${i + 1}`);
    columns.forEach((c, k) => sameValue(rows[i + 1][k], nav[i][c], `row ${i + 1} ${c}`));
  }
  assert.match(await page.textContent('#exp-status'), new RegExp(`${nav.length} samples`));
});

test('the Export view downloads the event log as CSV and as JSON, as REST has it', { timeout: slow(90000) }, async () => {
  assert.ok(missionId, 'the mission ran');
  await page.selectOption('#exp-mcap-mission', String(missionId));
  const events = await allItems(`/missions/${missionId}/events`, 1000);
  assert.ok(events.length > 0, 'a finished mission has events');

  const csv = await download('#exp-events-csv');
  assert.equal(csv.name, `mission-${missionId}-events.csv`);
  const rows = parseCsv(csv.text);
  assert.deepEqual(rows[0], ['id', 't_s', 'kind', 'message']);
  assert.equal(rows.length - 1, events.length, 'one row per entry');
  events.forEach((e, i) => ['id', 't_s', 'kind', 'message'].forEach((c, k) => sameValue(rows[i + 1][k], e[c], `event ${e.id} ${c}`)));

  const json = await download('#exp-events-json');
  assert.equal(json.name, `mission-${missionId}-events.json`);
  assert.deepEqual(JSON.parse(json.text), events, 'the JSON file is the REST items, every page');
  assert.deepEqual(pageErrors, [], 'no page errors');
});

// The Live plot's offline map background: a tile folder written here around
// a datum, `avk serve --sim --datum … --tiles DIR`, the Map switch turned on in the page. The
// plot's layout images must be the tiles of the view at the zoom whose tiles are about 256 px on
// screen, each placed where geo.js puts its corners in the local grid, and every tile the page
// asks for must be served. Expected values are computed here with the Web Mercator formulas.
//
// Environment: AVK_BINARY (default build/server/avk), AVK_SCREENSHOTS, AVK_CHROMIUM (browser.mjs).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { deflateSync } from 'node:zlib';

import { until } from './wait.mjs';
import { startAvkServer } from './avk_server.mjs';
import { AVK, webDir, launchBrowser, screenshot, tearDown, killServerOnExit } from './browser.mjs';
import { localGrid } from '../js/geo.js';

const DATUM = { lat_deg: 42.358456, lon_deg: -71.087589 };
const ZOOMS = [15, 16, 17, 18];
const R = 6378137;

const tmp = mkdtempSync(path.join(tmpdir(), 'avk-web-tiles-'));
const tileDir = path.join(tmp, 'tiles');
let server = null;
let b = null; // {browser, context, newPage, errors}
let page = null;
const tileResponses = new Map(); // URL -> status

// ---------------------------------------------------------------- a PNG, made here

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});

function crc32(buf) {
  let c = 0xffffffff;
  for (const b of buf) c = CRC_TABLE[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

function chunk(type, data) {
  const len = Buffer.alloc(4);
  len.writeUInt32BE(data.length);
  const body = Buffer.concat([Buffer.from(type, 'ascii'), data]);
  const crc = Buffer.alloc(4);
  crc.writeUInt32BE(crc32(body));
  return Buffer.concat([len, body, crc]);
}

/** A 256×256 RGB PNG of one colour with a dark 2-px border (a misplaced tile shows). */
function png([r, g, b]) {
  const size = 256;
  const raw = Buffer.alloc(size * (1 + size * 3));
  for (let y = 0; y < size; y++) {
    const row = y * (1 + size * 3);
    raw[row] = 0; // filter: none
    for (let x = 0; x < size; x++) {
      const edge = x < 2 || y < 2 || x >= size - 2 || y >= size - 2;
      raw.set(edge ? [40, 40, 40] : [r, g, b], row + 1 + x * 3);
    }
  }
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(size, 0);
  ihdr.writeUInt32BE(size, 4);
  ihdr[8] = 8; // bit depth
  ihdr[9] = 2; // RGB
  return Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]), chunk('IHDR', ihdr), chunk('IDAT', deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]);
}

// ---------------------------------------------------------------- Web Mercator, independently

const DEG = Math.PI / 180;
const tileX = (lon, z) => ((lon + 180) / 360) * 2 ** z;
const tileY = (lat, z) => ((1 - Math.asinh(Math.tan(lat * DEG)) / Math.PI) / 2) * 2 ** z;
const lonOf = (x, z) => (x / 2 ** z) * 360 - 180;
const latOf = (y, z) => Math.atan(Math.sinh(Math.PI * (1 - (2 * y) / 2 ** z))) / DEG;

/** Writes every tile of ZOOMS within ±1.2 km of the datum; returns how many. */
function writeTiles() {
  const colours = [png([170, 210, 235]), png([235, 225, 190])];
  const dLat = 1200 / 111000;
  const dLon = 1200 / (111000 * Math.cos(DATUM.lat_deg * DEG));
  let n = 0;
  for (const z of ZOOMS) {
    const x0 = Math.floor(tileX(DATUM.lon_deg - dLon, z));
    const x1 = Math.floor(tileX(DATUM.lon_deg + dLon, z));
    const y0 = Math.floor(tileY(DATUM.lat_deg + dLat, z));
    const y1 = Math.floor(tileY(DATUM.lat_deg - dLat, z));
    for (let x = x0; x <= x1; x++) {
      mkdirSync(path.join(tileDir, String(z), String(x)), { recursive: true });
      for (let y = y0; y <= y1; y++) {
        writeFileSync(path.join(tileDir, String(z), String(x), `${y}.png`), colours[(x + y) % 2]);
        n++;
      }
    }
  }
  return n;
}

/** The tiles at zoom z whose rectangle in the grid (edges at the mean of their corners) overlaps
 *  the view, each with its expected image. Candidates: every tile the folder has at z. */
function expectedImages(view, z) {
  const grid = localGrid(DATUM);
  const dLat = 1200 / 111000;
  const dLon = 1200 / (111000 * Math.cos(DATUM.lat_deg * DEG));
  const out = new Map();
  for (let x = Math.floor(tileX(DATUM.lon_deg - dLon, z)); x <= Math.floor(tileX(DATUM.lon_deg + dLon, z)); x++) {
    for (let y = Math.floor(tileY(DATUM.lat_deg + dLat, z)); y <= Math.floor(tileY(DATUM.lat_deg - dLat, z)); y++) {
      const [n, s, w, e] = [latOf(y, z), latOf(y + 1, z), lonOf(x, z), lonOf(x + 1, z)];
      const nw = grid.toGrid(n, w);
      const ne = grid.toGrid(n, e);
      const sw = grid.toGrid(s, w);
      const se = grid.toGrid(s, e);
      const left = (nw.x + sw.x) / 2;
      const right = (ne.x + se.x) / 2;
      const top = (nw.y + ne.y) / 2;
      const bottom = (sw.y + se.y) / 2;
      const overlaps = left < view.x1 && right > view.x0 && bottom < view.y1 && top > view.y0;
      if (overlaps) out.set(`/api/v1/tiles/${z}/${x}/${y}`, { x: left, y: top, sizex: right - left, sizey: top - bottom });
    }
  }
  return out;
}

/** The zoom whose tiles are about 256 px wide on screen at the view's centre, within the folder's. */
function expectedZoom(view) {
  const grid = localGrid(DATUM);
  const centre = grid.toLatLon((view.x0 + view.x1) / 2, (view.y0 + view.y1) / 2);
  const metresPerPx = (view.x1 - view.x0) / view.widthPx;
  const z = Math.round(Math.log2((2 * Math.PI * R * Math.cos(centre.lat * DEG)) / (256 * metresPerPx)));
  return Math.min(Math.max(z, ZOOMS[0]), ZOOMS[ZOOMS.length - 1]);
}

/** What the Live plot holds now: its view and its layout images. */
function livePlot() {
  return page.evaluate(() => {
    const el = document.getElementById('live-plot');
    const fl = el._fullLayout;
    if (!fl?.xaxis?.range) return null;
    const [x0, x1] = fl.xaxis.range;
    const [y0, y1] = fl.yaxis.range;
    const images = (el.layout.images || []).map((i) => ({ source: i.source, x: i.x, y: i.y, sizex: i.sizex, sizey: i.sizey, xref: i.xref, yref: i.yref, sizing: i.sizing, layer: i.layer, xanchor: i.xanchor, yanchor: i.yanchor }));
    return { view: { x0, x1, y0, y1, widthPx: fl.xaxis._length }, images };
  });
}

/** Compares the drawn images with the expected ones; a string says what differs. */
function mismatch(drawn) {
  if (!drawn) return 'no plot yet';
  const z = expectedZoom(drawn.view);
  const want = expectedImages(drawn.view, z);
  if (drawn.images.length !== want.size) return `${drawn.images.length} images, expected ${want.size} at zoom ${z}`;
  for (const img of drawn.images) {
    const url = new URL(img.source, server.base);
    const e = want.get(url.pathname);
    if (!e) return `unexpected tile ${url.pathname} (zoom ${z} expected)`;
    if (url.searchParams.get('token') !== server.token) return `${img.source} does not carry the token`;
    for (const k of ['x', 'y', 'sizex', 'sizey']) {
      if (!(Math.abs(img[k] - e[k]) < 1e-6)) return `${url.pathname} ${k} = ${img[k]}, expected ${e[k]}`;
    }
    if (img.xref !== 'x' || img.yref !== 'y' || img.sizing !== 'stretch' || img.layer !== 'below' || img.xanchor !== 'left' || img.yanchor !== 'top')
      return `${url.pathname} is not a stretched image below the data anchored at its top left`;
  }
  return '';
}

async function setView(x0, x1, y0, y1) {
  await page.evaluate(([a, b, c, d]) => window.Plotly.relayout('live-plot', { 'xaxis.range': [a, b], 'yaxis.range': [c, d] }), [x0, x1, y0, y1]);
}

/** Waits until the drawn images are the expected ones for the view shown and every one of them was
 *  served with 200; returns the plot. */
async function untilTilesMatch(what) {
  let last = null;
  await until(
    what,
    async () => {
      last = await livePlot();
      return last && last.images.length > 0 && mismatch(last) === '';
    },
    30000,
  );
  await until(`every tile of ${what} served`, () => last.images.every((i) => tileResponses.get(new URL(i.source, server.base).href) === 200), 30000);
  return last;
}

// ---------------------------------------------------------------- set-up and tear-down

before(async () => {
  b = await launchBrowser();
  assert.ok(writeTiles() > 0);
  server = await startAvkServer(AVK, ['serve', '--db', path.join(tmp, 'station.db'), '--sim', '--datum', `${DATUM.lat_deg},${DATUM.lon_deg}`, '--tiles', tileDir, '--port', '0', '--web', webDir]);
  page = await b.newPage();
  page.on('response', (r) => {
    if (r.url().includes('/api/v1/tiles/')) tileResponses.set(r.url(), r.status());
  });
});

after(() => tearDown({ browser: b?.browser, server, dir: tmp }));
killServerOnExit(() => server);

// ---------------------------------------------------------------- the test

test('the station says what tiles it has', async () => {
  const res = await fetch(`${server.base}/api/v1/tiles`);
  assert.equal(res.status, 200);
  const info = await res.json();
  assert.equal(info.available, true);
  assert.equal(info.source, 'folder');
  assert.equal(info.format, 'png');
  assert.equal(info.minzoom, ZOOMS[0]);
  assert.equal(info.maxzoom, ZOOMS[ZOOMS.length - 1]);
  assert.deepEqual(info.datum, DATUM);
  const health = await (await fetch(`${server.base}/api/v1/health`)).json();
  assert.deepEqual(health.datum, DATUM);
});

test('Map draws the tiles of the view in the local grid, and follows zoom and pan', async () => {
  await page.goto(`${server.base}/?token=${server.token}#live`);
  const toggle = page.locator('#live-plot-map');
  await toggle.waitFor({ state: 'visible' });
  assert.equal(await toggle.isChecked(), false, 'the map is off until the operator turns it on');
  await until('the live plot', () => livePlot());
  assert.equal((await livePlot()).images.length, 0, 'no tiles while the switch is off');
  await toggle.check();

  // A view about 500 m wide: zoom 17 on a 1280-px page.
  await setView(-250, 250, -180, 180);
  const wide = await untilTilesMatch('the tiles of a 500 m view');
  const zWide = expectedZoom(wide.view);
  assert.ok(wide.images.length >= 2, `a 500 m view takes several tiles (${wide.images.length})`);
  await screenshot(page, 'map-tiles-live');

  // Zoomed in past the finest tiles: the finest zoom, stretched (the operator's zoom is a relayout).
  await setView(-40, 40, -30, 30);
  const close = await untilTilesMatch('the tiles of an 80 m view');
  assert.equal(expectedZoom(close.view), ZOOMS[ZOOMS.length - 1]);
  assert.ok(new URL(close.images[0].source, server.base).pathname.startsWith(`/api/v1/tiles/${ZOOMS[ZOOMS.length - 1]}/`));
  assert.notEqual(expectedZoom(close.view), zWide);

  // Panned east: other tiles.
  await setView(260, 340, -30, 30);
  const panned = await untilTilesMatch('the tiles after a pan');
  assert.notDeepEqual(panned.images.map((i) => i.source).sort(), close.images.map((i) => i.source).sort());

  const bad = [...tileResponses].filter(([, status]) => status !== 200);
  assert.deepEqual(bad, [], 'every tile the page asked for was served');
  assert.deepEqual(b.errors, [], 'no console errors or page exceptions');
});

test('the switch is remembered, and off draws no tiles', async () => {
  await page.reload();
  await page.locator('#live-plot-map').waitFor({ state: 'visible' });
  assert.equal(await page.locator('#live-plot-map').isChecked(), true, 'remembered across a reload');
  await until('tiles after the reload', async () => (await livePlot())?.images.length > 0);
  await page.locator('#live-plot-map').uncheck();
  await until('no tiles with the switch off', async () => (await livePlot())?.images.length === 0);
  assert.equal(await page.evaluate(() => localStorage.getItem('avk-map-background')), '0');
  assert.deepEqual(b.errors, [], 'no console errors or page exceptions');
});

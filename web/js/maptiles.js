// The map background of the Live and Replay plots: raster tiles the operator gave `avk serve
// --tiles` (a tile folder or an MBTiles file, docs/dashboard.md), drawn as Plotly layout images
// under the track. Nothing is fetched from the internet: every tile comes from the station's
// /api/v1/tiles/{z}/{x}/{y}. Tiles are in Web Mercator; the plot is in the local grid of the
// station's datum (geo.js), so each tile is placed by its corners converted into the grid.

import { state, on } from './state.js';
import { getJson, BASE } from './api.js';
import { getToken } from './auth.js';
import { localGrid } from './geo.js';
import { el } from './format.js';

const TILE_PX = 256; // a tile is drawn about this wide on screen
const EARTH_RADIUS_M = 6378137; // Web Mercator's sphere
const MAX_LAT_DEG = 85.0511287798; // Web Mercator's edge
const MAX_TILES = 64; // a view needing more (zoomed out past the tiles' lowest zoom) shows none
const STORAGE_KEY = 'avk-map-background';
const DEG = Math.PI / 180;

// ---------------------------------------------------------------- Web Mercator tiles

export function lonToTileX(lonDeg, z) {
  return ((lonDeg + 180) / 360) * 2 ** z;
}

export function latToTileY(latDeg, z) {
  const lat = Math.max(-MAX_LAT_DEG, Math.min(MAX_LAT_DEG, latDeg)) * DEG;
  return ((1 - Math.log(Math.tan(lat) + 1 / Math.cos(lat)) / Math.PI) / 2) * 2 ** z;
}

export function tileXToLon(x, z) {
  return (x / 2 ** z) * 360 - 180;
}

export function tileYToLat(y, z) {
  return Math.atan(Math.sinh(Math.PI * (1 - (2 * y) / 2 ** z))) / DEG;
}

/** The zoom whose tiles are about TILE_PX wide on screen at metresPerPx, within [minzoom, maxzoom]:
 *  a Web Mercator tile at zoom z spans 2πR·cos(lat) / 2^z metres of the ground. */
export function tileZoom(metresPerPx, latDeg, minzoom, maxzoom) {
  const z = Math.round(Math.log2((2 * Math.PI * EARTH_RADIUS_M * Math.cos(latDeg * DEG)) / (TILE_PX * metresPerPx)));
  return Math.max(minzoom, Math.min(maxzoom, Number.isFinite(z) ? z : maxzoom));
}

/** The Plotly layout images of the tiles covering a view of the local grid.
 *  view: {xRange: [x0, x1], yRange: [y0, y1], widthPx} (metres, the plot area's pixel width);
 *  datum: {lat_deg, lon_deg}; info: GET /tiles. Returns {key, images}: key names the tiles, so a
 *  caller redraws only when it changes. */
export function tileImages(view, datum, info, token = '') {
  const none = { key: '', images: [] };
  if (!view || !datum || !info?.available) return none;
  const [x0, x1] = [...view.xRange].sort((a, b) => a - b);
  const [y0, y1] = [...view.yRange].sort((a, b) => a - b);
  if (!(view.widthPx > 0) || !(x1 > x0) || !(y1 > y0)) return none;
  const grid = localGrid(datum);
  // The view's extent on the earth: its corners and edge midpoints (the grid is a tangent plane,
  // so a parallel is slightly curved in it).
  let latMin = Infinity;
  let latMax = -Infinity;
  let lonMin = Infinity;
  let lonMax = -Infinity;
  for (const x of [x0, (x0 + x1) / 2, x1]) {
    for (const y of [y0, (y0 + y1) / 2, y1]) {
      const p = grid.toLatLon(x, y);
      if (!p) return none; // a view larger than the plane can put on the earth
      latMin = Math.min(latMin, p.lat);
      latMax = Math.max(latMax, p.lat);
      lonMin = Math.min(lonMin, p.lon);
      lonMax = Math.max(lonMax, p.lon);
    }
  }
  const centre = grid.toLatLon((x0 + x1) / 2, (y0 + y1) / 2);
  const z = tileZoom((x1 - x0) / view.widthPx, centre.lat, info.minzoom, info.maxzoom);
  const n = 2 ** z;
  let tx0 = Math.floor(lonToTileX(lonMin, z));
  let tx1 = Math.floor(lonToTileX(lonMax, z));
  let ty0 = Math.floor(latToTileY(latMax, z));
  let ty1 = Math.floor(latToTileY(latMin, z));
  // Only where the source has tiles (its bounds), so the page asks for nothing it knows is absent.
  const b = info.bounds;
  if (Array.isArray(b) && b.length === 4) {
    tx0 = Math.max(tx0, Math.floor(lonToTileX(b[0], z)));
    tx1 = Math.min(tx1, Math.ceil(lonToTileX(b[2], z)) - 1);
    ty0 = Math.max(ty0, Math.floor(latToTileY(b[3], z)));
    ty1 = Math.min(ty1, Math.ceil(latToTileY(b[1], z)) - 1);
  }
  tx0 = Math.max(tx0, 0);
  ty0 = Math.max(ty0, 0);
  tx1 = Math.min(tx1, n - 1);
  ty1 = Math.min(ty1, n - 1);
  if (tx1 < tx0 || ty1 < ty0 || (tx1 - tx0 + 1) * (ty1 - ty0 + 1) > MAX_TILES) return none;
  const query = token ? `?token=${encodeURIComponent(token)}` : '';
  const images = [];
  for (let ty = ty0; ty <= ty1; ty++) {
    const north = tileYToLat(ty, z);
    const south = tileYToLat(ty + 1, z);
    for (let tx = tx0; tx <= tx1; tx++) {
      const west = tileXToLon(tx, z);
      const east = tileXToLon(tx + 1, z);
      const nw = grid.toGrid(north, west);
      const ne = grid.toGrid(north, east);
      const sw = grid.toGrid(south, west);
      const se = grid.toGrid(south, east);
      // A tile is a near-rectangle in the grid: each edge at the mean of its two corners, so
      // neighbours share their edges exactly.
      const left = (nw.x + sw.x) / 2;
      const right = (ne.x + se.x) / 2;
      const top = (nw.y + ne.y) / 2;
      const bottom = (sw.y + se.y) / 2;
      images.push({
        source: `${BASE}/tiles/${z}/${tx}/${ty}${query}`,
        xref: 'x',
        yref: 'y',
        x: left,
        y: top,
        sizex: right - left,
        sizey: top - bottom,
        xanchor: 'left',
        yanchor: 'top',
        sizing: 'stretch',
        layer: 'below',
      });
    }
  }
  return { key: `${z}/${tx0}-${tx1}/${ty0}-${ty1}${query}`, images };
}

// ---------------------------------------------------------------- the plots' Map switch

let info = null; // GET /tiles
let infoLoading = null;
const plots = new Map(); // plot element -> {redraw, toggle, input, key (of the images drawn), bound}

function wanted() {
  return localStorage.getItem(STORAGE_KEY) === '1';
}

/** Whether a map can be drawn: the station has tiles and a datum places the grid on the earth. */
export function mapAvailable() {
  return Boolean(info?.available && state.datum);
}

function loadInfo() {
  infoLoading ??= getJson('/tiles')
    .then((j) => {
      info = j;
    })
    .catch(() => {
      info = null; // an older station, or no token yet: no switch
    })
    .finally(() => {
      infoLoading = null;
      refresh();
    });
  return infoLoading;
}

function refresh() {
  const available = mapAvailable();
  for (const p of plots.values()) {
    p.toggle.hidden = !available;
    p.input.checked = wanted();
    p.redraw();
  }
}

/** Adds the Map switch to a framed plot's toolbar (shown only when tiles and a datum are there),
 *  and redraws the plot (redraw()) when the switch or the plot's view changes the tiles. */
export function attachMap(plotEl, redraw) {
  if (plots.has(plotEl)) return;
  const input = el('input', { type: 'checkbox', id: `${plotEl.id}-map` });
  const toggle = el('label', { class: 'map-toggle', title: 'Draw the offline map tiles the station was given (avk serve --tiles) under the track' }, input, ' Map');
  toggle.hidden = true;
  input.checked = wanted();
  input.addEventListener('change', () => {
    localStorage.setItem(STORAGE_KEY, input.checked ? '1' : '0');
    refresh();
  });
  plotEl.parentElement.querySelector('.plot-buttons')?.prepend(toggle);
  plots.set(plotEl, { redraw, toggle, input, key: '', bound: false });
  if (plots.size === 1) {
    loadInfo();
    // The datum and the tiles are the station's: read again after every catch-up (a restart).
    on('synced', () => loadInfo());
  }
}

/** The plot's view as drawn: its axes' ranges and the x axis' length in pixels. */
function viewOf(plotEl) {
  const fl = plotEl._fullLayout;
  const xa = fl?.xaxis;
  const ya = fl?.yaxis;
  if (!xa?.range || !ya?.range) return null;
  return { xRange: [...xa.range], yRange: [...ya.range], widthPx: xa._length };
}

function imagesNow(plotEl) {
  if (!wanted() || !mapAvailable()) return { key: '', images: [] };
  return tileImages(viewOf(plotEl), state.datum, info, getToken());
}

/** The layout images for the plot's next draw (`images: mapImages(el)`): the tiles of the view it
 *  shows now. After the draw the view is checked once more (autorange may have moved it, the
 *  operator may zoom or pan) and the plot redrawn when it needs other tiles; images do not take
 *  part in autorange, so that converges at the next draw. */
export function mapImages(plotEl) {
  const p = plots.get(plotEl);
  const { key, images } = imagesNow(plotEl);
  if (!p) return images;
  p.key = key;
  requestAnimationFrame(() => check(plotEl));
  return images;
}

function check(plotEl) {
  const p = plots.get(plotEl);
  if (!p) return;
  if (!p.bound && plotEl.on) {
    p.bound = true;
    // Zoom, pan, double-click: the user's relayout keeps the figure (uirevision) but needs tiles.
    plotEl.on('plotly_relayout', () => check(plotEl));
  }
  if (imagesNow(plotEl).key !== p.key) p.redraw();
}

/** For the browser test: what the switch and the last draw hold. */
export function mapState(plotEl) {
  const p = plots.get(plotEl);
  return { info, available: mapAvailable(), on: wanted(), key: p?.key ?? null };
}

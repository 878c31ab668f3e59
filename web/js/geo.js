// The local grid on the earth: the same WGS-84 local tangent plane as the station's
// vehicle/local_grid.cpp (x east, y north, metres, from the datum `avk serve --datum` names), so a
// latitude/longitude the page shows is the one the Foxglove LocationFix and the MCAP export carry.

const A = 6378137.0;
const F = 1 / 298.257223563;
const E2 = F * (2 - F);
const B = A * (1 - F);
const DEG = Math.PI / 180;

function ecef(latDeg, lonDeg) {
  const lat = latDeg * DEG;
  const lon = lonDeg * DEG;
  const s = Math.sin(lat);
  const n = A / Math.sqrt(1 - E2 * s * s);
  return [n * Math.cos(lat) * Math.cos(lon), n * Math.cos(lat) * Math.sin(lon), n * (1 - E2) * s];
}

function wrapLon(lon) {
  let w = (lon + 180) % 360;
  if (w < 0) w += 360;
  return w - 180;
}

const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

/** The grid of a datum {lat_deg, lon_deg}: toGrid(lat, lon) -> {x, y}, toLatLon(x, y) -> {lat, lon}. */
export function localGrid(datum) {
  const lat0 = datum.lat_deg * DEG;
  const lon0 = wrapLon(datum.lon_deg) * DEG;
  const origin = ecef(datum.lat_deg, wrapLon(datum.lon_deg));
  const east = [-Math.sin(lon0), Math.cos(lon0), 0];
  const north = [-Math.sin(lat0) * Math.cos(lon0), -Math.sin(lat0) * Math.sin(lon0), Math.cos(lat0)];
  const up = [Math.cos(lat0) * Math.cos(lon0), Math.cos(lat0) * Math.sin(lon0), Math.sin(lat0)];
  return {
    toGrid(latDeg, lonDeg) {
      const p = ecef(latDeg, lonDeg);
      const d = [p[0] - origin[0], p[1] - origin[1], p[2] - origin[2]];
      return { x: dot(d, east), y: dot(d, north) };
    },
    // The point of the plane dropped along the datum's up onto the ellipsoid (the root nearest
    // the plane), then its geodetic latitude in closed form: as local_grid.cpp.
    toLatLon(x, y) {
      const q = [0, 1, 2].map((i) => origin[i] + x * east[i] + y * north[i]);
      const a2 = A * A;
      const b2 = B * B;
      const qa = (up[0] * up[0] + up[1] * up[1]) / a2 + (up[2] * up[2]) / b2;
      const qb = 2 * ((q[0] * up[0] + q[1] * up[1]) / a2 + (q[2] * up[2]) / b2);
      const qc = (q[0] * q[0] + q[1] * q[1]) / a2 + (q[2] * q[2]) / b2 - 1;
      const disc = qb * qb - 4 * qa * qc;
      const den = -qb - Math.sqrt(Math.max(disc, 0));
      if (disc < 0 || !(qb > 0) || den === 0) return null;
      const u = (2 * qc) / den;
      const p = [0, 1, 2].map((i) => q[i] + u * up[i]);
      const lat = Math.atan2(p[2], Math.hypot(p[0], p[1]) * (1 - E2));
      const lon = Math.atan2(p[1], p[0]);
      return { lat: lat / DEG, lon: wrapLon(lon / DEG) };
    },
  };
}

/** "42.358456° N, 71.087589° W" (6 decimals: 0.1 m). */
export function formatLatLon(p) {
  if (!p || !Number.isFinite(p.lat) || !Number.isFinite(p.lon)) return '–';
  const ns = p.lat >= 0 ? 'N' : 'S';
  const ew = p.lon >= 0 ? 'E' : 'W';
  return `${Math.abs(p.lat).toFixed(6)}° ${ns}, ${Math.abs(p.lon).toFixed(6)}° ${ew}`;
}

/** A round scale-bar length (1, 2 or 5 × 10^k m) no longer than maxM. */
export function scaleBarLength(maxM) {
  if (!(maxM > 0)) return null;
  const p = 10 ** Math.floor(Math.log10(maxM));
  for (const m of [5, 2, 1]) if (m * p <= maxM) return m * p;
  return p;
}

/** Lines of constant latitude and longitude over a grid box {xMin, xMax, yMin, yMax} (metres),
 *  at a round spacing in degrees that gives about 3 to 8 lines across: [{kind: 'lat'|'lon',
 *  value, x: [], y: []}]. Each line is sampled so that it bends as it should far from the datum. */
export function graticule(datum, box) {
  const g = localGrid(datum);
  const corners = [
    g.toLatLon(box.xMin, box.yMin),
    g.toLatLon(box.xMax, box.yMin),
    g.toLatLon(box.xMin, box.yMax),
    g.toLatLon(box.xMax, box.yMax),
  ].filter(Boolean);
  if (corners.length < 4) return { step: null, lines: [] };
  const lat0 = Math.min(...corners.map((c) => c.lat));
  const lat1 = Math.max(...corners.map((c) => c.lat));
  const lon0 = Math.min(...corners.map((c) => c.lon));
  const lon1 = Math.max(...corners.map((c) => c.lon));
  const span = Math.max(lat1 - lat0, lon1 - lon0);
  let step = null;
  for (const e of [-5, -4, -3, -2, -1, 0]) {
    for (const m of [1, 2, 5]) {
      const s = m * 10 ** e;
      if (!step && span / s <= 8) step = s;
    }
  }
  if (!step) return { step: null, lines: [] };
  const lines = [];
  const N = 24;
  const round = (v) => Number(v.toFixed(7));
  for (let lat = Math.ceil(lat0 / step) * step; lat <= lat1 + 1e-12; lat += step) {
    const x = [];
    const y = [];
    for (let k = 0; k <= N; k++) {
      const p = g.toGrid(lat, lon0 + ((lon1 - lon0) * k) / N);
      x.push(p.x);
      y.push(p.y);
    }
    lines.push({ kind: 'lat', value: round(lat), x, y });
  }
  for (let lon = Math.ceil(lon0 / step) * step; lon <= lon1 + 1e-12; lon += step) {
    const x = [];
    const y = [];
    for (let k = 0; k <= N; k++) {
      const p = g.toGrid(lat0 + ((lat1 - lat0) * k) / N, lon);
      x.push(p.x);
      y.push(p.y);
    }
    lines.push({ kind: 'lon', value: round(lon), x, y });
  }
  return { step, lines };
}

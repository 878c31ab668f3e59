// The page's local grid (web/js/geo.js) against GeographicLib's numbers — the same cases as the
// station's tests/vehicle/test_local_grid.cpp — and round trips, so the latitude and longitude the
// dashboard shows are the station's. Pure functions: no browser, no server.

import { test } from 'node:test';
import assert from 'node:assert/strict';

import { localGrid, formatLatLon, scaleBarLength } from '../js/geo.js';

const MIT = { lat_deg: 42.3584, lon_deg: -71.0876 };

test('the grid matches GeographicLib around the MIT datum to a millimetre', () => {
  // CartConvert -l 42.3584 -71.0876 0 -p 6 (tests/vehicle/test_local_grid.cpp).
  const cases = [
    [42 + 21.71114 / 60, -(71 + 5.44878 / 60), -264.686036, 383.491158],
    [42.3736, -71.119, -2586.241105, 1688.899473],
    [42.33, -71.05, 3099.041236, -3153.985939],
    [42.39, -71.03, 4742.952459, 3511.751665],
  ];
  const g = localGrid(MIT);
  for (const [lat, lon, x, y] of cases) {
    const p = g.toGrid(lat, lon);
    assert.ok(Math.abs(p.x - x) < 1e-3, `x ${p.x} vs ${x}`);
    assert.ok(Math.abs(p.y - y) < 1e-3, `y ${p.y} vs ${y}`);
  }
});

test('grid to latitude/longitude and back is exact to a micrometre, at several datums', () => {
  for (const datum of [MIT, { lat_deg: 0, lon_deg: 0 }, { lat_deg: -33.9, lon_deg: 151.2 }, { lat_deg: 64.1, lon_deg: 179.99 }]) {
    const g = localGrid(datum);
    const o = g.toLatLon(0, 0);
    assert.ok(Math.abs(o.lat - datum.lat_deg) < 1e-12 && Math.abs(o.lon - datum.lon_deg) < 1e-9, 'the datum is the origin');
    for (const [x, y] of [[100, 0], [0, -250], [-1234.5, 987.6], [3000, 3000]]) {
      const ll = g.toLatLon(x, y);
      const back = g.toGrid(ll.lat, ll.lon);
      assert.ok(Math.hypot(back.x - x, back.y - y) < 1e-6, `${x},${y} -> ${back.x},${back.y}`);
    }
  }
});

test('latitude and longitude read with hemispheres, and scale bars are round', () => {
  assert.equal(formatLatLon({ lat: 42.358456, lon: -71.087589 }), '42.358456° N, 71.087589° W');
  assert.equal(formatLatLon({ lat: -33.9, lon: 151.2 }), '33.900000° S, 151.200000° E');
  assert.equal(formatLatLon(null), '–');
  assert.equal(scaleBarLength(37), 20);
  assert.equal(scaleBarLength(9.9), 5);
  assert.equal(scaleBarLength(100), 100);
  assert.equal(scaleBarLength(260), 200);
  assert.equal(scaleBarLength(0), null);
});

test('the lat/lon grid has round lines that really are lines of constant latitude or longitude', async () => {
  const { graticule } = await import('../js/geo.js');
  const g = graticule(MIT, { xMin: -120, xMax: 120, yMin: -120, yMax: 120 });
  assert.ok([1, 2, 5].some((m) => [1e-4, 1e-3, 1e-2].some((e) => Math.abs(g.step - m * e) < 1e-12)), `step ${g.step}`);
  const lat = g.lines.filter((l) => l.kind === 'lat');
  const lon = g.lines.filter((l) => l.kind === 'lon');
  assert.ok(lat.length >= 2 && lat.length <= 9 && lon.length >= 2 && lon.length <= 9, `${lat.length} × ${lon.length}`);
  const grid = localGrid(MIT);
  for (const l of g.lines) {
    assert.ok(Math.abs(l.value / g.step - Math.round(l.value / g.step)) < 1e-6, `${l.value} is a multiple of ${g.step}`);
    for (let k = 0; k < l.x.length; k++) {
      const p = grid.toLatLon(l.x[k], l.y[k]);
      assert.ok(Math.abs((l.kind === 'lat' ? p.lat : p.lon) - l.value) < 1e-9, `${l.kind} ${l.value}: ${JSON.stringify(p)}`);
    }
  }
});

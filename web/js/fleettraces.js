// The fleet on the Live map: every other vehicle the station hears as an arrow along its heading
// with its id and helm mode, its short trail, and the selected vehicle's command point (the point
// it goes to or holds, with the hold radius). Live redraws at 10 Hz through Plotly's traces-only
// path, which takes new x, y and marker angles but any other new array as a change of the whole
// figure: the labels keep their identity until one of them changes (a helm mode, a vehicle come
// or gone), and nothing here is rebuilt until the fleet changes.

import { state } from './state.js';
import { C } from './plots.js';
import { fleetList, fleetVersion, onMap } from './fleet.js';

const OTHER_LINE = { color: C.black, width: 2 };
const HOLD_RING_POINTS = 48;

let cache = { version: -1, selected: undefined, markers: null, trails: null, labels: '' };

/** The other vehicles' markers and trails: {markers, trails}, the same objects while the fleet
 *  has not changed. */
export function fleetTraces() {
  if (cache.version === fleetVersion() && cache.selected === state.vehicleId) return cache;
  const others = fleetList().filter((v) => v.id !== state.vehicleId && onMap(v));
  const labels = others.map((v) => `${v.id} · ${v.helm?.mode ?? 'idle'}`);
  const key = labels.join('\n');
  const text = key === cache.labels && cache.markers ? cache.markers.text : labels;
  const trailX = [];
  const trailY = [];
  for (const v of others) {
    trailX.push(...v.trail.x, NaN); // NaN breaks the line between vehicles
    trailY.push(...v.trail.y, NaN);
  }
  const shown = others.length > 0;
  cache = {
    version: fleetVersion(),
    selected: state.vehicleId,
    labels: key,
    markers: {
      type: 'scatter',
      mode: 'markers+text',
      name: `other vehicles (${others.length})`,
      x: others.map((v) => v.nav.x_m),
      y: others.map((v) => v.nav.y_m),
      text,
      textposition: 'top center',
      textfont: { size: 11, color: C.black },
      cliponaxis: false, // a label at the view's edge is read whole
      marker: { symbol: 'arrow', size: 20, angle: others.map((v) => v.nav.heading_deg ?? 0), color: '#ffffff', line: OTHER_LINE },
      hovertemplate: '%{text}<br>x %{x:.1f} m<br>y %{y:.1f} m<extra>vehicle</extra>',
      showlegend: shown,
      visible: shown ? true : 'legendonly',
    },
    trails: {
      type: 'scatter',
      mode: 'lines',
      name: 'other vehicles (trails)',
      x: trailX,
      y: trailY,
      line: { color: C.grey, width: 1.5, dash: 'dot' },
      hoverinfo: 'skip',
      connectgaps: false,
      showlegend: false,
      visible: shown ? true : 'legendonly',
    },
  };
  return cache;
}

let labelCache = { id: undefined, text: [] };
/** The selected vehicle's id over its marker, on a station of several vehicles (one array while
 *  the selection stands). */
export function selectedLabel() {
  const id = state.fleet.size > 1 ? state.vehicleId : null;
  if (id !== labelCache.id) labelCache = { id, text: id ? [id] : [] };
  return labelCache.text;
}

let commandCache = { key: undefined, trace: null };
/** The selected vehicle's command point: a cross with the hold radius round it, or nothing. */
export function commandTrace(pending) {
  const c = state.helm?.command;
  const hasPoint = c && Number.isFinite(c.x_m) && Number.isFinite(c.y_m);
  const key = JSON.stringify([hasPoint ? [c.kind, c.x_m, c.y_m, c.radius_m] : null, pending]);
  if (key === commandCache.key) return commandCache.trace;
  const x = [];
  const y = [];
  if (hasPoint) {
    const r = Number.isFinite(c.radius_m) ? c.radius_m : 5;
    for (let i = 0; i <= HOLD_RING_POINTS; i++) {
      const a = (2 * Math.PI * i) / HOLD_RING_POINTS;
      x.push(c.x_m + r * Math.sin(a));
      y.push(c.y_m + r * Math.cos(a));
    }
    const k = Math.min(r, 3);
    x.push(NaN, c.x_m - k, c.x_m + k, NaN, c.x_m, c.x_m);
    y.push(NaN, c.y_m, c.y_m, NaN, c.y_m - k, c.y_m + k);
  }
  if (pending) {
    // The point picked for Go to, not sent yet: a diagonal cross.
    x.push(NaN, pending.x - 3, pending.x + 3, NaN, pending.x - 3, pending.x + 3);
    y.push(NaN, pending.y - 3, pending.y + 3, NaN, pending.y + 3, pending.y - 3);
  }
  const shown = x.length > 0;
  const name = hasPoint ? `command: ${c.kind.replace('_', ' ')} point` : 'go-to point (not sent)';
  commandCache = {
    key,
    trace: {
      type: 'scatter',
      mode: 'lines',
      name,
      x,
      y,
      line: { color: C.vermillion, width: 2 },
      hoverinfo: 'name',
      connectgaps: false,
      showlegend: shown,
      visible: shown ? true : 'legendonly',
    },
  };
  return commandCache.trace;
}

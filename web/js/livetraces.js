// The Live view's overlays on the track plot (lat/lon grid, current arrow, expected position)
// and the turn close-up drawn beside it.

import { state } from './state.js';
import { C, baseLayout, equalAxes, draw, showEmpty, vehicleMarker } from './plots.js';
import { along } from './geometry.js';
import { graticule } from './geo.js';
import { currentText } from './livepanels.js';

let turnPlotKey = null;
let turnPlotStart = null; // the start time of the turn the close-up shows

let gratCache = { key: undefined, trace: null };
/** With a datum, a latitude/longitude grid over the operating region (one trace, lines broken by
 *  NaN): where the grid lies on a chart. Without a datum or a region: nothing. */
export function graticuleTrace() {
  const region = state.mission?.config?.operating_region?.polygon_m;
  const key = state.datum && region?.length >= 3 ? JSON.stringify([state.datum, region]) : null;
  if (key !== gratCache.key) {
    let x = [];
    let y = [];
    let step = null;
    if (key) {
      const xs = region.map((p) => p[0]);
      const ys = region.map((p) => p[1]);
      const pad = 0.1 * Math.max(Math.max(...xs) - Math.min(...xs), Math.max(...ys) - Math.min(...ys));
      const g = graticule(state.datum, { xMin: Math.min(...xs) - pad, xMax: Math.max(...xs) + pad, yMin: Math.min(...ys) - pad, yMax: Math.max(...ys) + pad });
      step = g.step;
      for (const l of g.lines) {
        x.push(...l.x, NaN);
        y.push(...l.y, NaN);
      }
    }
    gratCache = {
      key,
      trace: {
        type: 'scatter',
        mode: 'lines',
        name: step ? `lat/lon grid (${step}°)` : 'lat/lon grid',
        x,
        y,
        line: { color: '#9aa3ad', width: 0.8, dash: 'dot' },
        hoverinfo: 'skip',
        visible: x.length ? true : 'legendonly',
        showlegend: x.length > 0,
      },
    };
  }
  return gratCache.trace;
}
/** The current as an arrow from the vehicle: where the water carries it in CURRENT_ARROW_S. */
const CURRENT_ARROW_S = 60;
// One object for every draw: Plotly takes a new array (the symbols, the sizes) as a change.
const CURRENT_MARKER = { symbol: ['circle', 'arrow'], size: [4, 14], angleref: 'previous', color: C.purple };
export function currentTrace(nav) {
  const c = state.current;
  const show = Boolean(c && nav);
  let x = [];
  let y = [];
  if (show) {
    const [ex, ey] = along(nav.x_m, nav.y_m, c.toward_deg, c.speed_mps * CURRENT_ARROW_S);
    x = [nav.x_m, ex];
    y = [nav.y_m, ey];
  }
  return {
    type: 'scatter',
    mode: 'lines+markers',
    name: `current (drift in ${CURRENT_ARROW_S} s)`,
    x,
    y,
    line: { color: C.purple, width: 2.5, dash: 'dot' },
    marker: CURRENT_MARKER,
    visible: show ? true : 'legendonly',
    hovertemplate: `${show ? currentText(c) : ''}<extra>current</extra>`,
  };
}

/** Where the prediction of the running turn puts the vehicle now (GET /maneuvers/ongoing). */
export function expectedTrace(extra = {}) {
  const e = state.turn ? state.ongoing?.expected : null;
  return {
    type: 'scatter',
    mode: 'markers',
    name: `expected now (${state.ongoing?.method === 'avk' ? 'AVK' : 'instantaneous'})`,
    x: e ? [e.x_m] : [],
    y: e ? [e.y_m] : [],
    marker: { symbol: 'circle-open', size: 14, color: C.black, line: { width: 2.5 } },
    visible: e ? true : 'legendonly',
    hovertemplate: 'expected x %{x:.1f} m, y %{y:.1f} m<extra></extra>',
    ...extra,
  };
}

/** The turn close-up: the turn and its predictions at a scale where they can be told apart (the
 *  track plot shows the whole region). Redrawn only when something in it changed. */
export function renderTurnPlot(turn, { turnX, turnY, goalRay, band, preds, nav, faded }) {
  const el = document.getElementById('turn-plot');
  if (!turn?.start) {
    if (turnPlotKey !== 'empty') {
      turnPlotKey = 'empty';
      showEmpty(el, 'No turn yet.');
    }
    return;
  }
  const running = !turn.ended;
  const key = running
    ? `${turn.start.t}|${turnX.length}|${Object.keys(turn.predictions).length}|${nav?.t_s}`
    : `${turn.start.t}|ended|${turnX.length}|${Object.keys(turn.predictions).length}`;
  if (key === turnPlotKey) return;
  turnPlotKey = key;
  // Its own legend: the close-up is read on its own, often without the track plot.
  // Only what is drawn is listed; names without the track plot's "(last turn)" suffix.
  const plain = (name) => name.replace(/ \(last turn\)$/, '');
  const traces = [
    { ...band, name: plain(band.name), showlegend: Boolean(band.x?.length) },
    { type: 'scatter', mode: 'lines+markers', name: running ? 'turn so far' : `turn (${turn.outcome})`, x: turnX, y: turnY, line: { color: C.orange, width: 4 }, marker: { size: 4 }, opacity: faded },
    ...preds.filter((t) => t.visible === true).map((t) => ({ ...t, name: plain(t.name) })),
    { type: 'scatter', mode: 'lines', name: 'goal heading', x: goalRay.x, y: goalRay.y, line: { color: C.vermillion, width: 2, dash: 'longdash' }, opacity: faded },
    expectedTrace({ showlegend: Boolean(state.turn && state.ongoing?.expected) }),
    {
      type: 'scatter',
      mode: 'markers',
      name: 'vehicle',
      showlegend: false,
      x: running && nav ? [nav.x_m] : [],
      y: running && nav ? [nav.y_m] : [],
      marker: vehicleMarker(nav, 20),
    },
  ];
  // A new turn is a new figure: Plotly.react from the last turn's equal axes, somewhere else on
  // the grid, could collapse the y axis to a line and keep it so for the whole turn.
  if (turn.start.t !== turnPlotStart && el._fullLayout) window.Plotly?.purge(el);
  turnPlotStart = turn.start.t;
  draw(el, traces, {
    ...baseLayout({ margin: { l: 44, r: 8, t: 8, b: 36 } }),
    ...equalAxes('x (m)', 'y (m)'),
    showlegend: true,
    legend: { orientation: 'h', x: 0, y: 1.01, yanchor: 'bottom', font: { size: 10 } },
  });
}


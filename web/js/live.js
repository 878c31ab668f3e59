// The Live view: the track in the local grid with the region and its buffer, the vehicle and its
// heading, the turn in progress with its predictions (AVK's with its corridor) and its commanded
// goal, the helm readout,
// the mission's turn-array grid and the event log.
//
// Drawing is decoupled from the stream: messages only mark the view dirty, and one
// requestAnimationFrame redraws at most once a frame, and only while the view is on screen, so a
// 72,000-point track at 10 Hz costs one plot update per nav message at most.

import { state, on } from './state.js';
import { C, METHOD_STYLE, baseLayout, equalAxes, draw, showEmpty, corridorTrace, vehicleMarker, updateScaleBar } from './plots.js';
import { regionRings, along } from './geometry.js';
import { TrackDecimator } from './decimate.js';
import { num, meanSd, headingDiff, el } from './format.js';
import { deviationText, deviationTitle } from './deviation.js';
import { drawSeries } from './timeseries.js';
import { localGrid, formatLatLon, scaleBarLength, graticule } from './geo.js';
import { attachMap, mapImages } from './maptiles.js';
import { renderEventLog } from './eventlog.js';
import { answersFrameText } from './frame.js';
import { setPredictionFrame } from './sync.js';
import { turnsDone } from './banner.js';
import { turnLabel } from './turnlabel.js';

const RAY_M = 20; // length of the goal-heading and heading rays


let plotEl;
let visible = false;
let dirtyPlot = true;
let dirtyText = true;
let dirtyProgress = true;
let dirtySeries = true;
// What the time series shows: {key, frame (window and marks), to (its newest time), pixelS (the
// seconds one pixel of it spans)}.
let seriesShown = { key: '', frame: '', to: -Infinity, pixelS: 0 };
let lastSeriesMs = -Infinity;
let seriesTimer = null;
// Samples that move the plot redraw it at most twice a second: a full redraw of five traces and
// four axes takes two or three frames on a machine without a GPU, and at four a second those were
// one frame in fifteen, past what a 95th-percentile frame time allows. A new window or new turn
// marks redraw at once.
const SERIES_MIN_MS = 500;
const SERIES_MAX_MS = 2000; // how long samples that move the plot by under a pixel wait at most
const SERIES_MAX_POINTS = 3000; // per trace: a 30-minute window at 10 Hz is drawn every 6th sample
let frameRequested = false;
let uirevision = 1;
// Arrays handed to Plotly keep their identity while unchanged, so Plotly.react recomputes only
// the traces that did change.
let regionCache = { key: undefined, region: null, buffer: null, ret: null };
let recordedCache = { n: -1, x: [], y: [] };
let trackCache = { version: -1, older: null, tail: null };
let decimator = null;
let turnPlotKey = null;
let turnPlotStart = null; // the start time of the turn the close-up shows

export function initLive() {
  plotEl = document.getElementById('live-plot');
  const markPlot = () => request(true);
  const markText = () => request(false);
  on('nav', markPlot);
  on('series', () => request(true));
  document.getElementById('ts-window').addEventListener('change', () => request(true));
  on('helm', markText);
  on('mission', () => {
    dirtyProgress = true; // the grid is rebuilt on mission messages only, not at 10 Hz
    request(true);
  });
  on('turn', markPlot);
  on('predictions', markPlot);
  on('ongoing', markPlot);
  on('current', () => {
    markPlot();
    markText();
  });
  on('recorded-turns', markPlot);
  on('restart', markPlot);
  on('nav-history', markPlot);
  on('previous-track', markPlot);
  on('events', renderEvents);
  on('link', markText);
  // A "fit" control: double-click already resets the zoom in Plotly; this is the keyboard way.
  const fit = el('button', { type: 'button', id: 'live-fit', class: 'png', text: 'Fit view', 'aria-label': 'Fit the live plot to the track' });
  fit.addEventListener('click', () => {
    uirevision++;
    operatorAxes = null;
    lastFit = null;
    request(true);
  });

  plotEl.parentElement.querySelector('.plot-buttons')?.prepend(fit);
  attachMap(plotEl, () => request(true));
  // The operator's override of the predictions' current and speed reference.
  for (const [id, key] of [
    ['live-pred-current', 'current'],
    ['live-pred-speedref', 'speedReference'],
  ]) {
    const select = document.getElementById(id);
    select.value = state.predictionFrame[key];
    select.addEventListener('change', () => setPredictionFrame({ [key]: select.value }));
  }
}

export function showLive(isVisible) {
  visible = isVisible;
  if (visible) {
    dirtyPlot = true;
    dirtyText = true;
    dirtyProgress = true;
    renderEvents();
    request(true);
  }
}

function request(plot) {
  if (plot) dirtyPlot = true;
  dirtyText = true;
  if (!visible || frameRequested) return;
  frameRequested = true;
  requestAnimationFrame(frame);
}

function frame() {
  frameRequested = false;
  if (!visible) return;
  if (dirtyText) {
    dirtyText = false;
    renderReadout();
    renderTurnPanel();
  }
  if (dirtyProgress) {
    dirtyProgress = false;
    renderProgress();
  }
  let plotted = false;
  if (dirtyPlot) {
    dirtyPlot = false;
    const t0 = performance.now();
    renderPlot();
    renderTimes.push(performance.now() - t0);
    if (renderTimes.length > 1000) renderTimes.shift();
    dirtySeries = true;
    plotted = true;
  }
  if (dirtySeries) {
    // At most two redraws a second for new samples: five traces of up to 18,000 samples are not
    // redrawn per frame.
    // Never in the frame that updated the track plot: the two together took two to four frames.
    const now = performance.now();
    if (plotted) {
      if (!frameRequested) {
        frameRequested = true;
        requestAnimationFrame(frame);
      }
    } else {
      // Redrawn when it changes by a pixel at least; samples that move it by less wait (at most
      // SERIES_MAX_MS) for more: a full redraw of five traces and four axes costs several frames.
      const change = seriesChange();
      const since = now - lastSeriesMs;
      if (change === 'none') dirtySeries = false;
      else if (
        change === 'frame' ||
        (since >= SERIES_MIN_MS && (change === 'pixel' || since >= SERIES_MAX_MS))
      ) {
        dirtySeries = false;
        lastSeriesMs = now;
        renderSeries();
        seriesTimes.push(performance.now() - now);
        if (seriesTimes.length > 1000) seriesTimes.shift();
      } else if (!seriesTimer) {
        seriesTimer = setTimeout(
          () => {
            seriesTimer = null;
            request(false);
          },
          (change === 'pixel' ? SERIES_MIN_MS : SERIES_MAX_MS) - since,
        );
      }
    }
  }
}

// How long the plot updates took (ms), newest last: the test hook reports them.
export const renderTimes = [];
// How long the time series' redraws took (ms), newest last (web/bench/frame_time.mjs).
export const seriesTimes = [];
// The deviations shown while a turn ran ({text, expected: [x, y]}), newest last, bounded: the test
// hook reports them (at a high real-time factor a turn is on screen for a moment only).
export const deviationLog = [];

/** Forces a synchronous redraw (the test hook measures what a real update costs). */
export function renderNow() {
  dirtyPlot = true;
  dirtyText = true;
  frame();
}

// ---------------------------------------------------------------- plot

function regionTraces() {
  const region = state.mission?.config?.operating_region;
  const key = region ? JSON.stringify(region) : null;
  if (key !== regionCache.key) {
    regionCache = { key, ...regionRings(region) };
  }
  return regionCache;
}

function recordedArrays() {
  const paths = state.recordedTurns;
  if (paths.length !== recordedCache.n || paths !== recordedCache.src) {
    const x = [];
    const y = [];
    for (const p of paths) {
      x.push(...p.x, NaN); // NaN breaks the line between turns
      y.push(...p.y, NaN);
    }
    recordedCache = { n: paths.length, src: paths, x, y };
  }
  return recordedCache;
}

function trackArrays() {
  if (trackCache.version !== state.track.version) {
    decimator ??= new TrackDecimator(state.track);
    const { older, tail } = decimator.update();
    trackCache = { version: state.track.version, older, tail };
  }
  return trackCache;
}

function renderPlot() {
  const reg = regionTraces();
  const rec = recordedArrays();
  const trk = trackArrays();
  const nav = state.nav;
  const turn = state.shownTurn; // in progress, or the last one (ended) until the next starts
  const faded = turn?.ended ? 0.7 : 1;

  // The current turn: the track since its start, highlighted.
  let turnX = [];
  let turnY = [];
  if (turn?.start) {
    // From the start pose on: at a high real-time factor a turn may span only a sample or two.
    const from = state.track.indexAtOrAfter(turn.start.t + 1e-6);
    const to = turn.ended && turn.endT !== null ? state.track.indexAtOrAfter(turn.endT + 1e-6) : state.track.length;
    const a = state.track.arrays(from, to);
    turnX = [turn.start.x, ...a.x];
    turnY = [turn.start.y, ...a.y];
  }
  const pred = (method) => {
    const p = turn?.predictions?.[method];
    const s = METHOD_STYLE[method];
    return {
      type: 'scatter',
      mode: 'lines',
      name: `${s.name} prediction${turn?.ended ? ' (last turn)' : ''}`,
      opacity: faded,
      x: p ? p.trajectory.map((q) => q[0]) : [],
      y: p ? p.trajectory.map((q) => q[1]) : [],
      line: { color: s.color, dash: s.dash, width: 2 },
      visible: p ? true : 'legendonly',
      hoverinfo: 'name',
    };
  };
  // AVK's corridor: the server places it at the turn's start pose with the trajectory (sync.js
  // asks /predict with x, y, heading), so it is drawn as it comes, in the same frame.
  const avkCorridor = turn?.predictions?.avk?.corridor ?? null;
  const band = corridorTrace(avkCorridor, { opacity: faded });
  if (turn?.ended && avkCorridor) band.name += ' (last turn)';
  // Commanded: the goal heading from the turn's start. Measured: the heading from the vehicle.
  let goalRay = { x: [], y: [] };
  if (turn?.start) {
    const [gx, gy] = along(turn.start.x, turn.start.y, turn.goalHeading, RAY_M);
    goalRay = { x: [turn.start.x, gx], y: [turn.start.y, gy] };
  }
  let headingRay = { x: [], y: [] };
  if (nav) {
    const [hx, hy] = along(nav.x_m, nav.y_m, nav.heading_deg, RAY_M);
    headingRay = { x: [nav.x_m, hx], y: [nav.y_m, hy] };
  }

  const grid = graticuleTrace();
  // The previous mission's track, faded grey under this one's (a new mission started while the
  // page was open: tracks.js).
  const previous = {
    type: 'scatter',
    mode: 'lines',
    name: state.previousTrack ? `mission ${state.previousTrack.missionId} track (previous)` : 'previous track',
    x: state.previousTrack?.x ?? [],
    y: state.previousTrack?.y ?? [],
    line: { color: C.grey, width: 1.2 },
    opacity: 0.45,
    visible: state.previousTrack ? true : 'legendonly',
    showlegend: Boolean(state.previousTrack),
    hoverinfo: 'skip',
  };
  const traces = [
    grid,
    { type: 'scatter', mode: 'lines', name: 'region', x: reg.region.x, y: reg.region.y, line: { color: C.black, width: 2 }, hoverinfo: 'skip' },
    { type: 'scatter', mode: 'lines', name: `buffer (${reg.bufferM ?? '–'} m)`, x: reg.buffer.x, y: reg.buffer.y, line: { color: C.grey, width: 1.5, dash: 'dash' }, hoverinfo: 'skip' },
    { type: 'scatter', mode: 'markers', name: 'return point', x: reg.ret.x, y: reg.ret.y, marker: { symbol: 'x-thin-open', size: 12, color: C.black, line: { width: 2 } } },
    // Stored turns as a wide halo under the track: where the turns were, and the history (from
    // REST) of a mission that ran before the page was opened.
    { type: 'scatter', mode: 'lines', name: 'recorded turns', x: rec.x, y: rec.y, line: { color: C.sky, width: 6 }, opacity: 0.55, hoverinfo: 'skip', connectgaps: false },
    previous,
    // The track: its simplified older part (unchanged between updates) and the raw newest minute.
    { type: 'scatter', mode: 'lines', name: 'track', legendgroup: 'track', showlegend: false, x: trk.older.x, y: trk.older.y, line: { color: C.blue, width: 1.5 }, hoverinfo: 'skip' },
    { type: 'scatter', mode: 'lines', name: 'track', legendgroup: 'track', x: trk.tail.x, y: trk.tail.y, line: { color: C.blue, width: 1.5 }, hoverinfo: 'skip' },
    band,
    { type: 'scatter', mode: 'lines', name: turn?.ended ? `last turn (${turn.outcome})` : 'current turn', x: turnX, y: turnY, opacity: faded, line: { color: C.orange, width: 5 }, hoverinfo: 'skip' },
    pred('avk'),
    pred('model'),
    pred('instantaneous'),
    { type: 'scatter', mode: 'lines', name: 'commanded goal heading', x: goalRay.x, y: goalRay.y, opacity: faded, line: { color: C.vermillion, width: 2.5, dash: 'longdash' }, hoverinfo: 'name' },
    { type: 'scatter', mode: 'lines', name: 'measured heading', x: headingRay.x, y: headingRay.y, line: { color: C.green, width: 2.5 }, hoverinfo: 'name' },
    expectedTrace(),
    currentTrace(nav),
    {
      type: 'scatter',
      mode: 'markers',
      name: 'vehicle',
      x: nav ? [nav.x_m] : [],
      y: nav ? [nav.y_m] : [],
      marker: vehicleMarker(nav, 26),
      hovertemplate: 'x %{x:.1f} m<br>y %{y:.1f} m<extra>vehicle</extra>',
    },
  ];
  const layout = {
    ...baseLayout({ margin: { l: 56, r: 10, t: 40, b: 40 } }),
    ...axesToDraw(traces.filter((t) => t !== previous && t !== grid)),
    uirevision,
    showlegend: true,
    images: mapImages(plotEl),
  };
  draw(plotEl, traces, layout, { scrollZoom: true }, { tracesOnly: true });
  updateScaleBar(plotEl, scaleBarLength);
  renderTurnPlot(turn, { turnX, turnY, goalRay, band, preds: [pred('avk'), pred('model'), pred('instantaneous')], nav, faded });
}

let lastAxes = null; // the axes last given to Plotly
let operatorAxes = null; // the fit held while the operator's zoom or pan stands

let zoomBound = false;

/** Plotly keeps a zoom across redraws only while the figure's own range stays the same, and the
 *  fit moves with every sample: once the operator zooms or pans, the fit is held where it was (the
 *  operator's view wins) until Fit view. Redraws by react() fire no relayout event. */
function axesToDraw(traces) {
  if (!zoomBound && plotEl.on) {
    zoomBound = true;
    plotEl.on('plotly_relayout', (e) => {
      if (e && Object.keys(e).some((k) => k.startsWith('xaxis.') || k.startsWith('yaxis.'))) operatorAxes = lastAxes;
    });
  }
  lastAxes = operatorAxes || fittedAxes(traces);
  return lastAxes;
}

const FIT_MARGIN = 0.06; // of the larger span, each side
const FIT_MIN_SPAN_M = 20;

/** The equal axes of the track plot, fitted to `traces`: the current mission (its region, track,
 *  stored turns, the turn drawn with its predictions) and the vehicle. Plotly's own autorange took
 *  in every trace, the previous mission's track too, which shrank the current turn into a corner;
 *  that track is still drawn, faded, wherever it lies. The operator's zoom is kept (uirevision)
 *  until Fit view. */
function fittedAxes(traces) {
  let x0 = Infinity;
  let x1 = -Infinity;
  let y0 = Infinity;
  let y1 = -Infinity;
  for (const t of traces) {
    if (t.visible === false || t.visible === 'legendonly' || !t.x) continue;
    for (let i = 0; i < t.x.length; i++) {
      const x = t.x[i];
      const y = t.y[i];
      if (!Number.isFinite(x) || !Number.isFinite(y)) continue;
      if (x < x0) x0 = x;
      if (x > x1) x1 = x;
      if (y < y0) y0 = y;
      if (y > y1) y1 = y;
    }
  }
  const axes = equalAxes();
  if (!Number.isFinite(x0)) {
    lastFit = null;
    return axes;
  }
  const span = Math.max(x1 - x0, y1 - y0, FIT_MIN_SPAN_M);
  const pad = FIT_MARGIN * span;
  const cx = (x0 + x1) / 2;
  const cy = (y0 + y1) / 2;
  const half = (v0, v1) => Math.max((v1 - v0) / 2, FIT_MIN_SPAN_M / 2) + pad;
  let fit = { x: [cx - half(x0, x1), cx + half(x0, x1)], y: [cy - half(y0, y1), cy + half(y0, y1)] };
  const edge = pad / 3; // what is fitted stays this far inside a kept fit
  if (lastFit && holds(lastFit.x, x0 - edge, x1 + edge, fit.x) && holds(lastFit.y, y0 - edge, y1 + edge, fit.y)) fit = lastFit;
  lastFit = fit;
  axes.xaxis = { ...axes.xaxis, range: fit.x.slice(), autorange: false };
  axes.yaxis = { ...axes.yaxis, range: fit.y.slice(), autorange: false };
  return axes;
}

// The last fit is kept while what is fitted stays inside it and it is not much larger than a
// fresh fit: the heading ray swinging at the edge of the track moved the fit by a metre at every
// sample, and each move costs a full redraw of the plot (axes, labels, legend) instead of the
// traces alone.
const FIT_SLACK = 1.25;
let lastFit = null;

function holds(range, v0, v1, fresh) {
  return range[0] <= v0 && v1 <= range[1] && range[1] - range[0] <= FIT_SLACK * (fresh[1] - fresh[0]);
}

function seriesSpanS() {
  return Number(document.getElementById('ts-window').value) || 120;
}

/** What drawing the time series now would change: 'none' (nothing), 'frame' (the window or the
 *  marks), 'pixel' (the samples, by a pixel at least) or 'subpixel' (newer samples that move the
 *  plot by less than a pixel: a 30-minute window moves by a pixel in about 1.6 s, not at every
 *  sample). */
function seriesChange() {
  const buf = state.series;
  const frame = `${seriesSpanS()}|${state.turnMarks.length}|${state.turnMarksMission}`;
  if (!buf.length) return seriesShown.key === 'empty' ? 'none' : 'frame';
  if (`${buf.version}|${frame}` === seriesShown.key) return 'none';
  if (frame !== seriesShown.frame) return 'frame';
  const moved = buf.lastT() - seriesShown.to;
  return moved < 0 || moved >= seriesShown.pixelS ? 'pixel' : 'subpixel';
}

/** The time series over the chosen window, ending at the newest sample. */
function renderSeries() {
  const el = document.getElementById('live-series');
  const buf = state.series;
  const span = seriesSpanS();
  if (!buf.length) {
    seriesShown = { key: 'empty', frame: '', to: -Infinity, pixelS: 0 };
    showEmpty(el, 'No navigation yet.');
    return;
  }
  const to = buf.lastT();
  const from = to - span;
  const frame = `${span}|${state.turnMarks.length}|${state.turnMarksMission}`;
  drawSeries(el, buf.window(from, to, SERIES_MAX_POINTS), { from, to, marks: state.turnMarks });
  const widthPx = el._fullLayout?.xaxis?._length;
  seriesShown = { key: `${buf.version}|${frame}`, frame, to, pixelS: widthPx > 0 ? span / widthPx : 0 };
}

let gratCache = { key: undefined, trace: null };
/** With a datum, a latitude/longitude grid over the operating region (one trace, lines broken by
 *  NaN): where the grid lies on a chart. Without a datum or a region: nothing. */
function graticuleTrace() {
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

/** "0.20 ± 0.01 m/s toward 182 ± 3°": the station's estimate of the current. */
export function currentText(c) {
  if (!c) return 'not estimated yet';
  const still = c.significant ? '' : ' (not told apart from still water)';
  return `${num(c.speed_mps, 2)} ± ${num(c.speed_sd_mps, 2)} m/s toward ${num(c.toward_deg, 0)} ± ${num(c.toward_sd_deg, 0)}°${still}`;
}

/** What the shown turn's predictions (and the running turn's deviation) move against, as each
 *  answer says it: one line when they agree. */
export function predictionFrameText() {
  const turn = state.shownTurn;
  const answers = {};
  for (const [method, p] of Object.entries(turn?.predictions ?? {})) answers[METHOD_STYLE[method]?.name ?? method] = p;
  if (state.turn && state.ongoing) answers.deviation = state.ongoing;
  return answersFrameText(answers);
}

/** The current as an arrow from the vehicle: where the water carries it in CURRENT_ARROW_S. */
const CURRENT_ARROW_S = 60;
// One object for every draw: Plotly takes a new array (the symbols, the sizes) as a change.
const CURRENT_MARKER = { symbol: ['circle', 'arrow'], size: [4, 14], angleref: 'previous', color: C.purple };
function currentTrace(nav) {
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
function expectedTrace(extra = {}) {
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
function renderTurnPlot(turn, { turnX, turnY, goalRay, band, preds, nav, faded }) {
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

// ---------------------------------------------------------------- text panels

function text(id, v) {
  const e = document.getElementById(id);
  if (e && e.textContent !== v) e.textContent = v;
}

let gridOf = { datum: null, grid: null };
/** The vehicle's latitude and longitude: the grid point through the station's datum
 *  (`avk serve --datum`); without a datum the grid is all there is. */
export function latLonText(nav) {
  if (!state.datum) return 'no datum (avk serve --datum LAT,LON)';
  if (!nav || !Number.isFinite(nav.x_m)) return '–';
  if (gridOf.datum !== state.datum) gridOf = { datum: state.datum, grid: localGrid(state.datum) };
  return formatLatLon(gridOf.grid.toLatLon(nav.x_m, nav.y_m));
}

function renderReadout() {
  const nav = state.nav;
  const helm = state.helm;
  text('live-mode', helm?.mode ?? '–');
  text('live-x', num(nav?.x_m, 1));
  text('live-y', num(nav?.y_m, 1));
  text('live-speed', num(nav?.speed_mps, 2));
  text('live-heading', num(nav?.heading_deg, 1));
  text('live-dspeed', num(helm?.desired_speed_mps, 2));
  text('live-dheading', num(helm?.desired_heading_deg, 1));
  text('live-t', num(nav?.t_s, 1));
  text('live-latlon', latLonText(nav));
  text('live-current', currentText(state.current));
  text('live-pred-frame', predictionFrameText());
  // Only a real vehicle (the M200 driver) reports a battery and a frontseat link.
  const fs = nav?.frontseat;
  for (const e of document.querySelectorAll('.frontseat')) e.hidden = !fs;
  if (fs) {
    text('live-battery', num(fs.battery_v, 2));
    text('live-frontseat', `${fs.failsafe === 'none' ? 'ok' : `all stop (${fs.failsafe})`}, ${fs.bad_lines} bad lines, ${fs.disconnects} disconnects`);
  }
}

function renderTurnPanel() {
  const turn = state.turn;
  const nav = state.nav;
  const last = state.lastTurn;
  const shown = state.shownTurn;
  const preds = shown ? Object.keys(shown.predictions) : [];
  if (turn) {
    text('turn-cmd-speed', num(turn.speed, 2));
    text('turn-cmd-dpsi', num(turn.dheading, 0));
    text('turn-cmd-goal', num(turn.goalHeading, 1));
    text('turn-meas-speed', num(nav?.speed_mps, 2));
    text('turn-meas-dpsi', turn.start && nav ? num(headingDiff(nav.heading_deg, turn.start.heading), 1) : '–');
    text('turn-meas-heading', num(nav?.heading_deg, 1));
    // Numbered as the event log and Replay number it: the next of the plan's turns to be done.
    const done = turn.missionId === state.mission?.id ? turnsDone(state.mission) : null;
    const which = done && done.done < done.planned ? ` · ${turnLabel(done.done + 1, done.planned)}` : '';
    text('turn-status', `Turn running (attempt ${turn.attempt ?? 1})${which} · predictions: ${preds.length ? preds.join(', ') : 'none yet'}`);
    const deviation = deviationText(state.ongoing);
    text('turn-deviation', deviation);
    const devEl = document.getElementById('turn-deviation');
    const devTitle = deviationTitle(state.ongoing);
    if (devEl.title !== devTitle) devEl.title = devTitle;
    const e = state.ongoing?.expected;
    if (e && deviation !== deviationLog.at(-1)?.text) {
      deviationLog.push({ text: deviation, expected: [e.x_m, e.y_m] });
      if (deviationLog.length > 200) deviationLog.shift();
    }
  } else {
    // Between turns (conditioning, containment, the return leg) nothing is a turn: the helm's
    // desired values are in the Vehicle readout, not presented here as one.
    for (const id of ['turn-cmd-speed', 'turn-cmd-dpsi', 'turn-cmd-goal', 'turn-meas-speed', 'turn-meas-dpsi', 'turn-meas-heading']) text(id, '–');
    text('turn-deviation', '–');
    text(
      'turn-status',
      last
        ? `No turn running. Last turn: ${last.event}${last.reason ? ` (${last.reason})` : ''}, ${num(last.speed_mps, 2)} m/s, Δψ ${num(last.goal_dheading_deg, 0)}°, advance ${num(last.advance_m, 1)} m, transfer ${num(last.transfer_m, 1)} m${preds.length ? `; drawn with its predictions: ${preds.join(', ')}` : ''}.`
        : 'No turn running.',
    );
  }
  const parts = [];
  if (state.conditioningSinceT !== null && nav) parts.push(`conditioning for ${num(nav.t_s - state.conditioningSinceT, 1)} s`);
  if (typeof last?.condition_set_time_s === 'number') parts.push(`last ${num(last.condition_set_time_s, 1)} s`);
  if (state.mission?.condition_set_time_s) parts.push(`mission mean ${meanSd(state.mission.condition_set_time_s, 1, ' s', state.mission.condition_set?.episodes?.set)}`);
  // Attempts the mission wasted: conditioning cut short by containment (or a pause, a link loss)
  // and conditions not set in time. A healthy mission shows few of either.
  const episodes = state.mission?.condition_set?.episodes;
  if (episodes) parts.push(`${episodes.interrupted ?? 0} interrupted, ${episodes.timeout ?? 0} timed out`);
  text('live-cst', parts.length ? parts.join(' · ') : '–');
}

/** A cell's state for the grid: running, done, aborted (given up, or tried and then the mission
 *  ended), not run (the mission ended before it was ever tried), pending. Each has a mark as well
 *  as a colour. */
export function cellState(c, missionStatus) {
  if (c.running) return 'running';
  const planned = c.planned ?? 1;
  if ((c.ok ?? 0) >= planned) return 'done';
  if ((c.given_up ?? 0) > 0) return 'aborted';
  const ended = ['done', 'aborted', 'halted'].includes(missionStatus);
  const tried = (c.ok ?? 0) + (c.aborted ?? 0) + (c.rejected ?? 0) > 0;
  if (ended) return tried ? 'aborted' : 'notrun';
  // Aborted attempts that will be re-queued stay pending (the label counts them with ✗n).
  return 'pending';
}

const MARK = { pending: '·', running: '▶', done: '✓', aborted: '✗', notrun: '–' };
const STATE_NAME = { pending: 'pending', running: 'running', done: 'done', aborted: 'aborted', notrun: 'not run' };

function renderProgress() {
  const grid = document.getElementById('progress-grid');
  const m = state.mission;
  text('progress-title', m ? `· mission ${m.id} “${m.name}” · ${m.status}${m.helm_mode ? ` · ${m.helm_mode}` : ''}` : '');
  if (!m) {
    grid.replaceChildren(el('p', { class: 'small muted', text: 'No mission yet. Start one in the Mission view.' }));
    text('progress-counts', '');
    return;
  }
  const cells = m.cells ?? [];
  if (cells.length === 0) {
    grid.replaceChildren(el('p', { class: 'small muted', text: m.config?.kind === 'persistent_excitation' ? 'Persistent excitation: no turn array.' : 'No cells.' }));
    text('progress-counts', '');
    return;
  }
  const speeds = [...new Set(cells.map((c) => c.speed_mps))].sort((a, b) => a - b);
  const dpsis = [...new Set(cells.map((c) => c.dheading_deg))].sort((a, b) => a - b);
  const counts = { pending: 0, running: 0, done: 0, aborted: 0, notrun: 0 };
  const table = el('table', { 'aria-label': 'Turn array: rows are speeds, columns heading changes' });
  table.append(el('tr', {}, el('th', { scope: 'col', text: 'm/s \\ Δψ' }), ...dpsis.map((d) => el('th', { scope: 'col', text: `${d}°` }))));
  for (const s of speeds) {
    const tr = el('tr', {}, el('th', { scope: 'row', text: s.toFixed(2) }));
    for (const d of dpsis) {
      const c = cells.find((q) => q.speed_mps === s && q.dheading_deg === d);
      if (!c) {
        tr.append(el('td'));
        continue;
      }
      const st = cellState(c, m.status);
      counts[st]++;
      const extra = (c.aborted ?? 0) + (c.rejected ?? 0);
      const label = `${MARK[st]} ${c.ok ?? 0}/${c.planned ?? 1}${extra ? ` ✗${extra}` : ''}`;
      tr.append(
        el('td', {
          class: `st-${st}`,
          text: label,
          title: `${s} m/s, ${d}°: ${STATE_NAME[st]}; ok ${c.ok ?? 0} of ${c.planned ?? 1}, aborted ${c.aborted ?? 0}, rejected ${c.rejected ?? 0}${c.given_up ? `, given up ${c.given_up}` : ''}`,
        }),
      );
    }
    table.append(tr);
  }
  grid.replaceChildren(table);
  text('progress-counts', `pending ${counts.pending} · running ${counts.running} · done ${counts.done} · aborted ${counts.aborted}${counts.notrun ? ` · not run ${counts.notrun}` : ''}`);
}

function renderEvents() {
  if (!visible) return;
  renderEventLog(document.getElementById('event-log')); // phrases, one entry per happening (eventlog.js)
}

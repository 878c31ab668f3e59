// The Live view: the track in the local grid with the region and its buffer, the vehicle and its
// heading, the turn in progress with its predictions (AVK's with its corridor) and its commanded
// goal, the helm readout,
// the mission's turn-array grid and the event log.
//
// Drawing is decoupled from the stream: messages only mark the view dirty, and one
// requestAnimationFrame redraws at most once a frame, and only while the view is on screen, so a
// 72,000-point track at 10 Hz costs one plot update per nav message at most.

import { state, on } from './state.js';
import { C, METHOD_STYLE, baseLayout, draw, showEmpty, corridorTrace, vehicleMarker, updateScaleBar } from './plots.js';
import { regionRings, along } from './geometry.js';
import { trafficTrace } from './traffic.js';
import { TrackDecimator } from './decimate.js';
import { el } from './format.js';
import { drawSeries } from './timeseries.js';
import { scaleBarLength } from './geo.js';
import { attachMap, mapImages } from './maptiles.js';
import { renderEventLog } from './eventlog.js';
import { setPredictionFrame } from './predictions.js';
import { axesToDraw, resetAxes } from './liveaxes.js';
import { graticuleTrace, currentTrace, expectedTrace, renderTurnPlot } from './livetraces.js';
import { renderReadout, renderTurnPanel, renderProgress } from './livepanels.js';
import { fleetTraces, selectedLabel, commandTrace } from './fleettraces.js';
import { pendingPoint } from './commands.js';

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
  on('traffic', markPlot);
  on('fleet', markPlot);
  on('command-point', markPlot);
  on('restart', markPlot);
  // Another vehicle shown: the view is fitted to it afresh (the operator's zoom was of the other).
  on('vehicle-changed', () => {
    uirevision++;
    resetAxes();
    markPlot();
  });
  on('nav-history', markPlot);
  on('previous-track', markPlot);
  on('events', renderEvents);
  on('link', markText);
  // A "fit" control: double-click already resets the zoom in Plotly; this is the keyboard way.
  const fit = el('button', { type: 'button', id: 'live-fit', class: 'png', text: 'Fit view', 'aria-label': 'Fit the live plot to the track' });
  fit.addEventListener('click', () => {
    uirevision++;
    resetAxes();
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
  // AIS contacts may be kilometres away: drawn, but the view is fitted to this vehicle's own.
  const traffic = trafficTrace();
  // The station's other vehicles, and where the selected one is told to go or hold.
  const fleet = fleetTraces();
  const command = commandTrace(pendingPoint());
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
    traffic,
    fleet.trails,
    command,
    fleet.markers,
    {
      type: 'scatter',
      mode: 'markers+text',
      name: 'vehicle',
      x: nav ? [nav.x_m] : [],
      y: nav ? [nav.y_m] : [],
      text: selectedLabel(),
      textposition: 'top center',
      textfont: { size: 12, color: C.black },
      marker: vehicleMarker(nav, 26),
      hovertemplate: `${state.vehicleId ?? ''}<br>x %{x:.1f} m<br>y %{y:.1f} m<extra>vehicle</extra>`,
    },
  ];
  // Fitted to this vehicle's mission, its command point and the fleet's positions; AIS contacts
  // and the trails are drawn wherever they lie.
  const unfitted = new Set([previous, grid, traffic, fleet.trails]);
  const layout = {
    ...baseLayout({ margin: { l: 56, r: 10, t: 40, b: 40 } }),
    ...axesToDraw(plotEl, traces.filter((t) => !unfitted.has(t))),
    uirevision,
    showlegend: true,
    images: mapImages(plotEl),
  };
  draw(plotEl, traces, layout, { scrollZoom: true }, { tracesOnly: true });
  updateScaleBar(plotEl, scaleBarLength);
  renderTurnPlot(turn, { turnX, turnY, goalRay, band, preds: [pred('avk'), pred('model'), pred('instantaneous')], nav, faded });
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


function renderEvents() {
  if (!visible) return;
  renderEventLog(document.getElementById('event-log')); // phrases, one entry per happening (eventlog.js)
}

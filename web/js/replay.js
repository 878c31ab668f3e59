// The Replay view: any stored mission played back from its stored navigation (GET
// /missions/{id}/nav), at any speed or scrubbed by hand. It draws what Live drew at that moment:
// the track so far, the vehicle, the turn in progress with its predictions placed at its start
// pose, the events up to then and the time series around it. The predictions never saw the
// replayed mission (`without_mission`): a turn is not shown against a table built from itself.

import { state, on } from './state.js';
import { getJson } from './api.js';
import { C, METHOD_STYLE, baseLayout, equalAxes, draw, showEmpty, corridorTrace, vehicleMarker, updateScaleBar } from './plots.js';
import { scaleBarLength } from './geo.js';
import { regionRings, along } from './geometry.js';
import { el, num, headingDiff, wrap360 } from './format.js';
import { SeriesBuffer, drawSeries } from './timeseries.js';
import { simplify } from './decimate.js';
import { firstAtOrAfter, lastAtOrBefore } from './bisect.js';
import { phrase } from './eventlog.js';
import { timeLabel } from './clock.js';
import { plannedTurns, storedTurnLabel } from './turnlabel.js';
import { refreshMissions } from './sync.js';
import { answerableMethods, sameCell } from './predictions.js';
import { attachMap, mapImages } from './maptiles.js';

const $ = (id) => document.getElementById(id);
const NAV_PAGE = 10000;
const SERIES_SPAN_S = 120; // the time series shows a minute either side of the replayed moment
const RAY_M = 20;

let visible = false;
let rec = null; // the loaded mission: {id, report, nav:{t,x,y,heading,speed,dh,ds,mode}, events, turns, series, rings}
let nowT = 0; // the replayed moment, station clock
let playing = false;
let lastFrameMs = null;
let frameRequested = false;
let lastSeriesMs = -Infinity;
let loading = null;

export function initReplay() {
  $('rp-load').addEventListener('click', () => loadSelected());
  $('rp-play').addEventListener('click', () => setPlaying(!playing));
  $('rp-slider').addEventListener('input', (ev) => {
    seek(Number(ev.target.value));
  });
  $('rp-back').addEventListener('click', () => seek(nowT - 10));
  $('rp-fwd').addEventListener('click', () => seek(nowT + 10));
  $('rp-prev-turn').addEventListener('click', () => jumpTurn(-1));
  $('rp-next-turn').addEventListener('click', () => jumpTurn(1));
  on('missions', renderMissionChoice);
  attachMap($('rp-plot'), () => request());
}

export function showReplay(isVisible) {
  visible = isVisible;
  if (!visible) {
    setPlaying(false);
    return;
  }
  renderMissionChoice();
  if (!state.missions.length) refreshMissions().catch(() => {});
  request();
}

function renderMissionChoice() {
  const sel = $('rp-mission');
  const keep = sel.value;
  const missions = [...state.missions].sort((a, b) => b.id - a.id);
  sel.replaceChildren(
    ...missions.map((m) => el('option', { value: m.id, text: `${m.id} · ${m.name} · ${m.status}${m.vehicle_id ? ` · ${m.vehicle_id}` : ''}` })),
  );
  if (keep && missions.some((m) => String(m.id) === keep)) sel.value = keep;
  $('rp-load').disabled = missions.length === 0;
}

function setStatus(text) {
  $('rp-status').textContent = text;
}

async function loadSelected() {
  const id = Number($('rp-mission').value);
  if (!id) return;
  await loadMissionForReplay(id);
}

/** Reads a mission whole (report, every nav page, events) and shows its first moment. */
export function loadMissionForReplay(id) {
  loading = doLoad(id).finally(() => {
    loading = null;
  });
  return loading;
}

async function doLoad(id) {
  setPlaying(false);
  setStatus(`Loading mission ${id}…`);
  try {
    const report = await getJson(`/missions/${id}`);
    const rows = [];
    let after;
    for (;;) {
      const page = await getJson(`/missions/${id}/nav`, { limit: NAV_PAGE, after });
      rows.push(...page.items);
      if (page.next === null || page.next === undefined) break;
      after = page.next;
    }
    const events = [];
    let evAfter;
    for (;;) {
      const page = await getJson(`/missions/${id}/events`, { limit: 1000, after: evAfter });
      events.push(...page.items);
      if (page.next === null || page.next === undefined) break;
      evAfter = page.next;
    }
    if (rows.length === 0) {
      rec = null;
      setStatus(`Mission ${id} has no stored navigation to replay.`);
      showEmpty($('rp-plot'), 'Nothing to replay.');
      showEmpty($('rp-series'), 'Nothing to replay.');
      return;
    }
    const nav = {
      t: rows.map((r) => r.t_s),
      x: rows.map((r) => r.x_m),
      y: rows.map((r) => r.y_m),
      heading: rows.map((r) => r.heading_deg),
      speed: rows.map((r) => r.speed_mps),
      dh: rows.map((r) => r.desired_heading_deg),
      ds: rows.map((r) => r.desired_speed_mps),
      mode: rows.map((r) => r.helm_mode),
    };
    const series = new SeriesBuffer(rows.length);
    for (const r of rows) series.push(r.t_s, r.heading_deg, r.desired_heading_deg, r.speed_mps, r.desired_speed_mps);
    const turns = (report.turn_list ?? []).map((r) => ({ ...r, predictions: null }));
    // The track drawn simplified (within 0.1 m, as Live's): two hours at 10 Hz stay cheap to
    // redraw at every frame of a playback.
    const keep = simplify(nav.x, nav.y, 0, nav.x.length - 1, 0.1);
    rec = {
      id,
      report,
      nav,
      keep,
      whole: { x: keep.map((i) => nav.x[i]), y: keep.map((i) => nav.y[i]) },
      events,
      turns,
      series,
      rings: regionRings(report.config?.operating_region),
      marks: turns.map((r) => ({ t: r.start_time_s, label: `${r.goal_dheading_deg > 0 ? '+' : ''}${Math.round(r.goal_dheading_deg)}°` })),
    };
    const slider = $('rp-slider');
    slider.min = String(nav.t[0]);
    slider.max = String(nav.t[nav.t.length - 1]);
    slider.step = '0.1';
    slider.disabled = false;
    $('rp-play').disabled = false;
    for (const b of ['rp-back', 'rp-fwd', 'rp-prev-turn', 'rp-next-turn']) $(b).disabled = false;
    setStatus(
      `Mission ${id} “${report.name}”: ${rows.length} samples, ${num(nav.t[nav.t.length - 1] - nav.t[0], 0)} s, ${turns.length} turns, ${events.length} events. Predictions are made without this mission’s turns, from the station’s other missions and a model not trained on this one.`,
    );
    seek(nav.t[0]);
  } catch (e) {
    setStatus(`Mission ${id} could not be read: ${e.message}`);
  }
}

function setPlaying(on) {
  playing = on && rec !== null;
  if (playing && nowT >= rec.nav.t[rec.nav.t.length - 1]) nowT = rec.nav.t[0]; // from the start again
  $('rp-play').textContent = playing ? 'Pause' : 'Play';
  $('rp-play').setAttribute('aria-pressed', playing ? 'true' : 'false');
  lastFrameMs = null;
  if (playing) request();
}

/** Moves the replayed moment (clamped to the mission). */
export function seek(t) {
  if (!rec) return;
  const t0 = rec.nav.t[0];
  const t1 = rec.nav.t[rec.nav.t.length - 1];
  nowT = Math.min(t1, Math.max(t0, t));
  request();
}

function jumpTurn(dir) {
  if (!rec?.turns.length) return;
  const starts = rec.turns.map((r) => r.start_time_s);
  const next = dir > 0 ? starts.find((s) => s > nowT + 0.05) : [...starts].reverse().find((s) => s < nowT - 0.05);
  if (next !== undefined) seek(next);
}

function request() {
  if (!visible || frameRequested) return;
  frameRequested = true;
  requestAnimationFrame(frame);
}

function frame(ms) {
  frameRequested = false;
  if (!visible || !rec) return;
  if (playing) {
    const speed = Number($('rp-speed').value) || 1;
    if (lastFrameMs !== null) nowT += ((ms - lastFrameMs) / 1000) * speed;
    lastFrameMs = ms;
    const t1 = rec.nav.t[rec.nav.t.length - 1];
    if (nowT >= t1) {
      nowT = t1;
      setPlaying(false);
    }
  }
  render();
  if (playing) request();
}

/** Index of the last sample at or before t. */
function indexAt(t) {
  const ts = rec.nav.t;
  return lastAtOrBefore(ts.length, (i) => ts[i], t);
}

/** The vehicle at time t, interpolated between the stored samples around it (heading along the
 *  shorter way round). */
export function poseAt(t) {
  const n = rec.nav;
  const i = indexAt(t);
  const j = Math.min(i + 1, n.t.length - 1);
  const f = j === i || n.t[j] === n.t[i] ? 0 : Math.min(1, Math.max(0, (t - n.t[i]) / (n.t[j] - n.t[i])));
  return {
    i,
    t,
    x_m: n.x[i] + f * (n.x[j] - n.x[i]),
    y_m: n.y[i] + f * (n.y[j] - n.y[i]),
    heading_deg: wrap360(n.heading[i] + f * headingDiff(n.heading[j], n.heading[i])),
    speed_mps: n.speed[i] + f * (n.speed[j] - n.speed[i]),
    desired_heading_deg: n.dh[i],
    desired_speed_mps: n.ds[i],
    mode: n.mode[i],
  };
}

/** The turn under way at t: commanded at or before t and not yet ended. */
function turnAt(t) {
  return rec.turns.find((r) => r.start_time_s <= t && t <= r.end_time_s) ?? null;
}

/** A turn's start pose: the stored sample at its commanding time. */
function turnStart(r) {
  const p = poseAt(r.start_time_s);
  return { x: p.x_m, y: p.y_m, heading: p.heading_deg };
}

/** Which predictions a stored turn can be shown against fairly: only by what never saw its
 *  mission (`without_mission`), so a replayed turn is not graded by a table built from it: AVK
 *  where its cell holds a turn of another mission, the model one not trained on this mission. */
function fairMethods(turn) {
  // The table and models read are the live vehicle's: another vehicle's mission gets neither.
  if (rec.report.vehicle_id !== state.vehicleId) return ['instantaneous'];
  const own = rec.turns.filter((t) => t.status === 'ok' && sameCell(t.speed_mps, t.goal_dheading_deg, turn.speed_mps, turn.goal_dheading_deg)).length;
  return answerableMethods(turn.speed_mps, turn.goal_dheading_deg, { cellTurns: own, missionId: rec.id });
}

/** What the drawn predictions are built from, and which are missing for want of one that never
 *  saw this mission. */
function fairnessNote(turn) {
  if (!turn.fair) return '';
  const missing = [['avk', 'AVK table'], ['model', 'yaw model']].filter(([m]) => !turn.fair.includes(m)).map(([, name]) => name);
  return `Predictions are made without this mission's turns${missing.length ? `; no ${missing.join(' or ')} without them` : ''}.`;
}

async function predictTurn(r) {
  r.predictions = {};
  const start = turnStart(r);
  const methods = fairMethods(r);
  r.fair = methods;
  await Promise.all(
    methods.map(async (method) => {
      try {
        r.predictions[method] = await getJson(`/vehicles/${encodeURIComponent(rec.report.vehicle_id)}/predict`, {
          speed: r.speed_mps,
          dheading: r.goal_dheading_deg,
          method,
          x: start.x,
          y: start.y,
          heading: start.heading,
          ...(method === 'instantaneous' ? {} : { without_mission: rec.id }),
        });
      } catch (e) {
        console.warn(`replay: no ${method} prediction`, e.message);
      }
    }),
  );
  request();
}

const capitalised = (t) => t.charAt(0).toUpperCase() + t.slice(1);

function render() {
  const nav = rec.nav;
  const p = poseAt(nowT);
  const slider = $('rp-slider');
  if (Math.abs(Number(slider.value) - nowT) > 0.05) slider.value = String(nowT);
  const elapsed = nowT - nav.t[0];
  // The mission's own time is the station clock (×realtime factor on the simulator); the moment's
  // wall-clock time where it is known (this server session ran the mission).
  const when = timeLabel(nowT, rec.report);
  $('rp-time').textContent = `T+${num(elapsed, 1)} s of ${num(nav.t[nav.t.length - 1] - nav.t[0], 1)} s, station clock (t ${num(nowT, 1)} s)${when.wall ? ` · ${when.text} local time` : ''}`;
  $('rp-mode').textContent = p.mode ?? '–';
  $('rp-xy').textContent = `${num(p.x_m, 1)} m east, ${num(p.y_m, 1)} m north`;
  $('rp-heading').textContent = `${num(p.heading_deg, 1)}° (desired ${num(p.desired_heading_deg, 1)}°)`;
  $('rp-speed-now').textContent = `${num(p.speed_mps, 2)} m/s (desired ${num(p.desired_speed_mps, 2)} m/s)`;

  const turn = turnAt(nowT);
  if (turn && turn.predictions === null) predictTurn(turn);
  $('rp-turn').textContent = turn
    ? `${capitalised(storedTurnLabel(rec.turns, turn, plannedTurns(rec.report.cells)))} under way: ${num(turn.speed_mps, 2)} m/s, Δψ ${turn.goal_dheading_deg > 0 ? '+' : ''}${num(turn.goal_dheading_deg, 0)}°, ${num(nowT - turn.start_time_s, 1)} s in; it ended ${turn.status}${typeof turn.advance_m === 'number' ? ` (advance ${num(turn.advance_m, 1)} m, transfer ${num(turn.transfer_m, 1)} m)` : ''}. ${fairnessNote(turn)}`
    : 'No turn under way at this moment.';
  renderTrack(p, turn);
  renderEvents();
  const now = performance.now();
  if (!playing || now - lastSeriesMs > 250) {
    lastSeriesMs = now;
    const from = nowT - SERIES_SPAN_S / 2;
    const to = nowT + SERIES_SPAN_S / 2;
    drawSeries($('rp-series'), rec.series.window(from, to, 3000), { from, to, marks: rec.marks, cursor: nowT });
  }
}

function renderTrack(p, turn) {
  const nav = rec.nav;
  const k = p.i + 1;
  // The simplified track up to the sample before now, then the raw samples since its last kept
  // point, then the interpolated pose.
  const m = firstAtOrAfter(rec.keep.length, (i) => rec.keep[i], k); // kept indices ascend
  const lastKept = m > 0 ? rec.keep[m - 1] : 0;
  const past = {
    x: [...rec.whole.x.slice(0, m), ...nav.x.slice(lastKept + 1, k), p.x_m],
    y: [...rec.whole.y.slice(0, m), ...nav.y.slice(lastKept + 1, k), p.y_m],
  };
  let turnX = [];
  let turnY = [];
  let goal = { x: [], y: [] };
  const pred = (method) => {
    const q = turn?.predictions?.[method];
    const s = METHOD_STYLE[method];
    return {
      type: 'scatter',
      mode: 'lines',
      name: `${s.name} prediction`,
      x: q ? q.trajectory.map((v) => v[0]) : [],
      y: q ? q.trajectory.map((v) => v[1]) : [],
      line: { color: s.color, dash: s.dash, width: 2 },
      visible: q ? true : 'legendonly',
      hoverinfo: 'name',
    };
  };
  if (turn) {
    const start = turnStart(turn);
    const a = indexAt(turn.start_time_s);
    turnX = [start.x, ...nav.x.slice(a + 1, k), p.x_m];
    turnY = [start.y, ...nav.y.slice(a + 1, k), p.y_m];
    const [gx, gy] = along(start.x, start.y, wrap360(start.heading + turn.goal_dheading_deg), RAY_M);
    goal = { x: [start.x, gx], y: [start.y, gy] };
  }
  const [hx, hy] = along(p.x_m, p.y_m, p.heading_deg, RAY_M);
  const r = rec.rings;
  const traces = [
    { type: 'scatter', mode: 'lines', name: 'region', x: r.region.x, y: r.region.y, line: { color: C.black, width: 2 }, hoverinfo: 'skip' },
    { type: 'scatter', mode: 'lines', name: `buffer (${r.bufferM ?? '–'} m)`, x: r.buffer.x, y: r.buffer.y, line: { color: C.grey, width: 1.5, dash: 'dash' }, hoverinfo: 'skip' },
    { type: 'scatter', mode: 'lines', name: 'whole track', x: rec.whole.x, y: rec.whole.y, line: { color: C.grey, width: 1.5 }, opacity: 0.6, hoverinfo: 'skip' },
    { type: 'scatter', mode: 'lines', name: 'track so far', x: past.x, y: past.y, line: { color: C.blue, width: 1.5 }, hoverinfo: 'skip' },
    corridorTrace(turn?.predictions?.avk?.corridor ?? null),
    { type: 'scatter', mode: 'lines', name: 'turn so far', x: turnX, y: turnY, line: { color: C.orange, width: 5 }, hoverinfo: 'skip' },
    pred('avk'),
    pred('model'),
    pred('instantaneous'),
    { type: 'scatter', mode: 'lines', name: 'commanded goal heading', x: goal.x, y: goal.y, line: { color: C.vermillion, width: 2.5, dash: 'longdash' }, hoverinfo: 'name' },
    { type: 'scatter', mode: 'lines', name: 'measured heading', x: [p.x_m, hx], y: [p.y_m, hy], line: { color: C.green, width: 2.5 }, hoverinfo: 'name' },
    {
      type: 'scatter',
      mode: 'markers',
      name: 'vehicle',
      x: [p.x_m],
      y: [p.y_m],
      marker: vehicleMarker(p, 24),
      hovertemplate: 'x %{x:.1f} m<br>y %{y:.1f} m<extra>vehicle</extra>',
    },
  ];
  draw($('rp-plot'), traces, { ...baseLayout({ margin: { l: 56, r: 10, t: 40, b: 40 } }), ...equalAxes(), uirevision: rec.id, showlegend: true, images: mapImages($('rp-plot')) });
  updateScaleBar($('rp-plot'), scaleBarLength);
}

let eventsKey = '';
function renderEvents() {
  const shown = rec.events.filter((e) => e.t_s <= nowT + 1e-9);
  const key = `${rec.id}|${shown.length}`;
  if (key === eventsKey) return;
  eventsKey = key;
  const list = $('rp-events');
  const items = shown.slice(-100).reverse();
  // T+ mission time, the wall-clock time (when this server session ran it) on hover; the
  // station's words for the kind, as in Live's log.
  list.replaceChildren(
    ...items.map((e) => {
      const when = timeLabel(e.t_s, rec.report);
      return el(
        'li',
        { 'data-kind': e.kind },
        el('span', { class: 't', text: `T+${num(e.t_s - rec.nav.t[0], 1)} s`, title: when.wall ? `${when.text} · ${when.title}` : when.title }),
        el('span', { class: 'kind', text: phrase(e.kind, e.message) }),
        el('span', { text: e.message }),
      );
    }),
  );
  if (!items.length) list.replaceChildren(el('li', { class: 'muted', text: 'No events yet at this moment.' }));
}

/** For the browser test: the replayed moment and what is drawn. */
export function replayState() {
  return rec ? { id: rec.id, t: nowT, t0: rec.nav.t[0], t1: rec.nav.t[rec.nav.t.length - 1], playing, loading: loading !== null } : { loading: loading !== null };
}

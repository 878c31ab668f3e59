// The Encounter view: the own vehicle at the origin and contacts with their velocity
// vectors, placed and dragged with the mouse; every candidate heading change as a trajectory
// coloured by its predicted CPA (POST /vehicles/{vid}/maneuvers/evaluate), the chosen one with
// its AVK corridor against the instantaneous ray of the same heading change, both methods'
// choices side by side, and "Run in simulator" (POST .../maneuvers/simulate): what the vehicle
// actually did, and its actual CPA. The choice is the station's risk rule (the smallest heading
// change whose risk of coming inside the standoff is at most the limit; optionally kept to
// starboard where COLREGS asks it), over ground by default: the answer says its frame, the
// current and the speed reference, and the operator may override them.

import { state, on } from './state.js';
import { postJson } from './api.js';
import { C, METHOD_STYLE, baseLayout, equalAxes, draw, corridorTrace } from './plots.js';
import { along } from './geometry.js';
import { el, num, setStatus } from './format.js';
import { cktCovers } from './predictions.js';
import { frameFields, answerFrameText, riskText, marginText, explanationText, colregsText, candidateText } from './frame.js';

const $ = (id) => document.getElementById(id);
const VECTOR_S = 10; // velocity vectors show 10 s of travel
const DEBOUNCE_MS = 150; // evaluations while a contact is dragged
const PICK_PX = 16; // how near the pointer must be to a contact to pick it up
const BINS = 12; // colour classes of the candidate fan
const SIM_MAX_HORIZON_S = 300;

/** The question: the own vehicle sits at the origin; contacts at their positions at t = 0. */
export const encounter = {
  own: { heading: 0, speed: 1.0 },
  contacts: [{ x: 30, y: 30, course: 270, speed: 1.0 }],
  standoff: 10,
  horizon: 120,
  step: 5,
  method: 'avk',
  maxRiskPct: 5, // the risk rule's limit, in percent
  colregs: false, // keep to starboard where COLREGS rules 14 and 15 ask it
  current: 'auto', // auto | live | none (frame.js)
  speedReference: 'auto', // auto | over_ground | through_water
};

let plotEl;
let visible = false;
let timer = null;
let seq = 0;
let drag = null; // {index} while a contact is dragged
// The last answers: the chosen method's, the instantaneous one's, the simulator's.
let result = { main: null, inst: null, method: null, note: '' };
let flown = null;

export function initEncounter() {
  plotEl = $('enc-plot');
  for (const [id, key, parse] of [
    ['enc-heading', 'heading', Number],
    ['enc-speed', 'speed', Number],
    ['enc-standoff', 'standoff', Number],
    ['enc-horizon', 'horizon', Number],
    ['enc-step', 'step', Number],
    ['enc-method', 'method', String],
    ['enc-max-risk', 'maxRiskPct', Number],
    ['enc-current', 'current', String],
    ['enc-speedref', 'speedReference', String],
  ]) {
    const input = $(id);
    const target = key === 'heading' || key === 'speed' ? encounter.own : encounter;
    input.value = target[key];
    input.addEventListener('change', () => {
      target[key] = parse(input.value);
      changed(true);
    });
  }
  const colregs = $('enc-colregs');
  colregs.checked = encounter.colregs;
  colregs.addEventListener('change', () => {
    encounter.colregs = colregs.checked;
    changed(true);
  });
  $('enc-add').addEventListener('click', () => {
    // A new contact crossing ahead from starboard, offset from the others so it can be picked.
    const k = encounter.contacts.length;
    encounter.contacts.push({ x: 25 + 8 * k, y: 35 + 6 * k, course: 270, speed: 1.0 });
    changed(true);
  });
  $('enc-simulate').addEventListener('click', simulate);
  plotEl.addEventListener('mousedown', pickUp, true);
  window.addEventListener('mousemove', dragTo);
  window.addEventListener('mouseup', drop);
  on('ckt', () => {
    if (visible) changed(true);
  });
  on('vehicle-changed', () => {
    result = { main: null, inst: null, method: null, note: '' }; // asked again of the new vehicle (below)
  });
  on('synced', () => {
    if (visible && !result.main) changed(true);
  });
  renderContacts();
}

export function showEncounter(isVisible) {
  visible = isVisible;
  if (visible) changed(true);
}

/** Something in the question changed: redraw what is known, evaluate again (debounced). */
function changed(now = false) {
  flown = null;
  if (plotEl) setStatus($('enc-sim'), '');
  renderContacts();
  render();
  clearTimeout(timer);
  timer = setTimeout(evaluate, now ? 0 : DEBOUNCE_MS);
}

// ---------------------------------------------------------------- the question and the answers

/** The encounter as the endpoints take it: own vehicle at the origin, the contacts, the standoff. */
function question() {
  return {
    own: { x_m: 0, y_m: 0, heading_deg: encounter.own.heading, speed_mps: encounter.own.speed },
    contacts: encounter.contacts.map((c) => ({ x_m: c.x, y_m: c.y, course_deg: c.course, speed_mps: c.speed })),
    standoff_m: encounter.standoff,
  };
}

/** The evaluation's body: the question, the risk rule's limit and COLREGS, and the operator's
 *  frame (nothing for "auto": the station answers over ground where it knows the current). */
export function body(method, e = encounter) {
  return {
    ...question(),
    horizon_s: e.horizon,
    candidate_step_deg: e.step,
    method,
    max_risk: Math.min(1, Math.max(0, (Number.isFinite(e.maxRiskPct) ? e.maxRiskPct : 5) / 100)),
    colregs: e.colregs,
    ...frameFields({ current: e.current, speedReference: e.speedReference }),
  };
}

/** The method asked: the one chosen, unless the station cannot answer it (no table covering the
 *  speed, no model), then the instantaneous assumption, said so. */
function methodToAsk() {
  const m = encounter.method;
  if (m === 'avk' && !cktCovers(encounter.own.speed))
    return { method: 'instantaneous', note: `No CKT covers ${encounter.own.speed} m/s yet: the instantaneous assumption only.` };
  if (m === 'model' && state.models.length === 0) return { method: 'instantaneous', note: 'No stored model yet: the instantaneous assumption only.' };
  return { method: m, note: '' };
}

// One evaluation in flight at a time: a question asked meanwhile (a contact dragged on) is asked
// when it returns, the newest only. Each evaluation is one or two expensive requests, and a busy
// station answering slowly must not collect the page's stale questions until its per-address
// limit refuses the current one.
let inFlight = false;
let askAgain = false;

async function evaluate() {
  if (!visible) return;
  if (inFlight) {
    askAgain = true;
    return;
  }
  const status = $('enc-status');
  if (!state.vehicleId) {
    setStatus(status, 'No vehicle.');
    return;
  }
  if (encounter.contacts.length === 0) {
    result = { main: null, inst: null, method: null, note: '' };
    setStatus(status, 'Add a contact.');
    render();
    return;
  }
  ++seq;
  const { method, note } = methodToAsk();
  const path = `/vehicles/${encodeURIComponent(state.vehicleId)}/maneuvers/evaluate`;
  inFlight = true;
  try {
    const [main, inst] = await Promise.all([
      postJson(path, body(method)),
      method === 'instantaneous' ? null : postJson(path, body('instantaneous')),
    ]);
    if (askAgain) return; // a newer question is on its way
    result = { main, inst: inst ?? main, method, note };
    setStatus(status, note || `${main.candidates.length} candidates, ${main.contacts.length} contact${main.contacts.length === 1 ? '' : 's'}.`);
  } catch (e) {
    if (askAgain) return;
    result = { main: null, inst: null, method, note };
    setStatus(status, e.message, 'error');
  } finally {
    inFlight = false;
    if (askAgain) {
      askAgain = false;
      evaluate();
    }
  }
  renderChoice();
  render();
}

/** "chosen: +35° (CPA 12.3 m, edge 10.8 m)", or "no candidate clears". */
export function choiceText(answer) {
  const c = answer?.chosen;
  if (!answer) return '–';
  if (!c) return `no candidate clears ${num(answer.standoff_m, 1)} m`;
  const d = c.dheading_deg;
  const edge = typeof c.min_edge_cpa_m === 'number' ? `, edge ${num(c.min_edge_cpa_m, 1)} m` : '';
  return `chosen: ${d > 0 ? '+' : ''}${num(d, 0)}° (CPA ${num(c.min_cpa_m, 1)} m${edge})`;
}

function renderChoice() {
  const main = result.main;
  const chosen = $('enc-chosen');
  chosen.textContent = choiceText(main);
  chosen.dataset.dheading = main?.chosen ? String(main.chosen.dheading_deg) : 'none';
  chosen.dataset.evaluations = String(seq);
  chosen.dataset.method = result.method ?? '';
  $('enc-chosen-method').textContent = `${METHOD_STYLE[result.method ?? 'avk'].name}:`;
  const same = result.method === 'instantaneous';
  $('enc-inst-row').hidden = same;
  $('enc-chosen-inst').textContent = same ? '' : choiceText(result.inst);
  $('enc-simulate').disabled = !main?.chosen;
  const risk = $('enc-risk');
  risk.textContent = riskText(main?.chosen, main?.max_risk);
  risk.dataset.risk = typeof main?.chosen?.risk === 'number' ? String(main.chosen.risk) : '';
  $('enc-margin').textContent = marginText(main?.chosen);
  $('enc-explanation').textContent = explanationText(main?.chosen);
  const rule = colregsText(main?.chosen, main?.prefer_starboard);
  $('enc-colregs-rule').textContent = rule;
  $('enc-colregs-rule').hidden = !rule;
  const frame = $('enc-frame');
  frame.textContent = main ? answerFrameText(main) : '–';
  frame.dataset.frame = main?.frame ?? '';
}

async function simulate() {
  const main = result.main;
  if (!main?.chosen || !state.vehicleId) return;
  const out = $('enc-sim');
  setStatus(out, 'Flying…');
  const d = main.chosen.dheading_deg;
  const flight = { ...question(), dheading_deg: d, horizon_s: Math.min(encounter.horizon, SIM_MAX_HORIZON_S) };
  try {
    const s = await postJson(`/vehicles/${encodeURIComponent(state.vehicleId)}/maneuvers/simulate`, flight);
    flown = { ...s, dheading_deg: d };
    const kept = s.violated ? `standoff ${num(encounter.standoff, 1)} m violated` : `standoff ${num(encounter.standoff, 1)} m kept`;
    setStatus(out, `Flown ${d > 0 ? '+' : ''}${num(d, 0)}°: actual CPA ${num(s.min_cpa_m, 1)} m, ${kept}${s.note ? ` (${s.note})` : ''}.`, s.violated ? 'error' : 'ok');
    out.dataset.violated = String(s.violated);
  } catch (e) {
    flown = null;
    setStatus(out, e.message, 'error');
  }
  render();
}

// ---------------------------------------------------------------- the contacts table

function renderContacts() {
  const tbody = $('enc-contacts').querySelector('tbody');
  tbody.replaceChildren(
    ...encounter.contacts.map((c, i) => {
      const input = (key, label, step) => {
        const inp = el('input', { type: 'number', step, value: String(c[key]), 'aria-label': `contact ${i + 1} ${label}`, class: 'num', 'data-contact': String(i), 'data-key': key });
        inp.addEventListener('change', () => {
          const v = Number(inp.value);
          if (!Number.isFinite(v)) return;
          c[key] = v;
          changed(true);
        });
        return el('td', {}, inp);
      };
      const remove = el('button', { type: 'button', class: 'secondary', text: '✗', 'aria-label': `remove contact ${i + 1}` });
      remove.addEventListener('click', () => {
        encounter.contacts.splice(i, 1);
        changed(true);
      });
      return el('tr', {}, el('th', { scope: 'row', text: String(i + 1) }), input('x', 'x east (m)', '1'), input('y', 'y north (m)', '1'), input('course', 'course (°)', '5'), input('speed', 'speed (m/s)', '0.1'), el('td', {}, remove));
    }),
  );
}

// ---------------------------------------------------------------- dragging

function axes() {
  const fl = plotEl._fullLayout;
  return fl?.xaxis?.c2p ? fl : null;
}

function pointer(ev) {
  const fl = axes();
  if (!fl) return null;
  // Pixels from the axes' own origin: with equal axes the x axis is narrowed inside the margins.
  const r = plotEl.getBoundingClientRect();
  const px = ev.clientX - r.left - fl.xaxis._offset;
  const py = ev.clientY - r.top - fl.yaxis._offset;
  return { px, py, x: fl.xaxis.p2c(px), y: fl.yaxis.p2c(py) };
}

function pickUp(ev) {
  if (ev.button !== 0) return;
  const p = pointer(ev);
  const fl = axes();
  if (!p || !fl) return;
  let best = null;
  encounter.contacts.forEach((c, i) => {
    const d = Math.hypot(fl.xaxis.c2p(c.x) - p.px, fl.yaxis.c2p(c.y) - p.py);
    if (d <= PICK_PX && (!best || d < best.d)) best = { i, d };
  });
  if (!best) return;
  // The axes hold still while dragging: the pointer's grid position must not move under it.
  drag = { index: best.i, range: viewRange() };
  plotEl.classList.add('dragging');
  ev.preventDefault();
  ev.stopPropagation();
}

function dragTo(ev) {
  if (!drag) return;
  const p = pointer(ev);
  if (!p) return;
  const c = encounter.contacts[drag.index];
  c.x = Math.round(p.x * 10) / 10;
  c.y = Math.round(p.y * 10) / 10;
  changed(false);
}

function drop() {
  if (!drag) return;
  drag = null;
  plotEl.classList.remove('dragging');
  changed(true);
}

// ---------------------------------------------------------------- the plot

/** Predicted CPA -> colour: vermillion at 0, yellow at the standoff, blue at twice it and beyond. */
const SCALE = [
  [0, C.vermillion],
  [0.5, C.yellow],
  [1, C.blue],
];

function mix(a, b, f) {
  const pa = parseInt(a.slice(1), 16);
  const pb = parseInt(b.slice(1), 16);
  const ch = (p, s) => (p >> s) & 255;
  const c = [16, 8, 0].map((s) => Math.round(ch(pa, s) + f * (ch(pb, s) - ch(pa, s))));
  return `rgb(${c.join(', ')})`;
}

export function cpaColour(cpa, standoff) {
  const f = Math.max(0, Math.min(1, cpa / (2 * standoff)));
  return f <= 0.5 ? mix(SCALE[0][1], SCALE[1][1], f / 0.5) : mix(SCALE[1][1], SCALE[2][1], (f - 0.5) / 0.5);
}

/** The judged figure of a candidate: the corridor's nearer edge when there is one. */
const judged = (k) => (typeof k.min_edge_cpa_m === 'number' ? k.min_edge_cpa_m : k.min_cpa_m);

/** The fan in BINS traces of one colour each (a gap between paths): 73 paths redraw fast. */
function fanTraces(answer, standoff) {
  const bins = Array.from({ length: BINS }, () => ({ x: [], y: [] }));
  for (const k of answer?.candidates ?? []) {
    const f = Math.max(0, Math.min(1, judged(k) / (2 * standoff)));
    const b = bins[Math.min(BINS - 1, Math.floor(f * BINS))];
    for (const p of k.path) {
      b.x.push(p[1]);
      b.y.push(p[2]);
    }
    b.x.push(null);
    b.y.push(null);
  }
  return bins.map((b, i) => ({
    type: 'scatter',
    mode: 'lines',
    name: 'candidates',
    legendgroup: 'fan',
    showlegend: i === 0,
    x: b.x,
    y: b.y,
    line: { color: cpaColour(((i + 0.5) / BINS) * 2 * standoff, standoff), width: 1.2 },
    opacity: 0.75,
    hoverinfo: 'skip',
  }));
}

/** Each candidate's end, coloured as its path, carrying its tooltip (risk, CPA): the fan itself
 *  skips hovering, 73 paths of hover points would be slow. */
function candidateEnds(answer, standoff) {
  const ks = (answer?.candidates ?? []).filter((k) => k.path?.length);
  return {
    type: 'scatter',
    mode: 'markers',
    name: 'candidate ends',
    showlegend: false,
    x: ks.map((k) => k.path.at(-1)[1]),
    y: ks.map((k) => k.path.at(-1)[2]),
    text: ks.map((k) => candidateText(k)),
    marker: { size: 6, color: ks.map((k) => cpaColour(judged(k), standoff)), line: { color: C.black, width: 0.5 } },
    hovertemplate: '%{text}<extra></extra>',
  };
}

const ELLIPSE_EVERY_S = 10; // the band is drawn every 10 s along the chosen path

/** The chosen candidate's position band: its ellipse (at the answer's share) every ELLIPSE_EVERY_S
 *  along the path, one trace broken by nulls. */
export function bandEllipses(candidate, everyS = ELLIPSE_EVERY_S) {
  const x = [];
  const y = [];
  const path = candidate?.path ?? [];
  const band = candidate?.band ?? [];
  let next = 0;
  for (let i = 0; i < path.length && i < band.length; i++) {
    const [t, px, py] = path[i];
    if (t + 1e-9 < next) continue;
    next = t + everyS;
    const e = band[i];
    if (!(e.major_m > 0)) continue;
    // The major axis' direction clockwise from north: unit vectors along it and across it.
    const a = (e.major_axis_deg * Math.PI) / 180;
    const ux = Math.sin(a);
    const uy = Math.cos(a);
    for (let k = 0; k <= 36; k++) {
      const w = (k / 36) * 2 * Math.PI;
      const m = e.major_m * Math.cos(w);
      const n = e.minor_m * Math.sin(w);
      x.push(px + m * ux + n * uy);
      y.push(py + m * uy - n * ux);
    }
    x.push(null);
    y.push(null);
  }
  return { x, y };
}

/** The band of a timed path with its half widths: each point moved sideways both ways. */
export function corridorOf(path, halfWidths, share) {
  if (!Array.isArray(halfWidths) || halfWidths.length !== path.length || path.length < 2) return null;
  const left = [];
  const right = [];
  for (let i = 0; i < path.length; i++) {
    const a = path[Math.max(0, i - 1)];
    const b = path[Math.min(path.length - 1, i + 1)];
    const dx = b[1] - a[1];
    const dy = b[2] - a[2];
    const len = Math.hypot(dx, dy) || 1;
    const nx = -dy / len; // left of the direction of travel
    const ny = dx / len;
    const w = halfWidths[i];
    left.push([path[i][1] + nx * w, path[i][2] + ny * w]);
    right.push([path[i][1] - nx * w, path[i][2] - ny * w]);
  }
  return { share, left, right, half_width_m: halfWidths };
}

function line(name, path, style, extra = {}) {
  return { type: 'scatter', mode: 'lines', name, x: path.map((p) => p[1]), y: path.map((p) => p[2]), line: style, hoverinfo: 'name', ...extra };
}

function candidateAt(answer, dheading) {
  return answer?.candidates?.find((k) => Math.abs(k.dheading_deg - dheading) < 1e-9) ?? null;
}

function viewRange() {
  let r = 40;
  for (const c of encounter.contacts) r = Math.max(r, Math.hypot(c.x, c.y) + c.speed * VECTOR_S + 10);
  return Math.min(r * 1.15, 1000);
}

function render() {
  if (!visible || !plotEl) return;
  const standoff = encounter.standoff > 0 ? encounter.standoff : 10;
  const main = result.main;
  const inst = result.inst;
  const chosen = main?.chosen ? main.candidates[main.chosen.index] : null;
  const instChosen = inst?.chosen && inst !== main ? inst.candidates[inst.chosen.index] : null;
  const sameRay = chosen && inst !== main ? candidateAt(inst, chosen.dheading_deg) : null;
  const band = corridorTrace(chosen ? corridorOf(chosen.path, chosen.half_width_m, main.corridor) : null);
  const ellipses = bandEllipses(chosen);
  const [ox, oy] = along(0, 0, encounter.own.heading, encounter.own.speed * VECTOR_S);
  const vectors = { x: [], y: [] };
  const circles = { x: [], y: [] };
  encounter.contacts.forEach((c, i) => {
    const [vx, vy] = along(c.x, c.y, c.course, c.speed * VECTOR_S);
    vectors.x.push(c.x, vx, null);
    vectors.y.push(c.y, vy, null);
    // The contact where the chosen maneuver passes it closest, with the standoff around it.
    const t = chosen?.contacts?.[i]?.cpa?.time_s;
    if (typeof t === 'number') {
      const [cx, cy] = along(c.x, c.y, c.course, c.speed * t);
      for (let k = 0; k <= 48; k++) {
        const a = (k / 48) * 2 * Math.PI;
        circles.x.push(cx + standoff * Math.cos(a));
        circles.y.push(cy + standoff * Math.sin(a));
      }
      circles.x.push(null);
      circles.y.push(null);
    }
  });
  const m = result.method ?? 'avk';
  const traces = [
    ...fanTraces(main, standoff),
    band,
    line(`instantaneous ray, same Δψ`, sameRay?.path ?? [], { color: METHOD_STYLE.instantaneous.color, dash: 'dot', width: 2.5 }, { visible: sameRay ? true : 'legendonly' }),
    line(`instantaneous choice`, instChosen?.path ?? [], { color: METHOD_STYLE.instantaneous.color, dash: 'dash', width: 3 }, { visible: instChosen ? true : 'legendonly' }),
    line(`${METHOD_STYLE[m].name} choice`, chosen?.path ?? [], { color: METHOD_STYLE[m].color, width: 4 }, { visible: chosen ? true : 'legendonly' }),
    { type: 'scatter', mode: 'lines', name: `position band of the choice (${Math.round((main?.band_share ?? 0.9) * 100)} %, every ${ELLIPSE_EVERY_S} s)`, x: ellipses.x, y: ellipses.y, line: { color: METHOD_STYLE[m].color, width: 1 }, opacity: 0.6, hoverinfo: 'skip', visible: ellipses.x.length ? true : 'legendonly' },
    candidateEnds(main, standoff),
    line('flown (simulator)', flown?.track ?? [], { color: C.green, width: 3 }, { visible: flown ? true : 'legendonly' }),
    { type: 'scatter', mode: 'lines', name: `standoff ${num(standoff, 0)} m at CPA`, x: circles.x, y: circles.y, line: { color: C.vermillion, dash: 'dash', width: 1 }, hoverinfo: 'skip', visible: circles.x.length ? true : 'legendonly' },
    { type: 'scatter', mode: 'lines', name: 'velocity (10 s)', x: [0, ox, null, ...vectors.x], y: [0, oy, null, ...vectors.y], line: { color: C.black, width: 2 }, hoverinfo: 'skip' },
    {
      type: 'scatter',
      mode: 'markers',
      name: 'own vehicle',
      x: [0],
      y: [0],
      marker: { symbol: 'triangle-up', size: 16, angle: encounter.own.heading, color: C.yellow, line: { color: C.black, width: 2 } },
      hovertemplate: 'own vehicle<extra></extra>',
    },
    {
      type: 'scatter',
      mode: 'markers+text',
      name: 'contacts (drag)',
      x: encounter.contacts.map((c) => c.x),
      y: encounter.contacts.map((c) => c.y),
      text: encounter.contacts.map((_, i) => String(i + 1)),
      textposition: 'top right',
      marker: { symbol: 'diamond', size: 15, color: C.purple, line: { color: C.black, width: 1.5 } },
      hovertemplate: 'contact %{text}: x %{x:.1f} m, y %{y:.1f} m<extra></extra>',
    },
    // The colour bar of the fan, carried by one point too small to see, under the own vehicle.
    {
      type: 'scatter',
      mode: 'markers',
      name: 'predicted CPA',
      showlegend: false,
      hoverinfo: 'skip',
      x: [0],
      y: [0],
      marker: {
        size: 1,
        opacity: 0,
        color: [0],
        cmin: 0,
        cmax: 2 * standoff,
        colorscale: SCALE,
        showscale: true,
        colorbar: { title: { text: `predicted CPA (m)${main?.use_corridor && m === 'avk' ? ', corridor edge' : ''}`, side: 'right' }, thickness: 12, len: 0.8 },
      },
    },
  ];
  const r = drag?.range ?? viewRange();
  const ax = equalAxes();
  ax.xaxis.range = [-r, r];
  ax.yaxis.range = [-r, r];
  draw(plotEl, traces, { ...baseLayout({ margin: { l: 56, r: 10, t: 40, b: 40 } }), ...ax, dragmode: false, showlegend: true }, { scrollZoom: false });
}

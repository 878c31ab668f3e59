// The Mission view: a form for the mission file (docs/mission-format.md), the server's 422
// validation errors shown next to the fields they name (JSON pointers), start, and pause /
// resume / abort of a mission. Empty optional fields are left out so the server's defaults apply.

import { state, on } from './state.js';
import { postJson, ApiError } from './api.js';
import { EXAMPLES } from './examples.js';
import { C, baseLayout, equalAxes, draw, showEmpty } from './plots.js';
import { insetPolygon, ring } from './geometry.js';
import { el, fillTable, setStatus } from './format.js';
import { timeLabel, fmtElapsed, missionWallElapsed } from './clock.js';
import { loadMission, refreshMissions } from './sync.js';

// id -> [JSON pointer, kind]. Kinds: list (numbers), number, int, text, select, points, point.
const FIELDS = {
  'm-name': ['/name', 'text'],
  'm-kind': ['/kind', 'select'],
  'm-speeds': ['/turn_array/speeds_mps', 'list'],
  'm-dheadings': ['/turn_array/dheadings_deg', 'list'],
  'm-direction': ['/turn_array/direction', 'select'],
  'm-repeats': ['/turn_array/repeats', 'int'],
  'm-attempts': ['/turn_array/max_attempts', 'int'],
  'm-x-speed': ['/excitation/speed_mps', 'number'],
  'm-x-duration': ['/excitation/duration_s', 'number'],
  'm-x-minstep': ['/excitation/min_step_deg', 'number'],
  'm-x-maxstep': ['/excitation/max_step_deg', 'number'],
  'm-x-minint': ['/excitation/min_interval_s', 'number'],
  'm-x-maxint': ['/excitation/max_interval_s', 'number'],
  'm-x-seed': ['/excitation/seed', 'int'],
  'm-speedtol': ['/condition_set/speed_tolerance_mps', 'number'],
  'm-yawrate': ['/condition_set/max_yaw_rate_dps', 'number'],
  'm-window': ['/condition_set/window', 'int'],
  'm-cstimeout': ['/condition_set/timeout_s', 'number'],
  'm-threshold': ['/constant_heading/completion_threshold_deg', 'number'],
  'm-chtimeout': ['/constant_heading/timeout_s', 'number'],
  'm-polygon': ['/operating_region/polygon_m', 'points'],
  'm-buffer': ['/operating_region/buffer_m', 'number'],
  'm-return': ['/operating_region/return_point_m', 'point'],
  'm-returnspeed': ['/operating_region/return_speed_mps', 'number'],
  'm-capture': ['/operating_region/capture_radius_m', 'number'],
};
const KIND_ONLY = { turn_array: 'turns', condition_set: 'turns', constant_heading: 'turns', excitation: 'persistent_excitation' };

const $ = (id) => document.getElementById(id);

class FieldError extends Error {
  constructor(pointer, message) {
    super(message);
    this.pointer = pointer;
  }
}

function parseNumberList(text, pointer) {
  const parts = text.split(/[\s,;]+/).filter((s) => s.length > 0);
  return parts.map((p, i) => {
    const v = Number(p);
    if (!Number.isFinite(v)) throw new FieldError(`${pointer}/${i}`, `“${p}” is not a number`);
    return v;
  });
}

function parsePoints(text, pointer) {
  const lines = text.split('\n').map((l) => l.trim()).filter((l) => l.length > 0);
  return lines.map((l, i) => {
    const v = parseNumberList(l, `${pointer}/${i}`);
    if (v.length !== 2) throw new FieldError(`${pointer}/${i}`, `line ${i + 1}: expected “x, y”, got “${l}”`);
    return v;
  });
}

function setPointer(obj, pointer, value) {
  const keys = pointer.split('/').slice(1);
  let o = obj;
  for (const k of keys.slice(0, -1)) o = o[k] ??= {};
  o[keys[keys.length - 1]] = value;
}

function getPointer(obj, pointer) {
  return pointer.split('/').slice(1).reduce((o, k) => (o === undefined || o === null ? undefined : o[k]), obj);
}

/** The mission file from the form, or throws FieldError[] for what cannot even be sent. */
export function buildMission() {
  const body = {};
  const errors = [];
  const kind = $('m-kind').value;
  for (const [id, [pointer, type]] of Object.entries(FIELDS)) {
    const section = pointer.split('/')[1];
    if (KIND_ONLY[section] && KIND_ONLY[section] !== kind) continue;
    const raw = $(id).value.trim();
    try {
      let value;
      switch (type) {
        case 'list':
          // An empty list is sent as []: the server says what it needs, next to the field.
          value = parseNumberList(raw, pointer);
          break;
        case 'points':
          value = parsePoints(raw, pointer);
          break;
        case 'point':
          if (raw === '') continue;
          value = parseNumberList(raw, pointer);
          if (value.length !== 2) throw new FieldError(pointer, 'expected “x, y”');
          break;
        case 'number':
        case 'int':
          if (raw === '') continue;
          value = Number(raw);
          if (!Number.isFinite(value)) throw new FieldError(pointer, `“${raw}” is not a number`);
          break;
        case 'select':
          if (raw === '') continue;
          value = raw;
          break;
        default:
          value = raw;
      }
      setPointer(body, pointer, value);
    } catch (e) {
      if (e instanceof FieldError) errors.push({ field: e.pointer, message: e.message });
      else throw e;
    }
  }
  return { body, errors };
}

/** Fills the form from a mission file. */
export function fillForm(mission) {
  clearErrors();
  for (const [id, [pointer, type]] of Object.entries(FIELDS)) {
    const v = getPointer(mission, pointer);
    const input = $(id);
    if (v === undefined || v === null) {
      input.value = type === 'select' && id === 'm-kind' ? 'turns' : '';
      continue;
    }
    if (type === 'list') input.value = v.join(', ');
    else if (type === 'points') input.value = v.map((p) => p.join(', ')).join('\n');
    else if (type === 'point') input.value = v.join(', ');
    else input.value = String(v);
  }
  applyKind();
  onFormChanged();
}

function applyKind() {
  const kind = $('m-kind').value;
  for (const fs of document.querySelectorAll('#mission-form fieldset[data-kind]')) fs.hidden = fs.dataset.kind !== kind;
}

// ---------------------------------------------------------------- errors next to fields

function clearErrors() {
  for (const e of document.querySelectorAll('#mission-form .field-error')) e.remove();
  for (const i of document.querySelectorAll('#mission-form [aria-invalid]')) {
    i.removeAttribute('aria-invalid');
    i.removeAttribute('aria-describedby');
  }
  $('m-general-errors').replaceChildren();
}

/** The form field a JSON pointer belongs to: the longest field pointer that is a prefix of it,
 *  segment by segment (/turn_array/speeds_mps/2 → the speeds field). */
function fieldFor(pointer) {
  let best = null;
  for (const f of document.querySelectorAll('#mission-form .field[data-pointer]')) {
    const p = f.dataset.pointer;
    if ((pointer === p || pointer.startsWith(`${p}/`)) && (!best || p.length > best.dataset.pointer.length)) best = f;
  }
  return best;
}

/** The words an operator reads for a field: its label without the typing hint in brackets
 *  ("Speeds (m/s, comma separated)" -> "Speeds (m/s)"). */
function fieldLabel(field) {
  const label = field.querySelector('label')?.textContent ?? field.dataset.pointer;
  return label.replace(/,\s*(comma separated|magnitudes)\)/, ')').replace(/\s*\(x east, y north in m; one "x, y" a line\)/, '').trim();
}

/** What the part of a pointer below its field names: "item 2" of a list, "vertex 3, y" of a
 *  polygon, "x" of a point. */
function partName(type, rest) {
  const seg = rest.split('/').filter((p) => p !== '');
  if (seg.length === 0) return '';
  const idx = seg.map((p) => (/^\d+$/.test(p) ? Number(p) : p));
  const coord = (k) => (k === 0 ? 'x' : k === 1 ? 'y' : `value ${k + 1}`);
  if (type === 'points') return typeof idx[0] === 'number' ? `vertex ${idx[0] + 1}${typeof idx[1] === 'number' ? `, ${coord(idx[1])}` : ''}` : seg.join(' ');
  if (type === 'point') return typeof idx[0] === 'number' ? coord(idx[0]) : seg.join(' ');
  return typeof idx[0] === 'number' ? `item ${idx[0] + 1}` : seg.join(' ').replaceAll('_', ' ');
}

const TYPE_OF = Object.fromEntries(Object.values(FIELDS).map(([pointer, type]) => [pointer, type]));

/** "Speeds (m/s) — item 1" for /turn_array/speeds_mps/0; a pointer with no field reads as its
 *  words ("/operating_region" -> "operating region"). */
export function pointerLabel(pointer) {
  const field = fieldFor(pointer || '');
  if (!field) return (pointer || '').split('/').filter(Boolean).join(' › ').replaceAll('_', ' ');
  const p = field.dataset.pointer;
  const part = partName(TYPE_OF[p], pointer.slice(p.length));
  return part ? `${fieldLabel(field)} — ${part}` : fieldLabel(field);
}

export function showErrors(errors) {
  clearErrors();
  const general = [];
  let first = null;
  for (const [i, e] of errors.entries()) {
    const field = fieldFor(e.field || '');
    if (!field || field.closest('fieldset')?.hidden) {
      general.push(e);
      continue;
    }
    const input = field.querySelector('input, select, textarea');
    // The field's label, not the JSON pointer (kept in data-field and the title for the file's writer).
    const msg = el('p', { class: 'field-error', id: `m-err-${i}`, 'data-field': e.field, title: e.field, text: `${pointerLabel(e.field)}: ${e.message}` });
    field.append(msg);
    input.setAttribute('aria-invalid', 'true');
    input.setAttribute('aria-describedby', [input.getAttribute('aria-describedby'), msg.id].filter(Boolean).join(' '));
    first ??= input;
  }
  if (general.length) {
    $('m-general-errors').replaceChildren(
      el('ul', {}, ...general.map((e) => el('li', { title: e.field || undefined, text: e.field ? `${pointerLabel(e.field)}: ${e.message}` : e.message }))),
    );
  }
  first?.focus();
}

// ---------------------------------------------------------------- region preview

let previewTimer = null;

function onFormChanged() {
  const { body } = buildMission();
  $('m-json').value = JSON.stringify(body, null, 2);
  clearTimeout(previewTimer);
  previewTimer = setTimeout(drawPreview, 150);
}

function drawPreview() {
  const plot = $('mission-region-plot');
  if (plot.closest('.view').hidden) return;
  let poly;
  let ret;
  try {
    poly = parsePoints($('m-polygon').value, '');
    ret = $('m-return').value.trim() ? parseNumberList($('m-return').value, '') : null;
  } catch {
    showEmpty(plot, 'The vertices are not “x, y” lines yet.');
    return;
  }
  if (poly.length < 3) {
    showEmpty(plot, 'A region needs at least 3 vertices.');
    return;
  }
  const buffer = Number($('m-buffer').value || 10);
  const r = ring(poly);
  const b = ring(insetPolygon(poly, buffer));
  draw(
    plot,
    [
      { type: 'scatter', mode: 'lines+markers', name: 'region', x: r.x, y: r.y, line: { color: C.black, width: 2 }, marker: { size: 7 } },
      { type: 'scatter', mode: 'lines', name: `buffer ${buffer} m`, x: b.x, y: b.y, line: { color: C.grey, dash: 'dash' } },
      { type: 'scatter', mode: 'markers', name: 'return point', x: ret ? [ret[0]] : [], y: ret ? [ret[1]] : [], marker: { symbol: 'x-thin-open', size: 12, color: C.vermillion, line: { width: 2 } } },
    ],
    { ...baseLayout(), ...equalAxes(), showlegend: true },
  );
}

// ---------------------------------------------------------------- start and control

async function startMission(ev) {
  ev.preventDefault();
  const result = $('m-result');
  const { body, errors } = buildMission();
  if (errors.length) {
    showErrors(errors);
    setStatus(result, 'Fix the fields marked.', 'error');
    return;
  }
  if (!state.vehicleId) {
    setStatus(result, 'No vehicle is connected.', 'error');
    return;
  }
  clearErrors();
  setStatus(result, 'Starting…');
  starting = true;
  updateStart();
  try {
    const r = await postJson(`/vehicles/${encodeURIComponent(state.vehicleId)}/missions`, body);
    setStatus(result, `Mission ${r.id} started.`, 'ok');
    await loadMission(r.id).catch(() => {});
    await refreshMissions().catch(() => {});
  } catch (e) {
    if (e instanceof ApiError && e.status === 422 && e.errors.length) {
      showErrors(e.errors);
      setStatus(result, `The mission is not valid (${e.errors.length} problem${e.errors.length > 1 ? 's' : ''}).`, 'error');
    } else if (e instanceof ApiError && e.status === 422) {
      showErrors([{ field: '', message: e.message }]);
      setStatus(result, 'The mission is not valid.', 'error');
    } else {
      setStatus(result, e.message, 'error');
    }
  } finally {
    starting = false;
    updateStart();
  }
}

let starting = false;

/** The mission holding the vehicle (running or paused), if any: another cannot start. */
function busyMission() {
  const m = state.mission;
  if (m && ['running', 'paused', 'created'].includes(m.status)) return m;
  return null;
}

/** Start is off while a mission holds the vehicle (the server would answer 409), and says why. */
function updateStart() {
  const b = $('m-start');
  const busy = busyMission();
  b.disabled = starting || Boolean(busy);
  // The vehicle it starts on: the one shown (on a fleet, chosen in the vehicle list).
  const label = state.vehicleId ? `Start mission on ${state.vehicleId}` : 'Start mission';
  if (b.textContent !== label) b.textContent = label;
  b.title = busy
    ? `Mission ${busy.id} “${busy.name}” is ${busy.status}: one mission at a time. Abort it, or wait for it to end.`
    : starting
      ? 'Starting…'
      : `Send the mission to ${state.vehicleId ?? 'the vehicle'}`;
}

function targetMission() {
  const id = Number($('m-target').value);
  return state.missions.find((m) => m.id === id) ?? null;
}

async function command(action) {
  const m = targetMission();
  const out = $('m-control-result');
  if (!m) return;
  setStatus(out, `${action}…`);
  try {
    await postJson(`/missions/${m.id}/${action}`);
    setStatus(out, `Mission ${m.id}: ${action} sent.`, 'ok');
    await refreshMissions();
    if (state.mission?.id === m.id || action === 'resume') await loadMission(m.id);
  } catch (e) {
    setStatus(out, `Mission ${m.id}: ${e.message}`, 'error');
  }
}

function renderControl() {
  const sel = $('m-target');
  const keep = Number(sel.value) || state.mission?.id;
  const missions = [...state.missions].sort((a, b) => b.id - a.id);
  const fleet = state.fleet.size > 1; // whose each mission is, when it can be another's
  sel.replaceChildren(...missions.map((m) => el('option', { value: m.id, text: `${m.id} · ${m.name} · ${m.status}${fleet && m.vehicle_id ? ` · ${m.vehicle_id}` : ''}` })));
  if (missions.length === 0) sel.append(el('option', { value: '', text: 'none' }));
  const live = state.mission?.live ? state.mission.id : null;
  sel.value = String(live ?? keep ?? missions[0]?.id ?? '');
  updateButtons();
  const cur = state.mission;
  $('m-current').textContent = cur
    ? `Current: mission ${cur.id} “${cur.name}”, ${cur.status}${cur.status_reason ? ` (${cur.status_reason})` : ''}.`
    : 'No mission.';
  fillTable(
    $('missions-table'),
    [
      { key: 'id', label: 'id' },
      { key: 'name', label: 'name' },
      { key: 'status', label: 'status' },
      // Every time says its clock: the start in local wall-clock time, the duration by the wall
      // clock and by the station clock (on the simulator it runs ×realtime factor, so a mission
      // of 5 minutes can last 50 on it).
      { key: 'started_s', label: 'started (local time)', get: (m) => timeCell(m.started_s, m) },
      { key: 'wall_s', label: 'duration (wall clock)', get: (m) => (m.live ? '–' : fmtElapsed(missionWallElapsed(m))) },
      { key: 'ended_s', label: 'duration (station clock)', get: (m) => (typeof m.started_s === 'number' && typeof m.ended_s === 'number' ? fmtElapsed(m.ended_s - m.started_s) : '–') },
      { key: 'status_reason', label: 'reason', get: (m) => el('span', { class: 'reason', text: m.status_reason ?? '–' }) },
    ],
    missions,
    { rowClass: (m) => (m.id === cur?.id ? 'current' : undefined) },
  );
}

/** A station-clock time of a mission: local wall time when this session ran it or the station
 *  stored it (a start or end), else its created_utc; UTC, the station clock and the session's
 *  note on hover. */
function timeCell(t, m) {
  if (typeof t !== 'number') return '–';
  const l = timeLabel(t, m);
  const created = (m.created_utc ?? '').replace('T', ' ').replace(/(\.\d+)?Z$/, ' UTC');
  return el('time', { title: l.title, text: l.wall ? l.text : created ? `created ${created}` : l.text });
}

function updateButtons() {
  updateStart();
  const m = targetMission();
  const s = m?.status;
  $('m-pause').disabled = s !== 'running';
  $('m-resume').disabled = !(s === 'paused' || s === 'interrupted');
  $('m-abort').disabled = !(s === 'running' || s === 'paused' || s === 'interrupted');
  // A confirmation asked for a mission that has since ended (or another one picked) goes away.
  if ($('m-abort').disabled || ($('m-abort-confirm').dataset.mission ?? '') !== String(m?.id ?? '')) hideAbortConfirm();
}

/** Abort cannot be undone: the first click only asks, inline, naming the mission and what is lost. */
function askAbort() {
  const m = targetMission();
  if (!m) return;
  const box = $('m-abort-confirm');
  box.dataset.mission = String(m.id);
  const left = (m.cells ?? []).reduce((n, c) => n + Math.max(0, (c.planned ?? 1) - (c.ok ?? 0)), 0);
  $('m-abort-question').textContent = `Abort mission ${m.id} “${m.name}”? The vehicle stops at once and ${left} planned turn${left === 1 ? '' : 's'} will not run. This cannot be undone (Pause can).`;
  box.hidden = false;
  $('m-abort-no').focus();
}

function hideAbortConfirm() {
  const box = $('m-abort-confirm');
  box.hidden = true;
  delete box.dataset.mission;
}

export function initMission() {
  const exampleSel = $('m-example');
  for (const name of Object.keys(EXAMPLES)) exampleSel.append(el('option', { value: name, text: name }));
  $('m-load-example').addEventListener('click', () => {
    const ex = EXAMPLES[exampleSel.value];
    if (ex) fillForm(structuredClone(ex));
  });
  $('m-kind').addEventListener('change', applyKind);
  const form = $('mission-form');
  // The JSON box mirrors the form; typing in it must not be overwritten by the mirror.
  const changed = (ev) => {
    if (ev.target.id !== 'm-json') onFormChanged();
  };
  form.addEventListener('input', changed);
  form.addEventListener('change', changed);
  form.addEventListener('submit', startMission);
  $('m-from-json').addEventListener('click', () => {
    try {
      fillForm(JSON.parse($('m-json').value));
    } catch (e) {
      showErrors([{ field: '', message: `the JSON does not parse: ${e.message}` }]);
    }
  });
  $('m-target').addEventListener('change', updateButtons);
  $('m-pause').addEventListener('click', () => command('pause'));
  $('m-resume').addEventListener('click', () => command('resume'));
  $('m-abort').addEventListener('click', askAbort);
  $('m-abort-no').addEventListener('click', hideAbortConfirm);
  $('m-abort-yes').addEventListener('click', () => {
    hideAbortConfirm();
    command('abort');
  });
  on('missions', renderControl);
  on('mission', renderControl);
  on('vehicle', updateStart);
  applyKind();
  onFormChanged();
}

export function showMission(visible) {
  if (visible) {
    renderControl();
    drawPreview();
  }
}

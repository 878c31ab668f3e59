// The event log as an operator reads it: a phrase for each kind instead of
// its internal name, one entry per happening, an entry per finished turn with its advance and
// transfer, and a severity shown by a coloured border, a word and an icon, not a character alone.
//
// One happening reaches the page several ways: the stored event (REST) and the stream's `status`
// message of the same event; a mission's stop as its own event (`aborted`) and as the state change
// (`mission_aborted`), followed by the mission leaving the vehicle (`mission_detached`); the turn
// under way aborted by that same stop. They are merged here, where the log is drawn: state.events
// stays what the station sent.

import { state, on, emit } from './state.js';
import { el, num } from './format.js';
import { timeLabel } from './clock.js';
import { alarmEntries } from './alarms.js';
import { plannedTurns, turnLabel } from './turnlabel.js';
import { namesVehicle } from './fleet.js';

/** kind → what an operator reads. A kind not listed reads as its name with spaces. */
export const PHRASES = {
  link: 'Navigation link',
  condition_set_timeout: 'Conditions not set in time',
  containment: 'Containment: heading back inside',
  turning_back: 'Turning back before the buffer',
  turn_rejected: 'Turn rejected',
  turn_given_up: 'Cell given up',
  turn_aborted: 'Turn aborted',
  turn_finished: 'Turn finished',
  excitation: 'Excitation started',
  returning: 'Returning to the return point',
  pause: 'Mission paused',
  resume: 'Mission resumed',
  halted: 'Mission halted',
  aborted: 'Mission aborted',
  interrupted: 'Mission interrupted',
  mission_attached: 'Mission started on the vehicle',
  mission_detached: 'Mission left the vehicle',
  mission_running: 'Mission running',
  mission_paused: 'Mission paused',
  mission_interrupted: 'Mission interrupted',
  mission_aborted: 'Mission aborted',
  mission_halted: 'Mission halted',
  mission_done: 'Mission done',
  station: 'Station',
  alarm: 'Alarm',
  vehicle_command: 'Vehicle command',
  arrived: 'Arrived at the point',
  vehicle_joined: 'Vehicle joined',
  vehicle_left: 'Vehicle left',
  collision_watch: 'Collision watch',
};

export function phrase(kind, message = '') {
  if (kind === 'link') return /^navigation is back/.test(message) ? 'Navigation back' : 'Navigation lost';
  return PHRASES[kind] ?? String(kind ?? 'event').replaceAll('_', ' ');
}

// The state change a stop or pause is also logged as: one happening, two kinds.
const SAME_AS = { mission_aborted: 'aborted', mission_paused: 'pause', mission_halted: 'halted', mission_interrupted: 'interrupted', mission_running: 'resume' };
const STOPS = new Set(['aborted', 'pause', 'halted', 'interrupted']);
const ENDS = new Set(['aborted', 'halted', 'interrupted', 'mission_done']);
// Severity as shown: the station names info and warning; a stop the operator did not ask for is an
// error, an alarm is an alarm, a finished turn is good news.
const ERRORS = new Set(['halted', 'interrupted']);

export function severityOf(e) {
  if (e.level === 'alarm' || e.kind === 'alarm') return 'alarm';
  if (e.kind === 'turn_finished') return 'ok';
  if (ERRORS.has(SAME_AS[e.kind] ?? e.kind)) return 'error';
  return e.level === 'warning' ? 'warning' : 'info';
}

const SEVERITY_WORD = { info: 'info', ok: 'ok', warning: 'warning', error: 'error', alarm: 'ALARM' };
const SEVERITY_ICON = { info: 'ℹ', ok: '✓', warning: '⚠', error: '✖', alarm: '‼' };

// ---------------------------------------------------------------- finished turns

let turnMission = null; // the mission whose turns are listed
const turns = new Map(); // id (or 't<time>') -> {t, speed, dheading, advance, transfer}
let lastTurnSeen = null;
let lastTurnList = null;

function addTurn(key, r) {
  turns.set(key, r);
}

function turnsFromMission(m) {
  if (!m || !Array.isArray(m.turn_list) || m.turn_list === lastTurnList) return false;
  lastTurnList = m.turn_list;
  if (turnMission !== m.id) {
    turns.clear();
    turnMission = m.id;
  }
  for (const r of m.turn_list) {
    if (r.status !== 'ok') continue; // aborted and rejected turns are logged as events already
    turns.delete(`t${r.end_time_s}`);
    addTurn(r.id, { t: r.end_time_s, speed: r.speed_mps, dheading: r.goal_dheading_deg, advance: r.advance_m, transfer: r.transfer_m, logged: true });
  }
  return true;
}

function turnFromStream() {
  const d = state.lastTurn;
  if (!d || d === lastTurnSeen) return false;
  lastTurnSeen = d;
  if (d.status !== 'ok' || (d.mission_id && state.mission && d.mission_id !== state.mission.id)) return false;
  if (turnMission !== d.mission_id) {
    turns.clear();
    turnMission = d.mission_id;
  }
  const key = d.id ?? `t${d.t}`;
  if (turns.has(key)) return false;
  addTurn(key, { t: d.t, speed: d.speed_mps, dheading: d.goal_dheading_deg, advance: d.advance_m, transfer: d.transfer_m });
  return true;
}

const signed = (d) => (typeof d === 'number' ? `${d > 0 ? '+' : ''}${d.toFixed(0)}°` : '–');

function turnEntries() {
  if (state.mission && turnMission !== state.mission.id) return [];
  const list = [...turns.values()].sort((a, b) => (a.t ?? 0) - (b.t ?? 0));
  const planned = plannedTurns(state.mission?.cells);
  return list.map((r, i) => ({
    kind: 'turn_finished',
    level: 'info',
    t: r.t,
    logged: r.logged,
    message: `${turnLabel(i + 1, planned)}: ${num(r.speed, 2)} m/s, Δψ ${signed(r.dheading)}, advance ${num(r.advance, 1)} m, transfer ${num(r.transfer, 1)} m`,
  }));
}

// ---------------------------------------------------------------- one entry per happening

const sameT = (a, b, tol) => typeof a === 'number' && typeof b === 'number' && Math.abs(a - b) <= tol;

// Entries of one kind within this long of the first whose words differ only in their numbers are
// one (the station rate-limits a kind's status messages per second, not its stored events).
const NEAR_S = 1;
const shape = (message) => String(message ?? '').replace(/[-+]?\d+(\.\d+)?/g, '#');
const sameShape = (a, b) => shape(a) === shape(b);

/** The log as shown, oldest first: [{kind, canon, t, message, level, severity, count, notes}]. */
export function logEntries(events = state.events, extra = [...turnEntries(), ...alarmEntries()]) {
  // Events in arrival order; finished turns placed by time among them.
  const all = [...events.map((e, i) => ({ ...e, order: i })), ...extra.map((e) => ({ ...e, order: Infinity }))];
  let lastT = -Infinity;
  for (const e of all) {
    if (e.order !== Infinity) lastT = typeof e.t === 'number' ? e.t : lastT;
    e.sortT = typeof e.t === 'number' ? e.t : lastT;
  }
  all.sort((a, b) => a.sortT - b.sortT || (a.order === Infinity) - (b.order === Infinity) || a.order - b.order);

  const seen = new Set();
  const out = [];
  for (const e of all) {
    const canon = SAME_AS[e.kind] ?? e.kind;
    const key = `${canon}|${typeof e.t === 'number' ? e.t.toFixed(1) : ''}|${e.message ?? ''}`;
    if (seen.has(key)) continue; // the same event again (stream and REST; event and state change)
    seen.add(key);
    // The mission leaving the vehicle right after its end, the turn under way aborted by a stop:
    // parts of the happening already listed.
    if (e.kind === 'mission_detached' && out.some((p) => ENDS.has(p.canon) && sameT(p.t, e.t, 1))) continue;
    if (canon === 'turn_aborted' && out.some((p) => STOPS.has(p.canon) && sameT(p.t, e.t, 0.05))) continue;
    if (STOPS.has(canon)) {
      const turn = out.findLastIndex((p) => p.canon === 'turn_aborted' && sameT(p.t, e.t, 0.05));
      if (turn >= 0) out.splice(turn, 1); // the stop is listed instead, the turn as its note
    }
    const prev = out.at(-1);
    const entry = {
      kind: e.kind,
      canon,
      t: e.t,
      logged: Boolean(e.logged),
      message: e.message ?? '',
      level: e.level ?? 'info',
      vehicle: e.vehicle_id ?? null, // the vehicle the event is about; none: the station's
      severity: severityOf(e),
      suppressed: e.suppressed ?? 0,
      count: 1,
      variants: [], // the other words of near-identical entries merged into this one
      firstT: e.t, // its first one's time: "near" is within NEAR_S of it
    };
    // Identical repeats (a link flapping, a condition timeout per attempt), and near-identical
    // ones within the same second (containment entered again 0.4 m further on: the same words,
    // other numbers): one line, ×n, the first one's words.
    const near = prev && prev.canon === canon && sameShape(prev.message, entry.message) && sameT(prev.firstT, entry.t, NEAR_S);
    if (prev && prev.canon === canon && (prev.message === entry.message || near)) {
      prev.count++;
      prev.t = entry.t ?? prev.t;
      prev.vehicle ??= entry.vehicle;
      prev.suppressed += entry.suppressed;
      if (entry.message !== prev.message && !prev.variants.includes(entry.message)) prev.variants.push(entry.message);
      continue;
    }
    out.push(entry);
  }
  return out;
}

// ---------------------------------------------------------------- drawing

/** Whether an entry is of vehicle `vid`: its own, the station's (no vehicle), or a collision watch
 *  naming it (the message names both vehicles, vehicle_id only one). */
export function aboutVehicle(e, vid) {
  if (!e.vehicle || !vid || e.vehicle === vid) return true;
  return (e.kind === 'collision_watch' || e.message?.startsWith('Collision watch:')) && namesVehicle(e.message, vid);
}

let onlySelected = false; // the operator's filter: the selected vehicle's events only

/** Fills the event log list, newest first (live.js calls it when the log changes). */
export function renderEventLog(list) {
  let entries = logEntries().slice(-200).reverse();
  if (onlySelected) entries = entries.filter((e) => aboutVehicle(e, state.vehicleId));
  if (entries.length === 0) {
    list.replaceChildren(el('li', { class: 'muted', text: onlySelected ? `No events of ${state.vehicleId ?? 'this vehicle'} yet.` : 'No events yet.' }));
    return;
  }
  list.replaceChildren(
    ...entries.map((e) => {
      // Times of the mission shown (its elapsed time on hover, and no wall time for a mission of
      // an earlier session); the station's own notes (a restart, an alarm) are of this session.
      const time = timeLabel(e.t, e.kind === 'station' || e.kind === 'alarm' ? null : state.mission);
      return el(
        'li',
        { class: `lvl-${e.level} sev-${e.severity}`, 'data-kind': e.kind, 'data-count': e.count, 'data-vehicle': e.vehicle ?? undefined },
        el('span', { class: 'sev', title: `severity: ${SEVERITY_WORD[e.severity]}` }, el('span', { 'aria-hidden': 'true', text: `${SEVERITY_ICON[e.severity]} ` }), SEVERITY_WORD[e.severity]),
        el('time', { class: 't', title: time.title, text: time.text }),
        e.vehicle ? el('span', { class: 'veh', title: `about vehicle ${e.vehicle}`, text: e.vehicle }) : null,
        el('span', { class: 'kind', title: e.kind, text: phrase(e.kind, e.message) }),
        e.count > 1 ? el('span', { class: 'count', title: `${e.count} times`, text: `×${e.count}` }) : null,
        el('span', { class: 'msg', title: e.variants.length ? ['also:', ...e.variants.slice(0, 5)].join('\n') : undefined, text: e.message + (e.suppressed ? ` (+${e.suppressed} suppressed)` : '') }),
      );
    }),
  );
}

export function initEventLog() {
  on('mission', (m) => {
    if (turnsFromMission(m)) emit('events', state.events);
  });
  on('turn', () => {
    if (turnFromStream()) emit('events', state.events);
  });
  on('clock', () => emit('events', state.events));
  const filter = document.getElementById('event-filter');
  const filterName = () => {
    document.getElementById('event-filter-vehicle').textContent = state.vehicleId ?? 'this vehicle';
  };
  filter?.addEventListener('change', () => {
    onlySelected = filter.checked;
    emit('events', state.events);
  });
  on('vehicle', filterName);
  on('vehicle-changed', () => {
    turns.clear(); // the finished turns listed were the other vehicle's mission's
    turnMission = null;
    lastTurnList = null;
  });
}

// Keeps `state` in step with the station: reads everything over REST at start and after every
// reconnection (catch-up), then applies the stream's messages. A new session_id in the hello means
// the server restarted: the live track is cleared because the vehicle's history no longer joins.

import { state, emit, addEvent } from './state.js';
import { getJson, getAllItems } from './api.js';
import { wrap360 } from './format.js';
import { simplify } from './decimate.js';
import { mergeStoredRows } from './timeseries.js';
import { setClockMapping } from './clock.js';
import { retireTrack } from './tracks.js';
import { frameParams } from './frame.js';

const STALE_AFTER_MS = 2000;
const MAX_RECORDED_TURNS = 60; // drawn as history in Live; older ones are in the CKT view

let stream = null;
let catchingUp = null;
let lastCatchUpMs = -Infinity;
let helloSeen = false;
let ckTimer = null;

export function attachStream(s) {
  stream = s;
}

/** Re-reads the station over REST. Concurrent calls share one run. */
export function catchUp() {
  if (!catchingUp) {
    catchingUp = doCatchUp().finally(() => {
      catchingUp = null;
      lastCatchUpMs = performance.now();
    });
  }
  return catchingUp;
}

async function doCatchUp() {
  const health = await getJson('/health');
  setClockMapping(health); // this session's station clock -> wall clock (clock.js)
  emit('clock', health);
  state.serverVersion = health.server_version;
  if (state.sessionId === null) state.sessionId = health.session_id;
  // Where the grid lies on the earth (null without --datum); a new object only when it changed,
  // so views that cache a grid by it keep theirs.
  const d = health.datum ?? null;
  if (JSON.stringify(d) !== JSON.stringify(state.datum)) state.datum = d;
  state.vehicleId = health.vehicle_id ?? null;
  const vid = state.vehicleId;
  if (vid) {
    const v = await getJson(`/vehicles/${encodeURIComponent(vid)}`);
    state.vehicle = v;
    // A ?test=1 hook feeding nav replaces the vehicle's, from REST as from the stream.
    if (v.nav && !state.testFeed) applyNav({ ...v.nav, link: v.link, vehicle_id: vid }, false);
    state.helm = {
      vehicle_id: vid,
      mode: v.helm_mode,
      desired_heading_deg: v.desired_heading_deg,
      desired_speed_mps: v.desired_speed_mps,
      mission_id: v.mission_id,
    };
  }
  emit('vehicle', state.vehicle);
  emit('helm', state.helm);
  // The table's grid before the mission: a turn under way is judged (deviation.js) by AVK where
  // the table covers its speed, and asked before the grid was read it was judged by the
  // instantaneous ray instead (a page loaded mid-turn showed 10–12 m for a moment).
  await Promise.all([refreshMissions(), refreshTurnCount().then(refreshCktSummary), refreshModels(), vid ? refreshCurrent(vid) : null]);
  const mine = state.missions.filter((m) => !vid || m.vehicle_id === vid);
  const currentId = state.helm?.mission_id ?? (mine.length ? Math.max(...mine.map((m) => m.id)) : null);
  if (currentId) await loadMission(currentId, { force: true });
  else {
    state.mission = null;
    state.events = [];
    emit('mission', null);
    emit('events', state.events);
  }
  emit('synced');
}

export async function refreshMissions() {
  state.missions = await getJson('/missions');
  emit('missions', state.missions);
}

export async function refreshModels() {
  if (!state.vehicleId) return;
  state.models = await getJson(`/vehicles/${encodeURIComponent(state.vehicleId)}/models`);
  emit('models', state.models);
}

/** Whether the vehicle has stored ok turns: without them the CKT and the comparison are 404s, so
 *  the views say "no turns yet" instead of asking. */
export async function refreshTurnCount() {
  if (!state.vehicleId) return;
  const page = await getJson('/turns', { status: 'ok', limit: 1 });
  state.okTurns = page.items.length;
}

/** The CKT's grid (speed range, heading changes): predictions are only asked inside it. */
export async function refreshCktSummary() {
  if (!state.vehicleId || state.okTurns === 0) {
    state.ckt = null;
    return;
  }
  try {
    state.ckt = await getJson(`/vehicles/${encodeURIComponent(state.vehicleId)}/ckt`);
  } catch {
    state.ckt = null;
  }
  emit('ckt', state.ckt);
}

/** Loads a mission's detail; a mission not seen before also brings its event log and the raw
 *  paths of its recorded turns (the history drawn under the live track). */
export async function loadMission(id, { force = false } = {}) {
  const seqBefore = missionMessages;
  const turnsBefore = turnMessages;
  const m = await getJson(`/missions/${id}`);
  const isNew = force || state.mission?.id !== id;
  if (!isNew && missionMessages !== seqBefore && state.mission) {
    // A stream message overtook this answer: its progress is the newer one.
    m.cells = state.mission.cells;
    m.status = state.mission.status;
    m.helm_mode = state.mission.helm_mode;
    m.live = state.mission.live;
  }
  // Another mission than the one drawn: its track starts afresh, the last one is kept faded.
  if (state.mission && state.mission.id !== id && !state.testFeed) retireTrack(state.mission.id, m.started_s);
  state.mission = m;
  emit('mission', m);
  setTurnMarks(m);
  adoptRunningTurn(m, turnMessages === turnsBefore);
  if (isNew) {
    await Promise.all([loadEvents(id), loadRecordedTurns(id), loadTrackHistory(id)]);
    if (!state.shownTurn) await adoptLastTurn(m);
  }
}

const markLabel = (speed, dheading) => `${dheading > 0 ? '+' : ''}${Math.round(dheading)}° @ ${speed} m/s`;

/** The turn starts the time series marks: the mission's stored turns, the one under way, and any
 *  the stream started since (kept when the report does not list them yet). */
function setTurnMarks(m) {
  const marks = (m.turn_list ?? []).map((r) => ({ t: r.start_time_s, label: markLabel(r.speed_mps, r.goal_dheading_deg) }));
  if (m.running_turn) marks.push({ t: m.running_turn.t_s, label: markLabel(m.running_turn.speed_mps, m.running_turn.dheading_deg) });
  const newest = marks.length ? Math.max(...marks.map((k) => k.t)) : -Infinity;
  const sameMission = state.turnMarksMission === m.id;
  if (sameMission) for (const k of state.turnMarks) if (k.t > newest + 1e-6) marks.push(k);
  state.turnMarks = marks.sort((a, b) => a.t - b.t);
  state.turnMarksMission = m.id;
  emit('series');
}

function turnFromServer(missionId, rt) {
  return {
    missionId,
    speed: rt.speed_mps,
    dheading: rt.dheading_deg,
    goalHeading: rt.goal_heading_deg,
    attempt: rt.attempt,
    start: { t: rt.t_s, x: rt.x_m, y: rt.y_m, heading: rt.heading_deg },
    predictions: {},
  };
}

/** The turn under way as the server has it: a page opened or reloaded mid-turn, or one
 *  that missed the stream's `started`, draws it from the report. `current`: no turn message came
 *  on the stream while the report was asked for, so the report is the newer word; then a report
 *  without a running turn ends the one the page still shows as running (its `finished` was lost:
 *  a stream closed under load, a gap), instead of leaving the panel on "Turn running" with a
 *  deviation that grows past the prediction's end. A report that a stream message overtook never
 *  clears a turn the stream started: it may predate it. */
function adoptRunningTurn(m, current = false) {
  const rt = m.running_turn;
  if (!rt) {
    if (current && state.turn && state.turn.missionId === m.id) endTurnByReport(m, endedRow(m, state.turn));
    // A turn a mission message ended without saying how: the report tells it now.
    else if (state.shownTurn?.outcome === 'ended' && state.shownTurn.missionId === m.id) settleEnded(m, state.shownTurn);
    return;
  }
  if (state.turn && state.turn.missionId === m.id && Math.abs((state.turn.start?.t ?? NaN) - rt.t_s) < 1e-6) return;
  state.turn = turnFromServer(m.id, rt);
  state.shownTurn = state.turn;
  emit('turn', state.turn);
  fetchPredictions(state.turn);
}

/** The stored row of a turn that started at turn.start.t (the report's turn_list), or null. */
function endedRow(m, turn) {
  return (m.turn_list ?? []).find((r) => Math.abs(r.start_time_s - (turn.start?.t ?? NaN)) < 0.5) ?? null;
}

/** The turn under way has ended: it stays drawn (faded) with its predictions until the next one
 *  starts, so the operator can see how they compared with what the vehicle did, and the panel
 *  leaves "Turn running". */
function endTurn({ event, endT, storedId }) {
  const turn = state.turn;
  if (turn) {
    turn.ended = true;
    turn.endT = endT;
    turn.outcome = event;
    turn.storedId = storedId;
  }
  state.turn = null;
  emit('turn', null);
}

/** The turn under way ended as a report says (its stored row, when the report has it yet). */
function endTurnByReport(m, row) {
  if (row) state.lastTurn = lastTurnOf(row, m.id);
  endTurn({ event: row ? state.lastTurn.event : 'ended', endT: row?.end_time_s ?? state.nav?.t_s ?? null, storedId: row?.id ?? null });
}

/** An ended turn whose outcome the page did not hear: how it ended, from the report's row. */
function settleEnded(m, turn) {
  const row = endedRow(m, turn);
  if (!row) return;
  state.lastTurn = lastTurnOf(row, m.id);
  turn.outcome = state.lastTurn.event;
  turn.endT = row.end_time_s;
  turn.storedId = row.id;
  emit('turn', state.turn);
}

/** A stored turn (a report's turn_list row) as the stream's event of its end. */
function lastTurnOf(row, missionId) {
  return {
    event: row.status === 'ok' ? 'finished' : row.status,
    status: row.status,
    reason: row.reason,
    id: row.id,
    mission_id: missionId,
    speed_mps: row.speed_mps,
    goal_dheading_deg: row.goal_dheading_deg,
    advance_m: row.advance_m,
    transfer_m: row.transfer_m,
    condition_set_time_s: row.condition_set_time_s,
    t: row.end_time_s,
  };
}

/** The mission's last stored turn, drawn (faded, with its predictions) as the last turn when the
 *  page did not see it happen: its start pose is the first sample of its record. */
async function adoptLastTurn(m) {
  const row = m.turn_list?.at(-1);
  if (!row) return;
  state.lastTurn = lastTurnOf(row, m.id);
  let first;
  try {
    first = (await getJson(`/turns/${row.id}`)).raw?.samples?.[0];
  } catch (e) {
    console.warn('the last turn could not be read', e.message);
  }
  if (state.shownTurn || !first) {
    emit('turn', state.turn);
    return;
  }
  const [t, x, y, heading] = first;
  state.shownTurn = {
    ...turnFromServer(m.id, {
      t_s: t,
      x_m: x,
      y_m: y,
      heading_deg: heading,
      speed_mps: row.speed_mps,
      dheading_deg: row.goal_dheading_deg,
      goal_heading_deg: wrap360(heading + row.goal_dheading_deg),
      attempt: null,
    }),
    ended: true,
    endT: row.end_time_s,
    outcome: state.lastTurn.event,
    storedId: row.id,
  };
  emit('turn', state.turn);
  fetchPredictions(state.shownTurn);
}

const NAV_PAGE = 5000;
// How far the stored track of a mission has been read into the live track: the next catch-up
// reads only what was recorded since. Tied to the track's epoch: a cleared track (server restart)
// is read again from the start.
let navCursor = { missionId: null, after: 0, epoch: -1, rows: 0 };

/** The mission's stored track (GET /missions/{id}/nav, page by page) merged into the bounded live
 *  track, so a page opened mid-mission shows the track so far. Samples are merged by time with
 *  what the stream has already delivered; the track is rebuilt once, which restarts its
 *  decimation (TrackDecimator sees the new epoch) like any other clear. */
async function loadTrackHistory(id) {
  const tr = state.track;
  const resume = navCursor.missionId === id && navCursor.epoch === tr.epoch;
  let after = resume ? navCursor.after : 0;
  const t = [];
  const x = [];
  const y = [];
  const stored = [];
  let lastCount = 0;
  let lastAfter = after;
  for (;;) {
    const page = await getJson(`/missions/${id}/nav`, { limit: NAV_PAGE, after: after || undefined });
    for (const r of page.items) {
      t.push(r.t_s);
      x.push(r.x_m);
      y.push(r.y_m);
      stored.push(r);
    }
    lastCount = page.items.length;
    lastAfter = after;
    if (page.next === null || page.next === undefined) break;
    after = page.next;
  }
  // The last page is not full, so it has no cursor: the same page asked with a limit of exactly
  // its row count is full, and its `next` is the rowid to continue after at the next catch-up.
  if (lastCount > 0) {
    const again = await getJson(`/missions/${id}/nav`, { limit: lastCount, after: lastAfter || undefined });
    after = again.next ?? lastAfter;
  }
  const rows = (resume ? navCursor.rows : 0) + t.length;
  if (t.length && !state.testFeed) {
    mergeIntoTrack(t, x, y); // a test hook owns the track then
    mergeStoredRows(state.series, stored);
    emit('series');
  }
  navCursor = { missionId: id, after, epoch: tr.epoch, rows };
  emit('nav-history', { missionId: id, rows });
}

function mergeIntoTrack(ht, hx, hy) {
  const tr = state.track;
  const order = ht.map((_, i) => i).sort((a, b) => ht[a] - ht[b] || a - b);
  const live = { t: [], x: [], y: [] };
  for (let k = 0; k < tr.length; k++) {
    const j = (tr.start + k) % tr.capacity;
    live.t.push(tr.t[j]);
    live.x.push(tr.x[j]);
    live.y.push(tr.y[j]);
  }
  tr.clear();
  let a = 0;
  let lastT = -Infinity;
  let lastX = NaN;
  let lastY = NaN;
  const push = (t, x, y) => {
    if (Math.abs(t - lastT) < 1e-9) return; // the same sample from the stream and from the store
    // As applyNav: a sample that repeats the last position does not take a slot.
    if (Math.abs(lastX - x) < 0.01 && Math.abs(lastY - y) < 0.01 && t - lastT < 5) return;
    tr.push(t, x, y);
    lastT = t;
    lastX = x;
    lastY = y;
  };
  for (const i of order) {
    while (a < live.t.length && live.t[a] <= ht[i]) {
      push(live.t[a], live.x[a], live.y[a]);
      a++;
    }
    push(ht[i], hx[i], hy[i]);
  }
  for (; a < live.t.length; a++) push(live.t[a], live.x[a], live.y[a]);
}

/** The level the station gives an event kind (its vocabulary, from the hello); info for a kind
 *  it does not name (an old log's, or before the first hello). */
function levelOf(kind) {
  return state.eventLevels.get(kind) ?? 'info';
}

async function loadEvents(id) {
  const items = await getAllItems(`/missions/${id}/events`, {}, 2000);
  // `logged`: the level is ours, not the server's, so a later vocabulary may correct it.
  state.events = items.map((e) => ({
    t: e.t_s,
    kind: e.kind,
    level: levelOf(e.kind),
    message: e.message,
    logged: true,
  }));
  emit('events', state.events);
}

/** Takes the vocabulary of a hello. The first read of the event log comes before the first hello,
 *  so the levels given then are given again. */
function applyVocabulary(hello) {
  if (!Array.isArray(hello.event_kinds)) return; // an older server: every event stays info
  state.eventLevels = new Map(
    hello.event_kinds.map((e) => [e.kind, e.severity === 'warning' ? 'warning' : 'info']),
  );
  let changed = false;
  for (const e of state.events) {
    if (!e.logged) continue;
    const level = levelOf(e.kind);
    if (level !== e.level) {
      e.level = level;
      changed = true;
    }
  }
  if (changed) emit('events', state.events);
}

async function loadRecordedTurns(id) {
  const items = await getAllItems('/turns', { mission: id }, 5000);
  const recent = items.slice(-MAX_RECORDED_TURNS);
  const paths = [];
  // A few requests at a time: the station serves missions, we must not crowd it.
  for (let i = 0; i < recent.length; i += 4) {
    const batch = await Promise.all(recent.slice(i, i + 4).map((t) => fetchRawPath(t.id)));
    paths.push(...batch.filter(Boolean));
  }
  state.recordedTurns = paths;
  emit('recorded-turns', paths);
}

async function fetchRawPath(turnId) {
  try {
    const t = await getJson(`/turns/${turnId}`);
    const s = t.raw?.samples ?? [];
    const xs = s.map((p) => p[1]);
    const ys = s.map((p) => p[2]);
    // Simplified like the live track (within 0.1 m): 60 turns stay cheap to redraw at 10 Hz.
    const keep = simplify(xs, ys, 0, xs.length - 1, 0.1);
    return { id: t.id, status: t.status, x: keep.map((i) => xs[i]), y: keep.map((i) => ys[i]) };
  } catch {
    return null;
  }
}

// ---------------------------------------------------------------- stream messages

export function onHello(hello) {
  const restarted = state.sessionId !== null && hello.session_id !== state.sessionId;
  state.sessionId = hello.session_id;
  state.serverVersion = hello.server_version;
  applyVocabulary(hello);
  if (restarted) {
    state.track.clear();
    state.series.clear();
    state.turn = null;
    state.shownTurn = null;
    state.recordedTurns = [];
    addEvent({ t: null, kind: 'station', level: 'warning', message: 'the server restarted: state re-read' });
    emit('restart');
  }
  // Whatever happened while we were away (turns, events) is read back over REST; the very first
  // hello follows the start-up read closely, so that one is not repeated.
  const justRead = !helloSeen && performance.now() - lastCatchUpMs < 3000;
  helloSeen = true;
  if (restarted || !justRead) catchUp().catch((e) => console.warn('catch-up failed', e));
  // Even then, a turn may have started or ended between that read and the subscription: the
  // running mission's report is read again, so the turn panel follows the server, not a guess.
  else if (state.mission?.live) loadMission(state.mission.id).catch((e) => console.warn('mission re-read failed', e));
  updateLink();
}

export function onStreamClose() {
  updateLink();
}

export function onGap() {
  // An event was lost (a slow tab): the REST state is the truth.
  catchUp().catch((e) => console.warn('catch-up failed', e));
}

export function onMessage(msg) {
  const d = msg.data;
  switch (msg.topic) {
    case 'nav':
      if (!state.testFeed) applyNav(d, true); // a ?test=1 hook is feeding nav instead
      break;
    case 'helm':
      applyHelm(d);
      break;
    case 'mission':
      applyMission(d, msg.t);
      break;
    case 'turn':
      applyTurn(d, msg.t);
      break;
    case 'current':
      applyCurrent(d);
      break;
    case 'status':
      addEvent({ t: msg.t, kind: d.kind, level: d.level, message: d.message, suppressed: d.suppressed_before });
      break;
    default:
  }
}

/** A nav sample: the readout and the bounded live track. Samples that repeat the last position
 *  are not stored: an idle vehicle must not push the track out. */
export function applyNav(d, live) {
  if (state.vehicleId && d.vehicle_id && d.vehicle_id !== state.vehicleId) return;
  state.nav = d;
  if (live) state.navWallMs = performance.now();
  if (Number.isFinite(d.x_m) && Number.isFinite(d.y_m)) {
    const last = state.track.last();
    const still = last && Math.abs(last.x - d.x_m) < 0.01 && Math.abs(last.y - d.y_m) < 0.01 && d.t_s - last.t < 5;
    if (!still) state.track.push(d.t_s, d.x_m, d.y_m);
  }
  if (Number.isFinite(d.t_s) && Number.isFinite(d.heading_deg)) {
    state.series.push(d.t_s, d.heading_deg, state.helm?.desired_heading_deg, d.speed_mps, state.helm?.desired_speed_mps);
  }
  emit('nav', d);
}

/** The current the vehicle is in: drawn as an arrow in Live; when it is told apart from
 *  still water the turn's predictions are asked with its drift (current=live). */
function applyCurrent(d) {
  if (state.vehicleId && d?.vehicle_id && d.vehicle_id !== state.vehicleId) return;
  state.current = d?.estimated === false ? null : d; // GET /current before any estimate
  emit('current', d);
}

/** The query parameters of Live's predictions: the operator's choice of current and speed
 *  reference (frame.js); none by default, so the station answers over ground wherever it knows
 *  the current. */
export function predictionParams() {
  return frameParams(state.predictionFrame);
}

/** The operator changed the frame: the shown turn's predictions are asked again with it (the
 *  running turn's deviation follows at its next poll). */
export function setPredictionFrame(choice) {
  state.predictionFrame = { ...state.predictionFrame, ...choice };
  const turn = state.shownTurn;
  if (turn) {
    turn.predictions = {};
    emit('predictions', turn);
    fetchPredictions(turn);
  }
}

async function refreshCurrent(vid) {
  try {
    applyCurrent(await getJson(`/vehicles/${encodeURIComponent(vid)}/current`));
  } catch (e) {
    console.warn('no current estimate', e.message);
  }
}

function applyHelm(d) {
  const prevMode = state.helm?.mode;
  state.helm = d;
  if (d.mode === 'CONDITIONING' && prevMode !== 'CONDITIONING') state.conditioningSinceT = state.nav?.t_s ?? null;
  if (d.mode !== 'CONDITIONING') state.conditioningSinceT = null;
  emit('helm', d);
}

let missionMessages = 0; // stream mission messages so far (to order them against REST answers)

function applyMission(d, t) {
  missionMessages++;
  if (!state.mission || state.mission.id !== d.mission_id) {
    // A mission started elsewhere (another tab, the CLI over the API): read it whole.
    loadMission(d.mission_id).then(refreshMissions).catch((e) => console.warn(e));
    return;
  }
  const stateChanged = state.mission.status !== d.state;
  // The runner marks the turn's cell running before it says `started` and clears it before it
  // says how the turn ended, and the stream keeps their order: a message with no running cell
  // while the page shows a turn of this mission running means its end was lost. The report has
  // how it ended.
  const cells = Array.isArray(d.cells) ? d.cells : [];
  if (state.turn && state.turn.missionId === d.mission_id && cells.length > 0 && !cells.some((c) => c.running)) {
    endTurn({ event: 'ended', endT: state.nav?.t_s ?? null, storedId: null });
    loadMission(d.mission_id).catch((e) => console.warn(e));
  }
  state.mission.cells = d.cells;
  state.mission.status = d.state;
  state.mission.helm_mode = d.helm_mode;
  state.mission.live = true;
  emit('mission', state.mission);
  if (stateChanged) {
    // Ended, paused, resumed: the REST detail has the reason and the end time.
    loadMission(d.mission_id).then(refreshMissions).catch((e) => console.warn(e));
  }
}

let turnMessages = 0; // stream turn messages so far (a report asked before one is older than it)

function applyTurn(d, t) {
  turnMessages++;
  if (d.event === 'started') {
    // The event is the report's running_turn: the signed Δψ (the side the runner chose; a half
    // turn's goal lies both ways) and the sample at which the new heading was commanded.
    state.turn = turnFromServer(d.mission_id, d);
    state.shownTurn = state.turn;
    if (state.turnMarksMission === d.mission_id) {
      state.turnMarks.push({ t: state.turn.start.t, label: markLabel(d.speed_mps, d.dheading_deg) });
      emit('series');
    }
    emit('turn', state.turn);
    fetchPredictions(state.turn);
    return;
  }
  state.lastTurn = { ...d, t };
  endTurn({ event: d.event, endT: state.nav?.t_s ?? null, storedId: d.id ?? null });
  if (d.id) {
    fetchRawPath(d.id).then((p) => {
      if (!p) return;
      state.recordedTurns.push(p);
      if (state.recordedTurns.length > MAX_RECORDED_TURNS) state.recordedTurns.shift();
      emit('recorded-turns', state.recordedTurns);
    });
  }
  // The mission's detail has the time-to-set-conditions statistics: read it again.
  if (state.mission?.id === d.mission_id) loadMission(d.mission_id).catch((e) => console.warn(e));
  if (d.status === 'ok') {
    state.okTurns++;
    // The CKT is rebuilt at most once a second on the server; ask a little later, once.
    clearTimeout(ckTimer);
    ckTimer = setTimeout(async () => {
      await refreshCktSummary();
      emit('turns-changed');
      // The turn just drawn may have started before the table covered its speed: complete its
      // predictions now, for the comparison with what the vehicle did.
      if (state.shownTurn?.ended) fetchPredictions(state.shownTurn);
    }, 1500);
  }
}

/** Whether the vehicle's CKT (as last read) answers at this speed: AVK is asked only then, so
 *  nothing answers 4xx routinely. */
export function cktCovers(speed) {
  const r = state.ckt?.speed_range_mps;
  return Boolean(r) && speed >= r[0] - 1e-9 && speed <= r[1] + 1e-9;
}

/** Whether two turns (or a turn and a table cell) are of one cell: the same commanded speed and
 *  heading change on either side, within the station's own tolerances (GET /turns). */
export function sameCell(speedA, dheadingA, speedB, dheadingB) {
  return Math.abs(speedA - speedB) < 0.05 && Math.abs(Math.abs(dheadingA) - Math.abs(dheadingB)) < 0.5;
}

/** The turns the vehicle's table (as last read) holds in the cell of a turn of this speed and
 *  heading change (either side); 0 when it has no such cell. */
function cellTurns(speed, dheading) {
  return state.ckt?.cells?.find((c) => sameCell(c.speed_mps, c.dheading_deg, speed, dheading))?.n_turns ?? 0;
}

/** The predictions a turn can be drawn against, asked only where one answers (a CKT covering the
 *  speed, a stored model), so nothing answers 4xx routinely. A stored turn is drawn only against
 *  what never saw it (`heldOut`, asked with without_turn or without_mission): a table that keeps
 *  a turn in its cell once `heldOut.cellTurns` of them are left out (the turn itself; Replay: its
 *  mission's), a model not trained on `heldOut.missionId`. */
export function answerableMethods(speed, dheading, heldOut = null) {
  const methods = ['instantaneous'];
  if (cktCovers(speed) && (!heldOut || cellTurns(speed, dheading) > heldOut.cellTurns)) methods.push('avk');
  if (heldOut ? state.models.some((m) => !(m.training_missions ?? []).includes(heldOut.missionId)) : state.models.length > 0) methods.push('model');
  return methods;
}

/** AVK, model and instantaneous predictions placed at the turn's start pose, where they answer
 *  (answerableMethods); a stored turn (ended) only against a table and model that never saw it. */
async function fetchPredictions(turn) {
  if (!turn.start || !state.vehicleId) return;
  // Turns finished since the table was last read may cover this speed now: read it again first.
  if (!cktCovers(turn.speed) && state.okTurns > 0) await refreshCktSummary();
  const heldOut = turn.storedId ? { cellTurns: 1, missionId: turn.missionId } : null;
  const methods = answerableMethods(turn.speed, turn.dheading, heldOut).filter((m) => !turn.predictions[m]);
  const params = predictionParams();
  const asked = state.predictionFrame;
  await Promise.all(
    methods.map(async (method) => {
      try {
        const p = await getJson(`/vehicles/${encodeURIComponent(state.vehicleId)}/predict`, {
          speed: turn.speed,
          dheading: turn.dheading,
          method,
          x: turn.start.x,
          y: turn.start.y,
          heading: turn.start.heading,
          ...params,
          // A stored turn is drawn against predictions that never saw it: asked for after it
          // ended (a table that had not covered its speed, a page opened later), the table and
          // model must leave it out.
          ...(turn.storedId && method !== 'instantaneous' ? { without_turn: turn.storedId } : {}),
        });
        if (state.shownTurn !== turn) return; // a newer turn is drawn now
        if (state.predictionFrame !== asked) return; // asked again in another frame meanwhile
        turn.predictions[method] = p;
        emit('predictions', turn);
      } catch (e) {
        console.warn(`no ${method} prediction`, e.message);
      }
    }),
  );
}

// ---------------------------------------------------------------- link state

/** LIVE: stream open and a fresh nav sample from a vehicle whose link is LIVE. STALE: the stream is
 *  open but navigation is old or the vehicle's link is not LIVE. DISCONNECTED: no stream. */
export function updateLink() {
  let link = 'DISCONNECTED';
  if (stream?.open) {
    const fresh = performance.now() - state.navWallMs < STALE_AFTER_MS;
    link = fresh && (state.nav?.link ?? 'LIVE') === 'LIVE' ? 'LIVE' : 'STALE';
  }
  if (link !== state.link) {
    state.link = link;
    emit('link', link);
  }
}

// Keeps `state` in step with the station: reads everything over REST at start and after every
// reconnection (catch-up), then applies the stream's messages. A new session_id in the hello means
// the server restarted: the live track is cleared because the vehicle's history no longer joins.
import { state, emit, addEvent } from './state.js';
import { getJson, getAllItems } from './api.js';
import { simplify } from './decimate.js';
import { setClockMapping } from './clock.js';
import { retireTrack } from './tracks.js';
import { refreshCktSummary, fetchPredictions } from './predictions.js';
import { loadTrackHistory } from './trackhistory.js';
import { noteFleetNav, noteFleetHelm, noteVehicles, noteFleetIds, fleetIdsOf, helmOf, wantedVehicle, setWantedVehicle } from './fleet.js';
import { markLabel, setTurnMarks, turnFromServer, adoptRunningTurn, endTurn, adoptLastTurn } from './turnstate.js';

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

// A fleet's telemetry at full rate is 100 nav and 100 helm messages a second per vehicle at x10:
// more than a page can handle beside its drawing. With several vehicles the page asks for 20 a
// second per vehicle (every 50 ms of wall clock, smoother than the eye follows); one vehicle is
// followed at full rate, as before.
const FLEET_TELEMETRY_HZ = 20;
function limitFleetTelemetry() {
  stream?.setTelemetryRate(state.fleetIds.length > 1 ? FLEET_TELEMETRY_HZ : null);
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
  noteFleetIds(fleetIdsOf(health));
  limitFleetTelemetry();
  let list = await getJson('/vehicles').catch(() => []);
  if (!Array.isArray(list)) list = [];
  noteVehicles(list);
  const vid = chooseVehicle(health, list);
  if (vid !== state.vehicleId) {
    if (state.vehicleId !== null) forgetVehicle();
    state.vehicleId = vid;
    emit('vehicle-changed', vid);
  }
  state.vehicle = null;
  state.helm = null;
  if (vid) {
    const v = list.find((r) => r.id === vid) ?? (await getJson(`/vehicles/${encodeURIComponent(vid)}`));
    state.vehicle = v;
    // A ?test=1 hook feeding nav replaces the vehicle's, from REST as from the stream.
    if (v.nav && !state.testFeed) applyNav({ ...v.nav, link: v.link, vehicle_id: vid }, false);
    if ('helm_mode' in v) state.helm = helmOf(v); // a vehicle known from stored missions only has none
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

/** The vehicle shown: the one chosen (in the address) when the station knows it, else the
 *  station's own (an older station's only one), else its first. */
function chooseVehicle(health, list) {
  const wanted = wantedVehicle();
  if (wanted && (state.fleetIds.includes(wanted) || list.some((r) => r.id === wanted))) return wanted;
  return health.vehicle_id ?? state.fleetIds[0] ?? null;
}

/** What the page holds of the vehicle shown, dropped when another is chosen: its track, turns,
 *  mission, table and models are read for the new one as at a fresh load. */
function forgetVehicle() {
  state.track.clear();
  state.series.clear();
  state.nav = null;
  state.navWallMs = 0;
  state.helm = null;
  state.vehicle = null;
  state.turn = null;
  state.shownTurn = null;
  state.lastTurn = null;
  state.ongoing = null;
  state.current = null;
  state.ckt = null;
  state.okTurns = 0;
  state.models = [];
  state.mission = null;
  state.events = [];
  state.recordedTurns = [];
  state.previousTrack = null;
  state.turnMarks = [];
  state.turnMarksMission = null;
  state.conditioningSinceT = null;
}

/** Shows another vehicle: the address keeps the choice, and the page reads the station again as
 *  a fresh load with that vehicle would (a catch-up under way finishes first). */
export async function selectVehicle(id) {
  if (!id || id === state.vehicleId) return;
  setWantedVehicle(id);
  if (catchingUp) await catchingUp.catch(() => {});
  if (!state.fleet.has(id) || id === state.vehicleId) return; // gone meanwhile, or shown already
  forgetVehicle();
  state.vehicleId = id;
  emit('vehicle-changed', id); // the views that keep what they drew of a vehicle start afresh
  emit('recorded-turns', state.recordedTurns);
  emit('previous-track', null);
  emit('mission', null);
  emit('events', state.events);
  await catchUp();
}

/** The station's vehicles read again (GET /health, GET /vehicles), the vehicle shown kept. */
export async function refreshFleet() {
  const health = await getJson('/health');
  noteFleetIds(fleetIdsOf(health));
  limitFleetTelemetry();
  const list = await getJson('/vehicles');
  if (Array.isArray(list)) noteVehicles(list);
}

/** Whether a mission (by id) is another vehicle's than the one shown, as far as the missions read
 *  say; a mission not read yet is taken as this one's on a station of one vehicle. */
function othersMission(missionId) {
  if (state.mission?.id === missionId) return false;
  const m = state.missions.find((q) => q.id === missionId);
  if (m) return Boolean(state.vehicleId && m.vehicle_id && m.vehicle_id !== state.vehicleId);
  return state.fleetIds.length > 1 ? null : false; // null: not known yet
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
  // GET /turns is the station's, every vehicle's: on a fleet the vehicle's own are its missions'.
  if (state.okTurns > 0 && state.fleet.size > 1) {
    const missions = await getJson('/missions');
    state.okTurns = missions.filter((m) => m.vehicle_id === state.vehicleId).reduce((n, m) => n + (m.turns?.ok ?? 0), 0);
  }
}


/** Loads a mission's detail; a mission not seen before also brings its event log and the raw
 *  paths of its recorded turns (the history drawn under the live track). */
export async function loadMission(id, { force = false } = {}) {
  const seqBefore = missionMessages;
  const turnsBefore = turnMessages;
  const vid = state.vehicleId;
  const m = await getJson(`/missions/${id}`);
  if (state.vehicleId !== vid) return; // another vehicle chosen meanwhile: its own are read
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
    await Promise.all([loadEvents(id, m.vehicle_id), loadRecordedTurns(id), loadTrackHistory(id)]);
    if (state.vehicleId !== vid) return;
    if (!state.shownTurn) await adoptLastTurn(m);
  }
}

/** The level the station gives an event kind (its vocabulary, from the hello); info for a kind
 *  it does not name (an old log's, or before the first hello). */
function levelOf(kind) {
  return state.eventLevels.get(kind) ?? 'info';
}

async function loadEvents(id, vehicleId) {
  const vid = state.vehicleId;
  const items = await getAllItems(`/missions/${id}/events`, {}, 2000);
  if (state.vehicleId !== vid) return;
  // `logged`: the level is ours, not the server's, so a later vocabulary may correct it. The
  // mission's events are of its vehicle.
  state.events = items.map((e) => ({
    t: e.t_s,
    kind: e.kind,
    level: levelOf(e.kind),
    message: e.message,
    logged: true,
    vehicle_id: e.vehicle_id ?? vehicleId ?? null,
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
  const vid = state.vehicleId;
  const items = await getAllItems('/turns', { mission: id }, 5000);
  const recent = items.slice(-MAX_RECORDED_TURNS);
  const paths = [];
  // A few requests at a time: the station serves missions, we must not crowd it.
  for (let i = 0; i < recent.length; i += 4) {
    const batch = await Promise.all(recent.slice(i, i + 4).map((t) => fetchRawPath(t.id)));
    paths.push(...batch.filter(Boolean));
  }
  if (state.vehicleId !== vid) return;
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
      // A ?test=1 hook may be feeding the shown vehicle's nav instead; the others' go on.
      if (!state.testFeed) applyNav(d, true);
      else if (d?.vehicle_id && d.vehicle_id !== state.vehicleId) noteFleetNav(d);
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
      // vehicle_id: the vehicle the event is about (none: the station's).
      addEvent({ t: msg.t, kind: d.kind, level: d.level, message: d.message, suppressed: d.suppressed_before, vehicle_id: d.vehicle_id ?? null });
      // A vehicle come or gone: the station's list of them is read again.
      if (d.kind === 'vehicle_joined' || d.kind === 'vehicle_left') refreshFleet().catch((e) => console.warn('fleet re-read failed', e));
      break;
    default:
  }
}

/** A nav sample: the readout and the bounded live track. Samples that repeat the last position
 *  are not stored: an idle vehicle must not push the track out. */
export function applyNav(d, live) {
  noteFleetNav(d); // every vehicle's, for the fleet list and the map
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

async function refreshCurrent(vid) {
  try {
    applyCurrent(await getJson(`/vehicles/${encodeURIComponent(vid)}/current`));
  } catch (e) {
    console.warn('no current estimate', e.message);
  }
}

function applyHelm(d) {
  noteFleetHelm(d);
  if (state.vehicleId && d.vehicle_id && d.vehicle_id !== state.vehicleId) return;
  const prevMode = state.helm?.mode;
  state.helm = d;
  if (d.mode === 'CONDITIONING' && prevMode !== 'CONDITIONING') state.conditioningSinceT = state.nav?.t_s ?? null;
  if (d.mode !== 'CONDITIONING') state.conditioningSinceT = null;
  emit('helm', d);
}

/** A vehicle command's answer (the vehicle after it, commands.js): its entry in the fleet, and the
 *  helm when it is the vehicle shown; the stream's next helm message says the same. */
export function applyVehicleAnswer(v) {
  if (!v?.id) return;
  noteVehicles([v]);
  if (v.id === state.vehicleId && 'helm_mode' in v) applyHelm(helmOf(v));
}

let missionMessages = 0; // stream mission messages so far (to order them against REST answers)
const asking = new Set(); // missions whose vehicle is being read (GET /missions)

function applyMission(d, t) {
  const others = othersMission(d.mission_id);
  if (others) return; // another vehicle's: its progress is not shown
  missionMessages++;
  if (others === null) {
    // Of a vehicle not known yet (a mission just started on a fleet): the list says whose.
    if (asking.has(d.mission_id)) return;
    asking.add(d.mission_id);
    refreshMissions()
      .then(() => (othersMission(d.mission_id) ? null : loadMission(d.mission_id)))
      .catch((e) => console.warn(e))
      .finally(() => asking.delete(d.mission_id));
    return;
  }
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
  // Another vehicle's turn, or one of a mission not read yet on a fleet (its report, read when
  // its mission message comes, has the turn under way).
  if (othersMission(d.mission_id) !== false) return;
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

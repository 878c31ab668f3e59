// Hooks for the browser tests, installed only with ?test=1 in the address: they load a long
// synthetic track and feed navigation through the same path as the stream, so the test measures
// what a real 2-hour mission at 10 Hz costs the page.

import { state, on } from './state.js';
import { applyNav, onMessage, catchUp } from './sync.js';
import { retireTrack } from './tracks.js';
import { renderNow, renderTimes, seriesTimes } from './live.js';
import { deviationLog, latLonText } from './livepanels.js';
import { replayState, seek as replaySeek, poseAt as replayPoseAt } from './replay.js';
import { logEntries } from './eventlog.js';
import { alarmsState } from './alarms.js';
import { clockMapping } from './clock.js';
import { fleetList } from './fleet.js';

/** A lawn-mower survey at 1 m/s sampled at 10 Hz: long straight legs joined by half circles,
 *  which is what two hours of turn collection looks like to the renderer. */
function pathPoint(i) {
  const t = i * 0.1; // s
  const legM = 300;
  const turnR = 10;
  const period = legM + Math.PI * turnR; // metres per leg + turn
  const s = t * 1.0; // metres travelled
  const k = Math.floor(s / period);
  const u = s - k * period;
  const dir = k % 2 === 0 ? 1 : -1;
  const y0 = (k * 2 * turnR) % 2000;
  if (u < legM) {
    const x = dir > 0 ? -150 + u : 150 - u;
    return { x, y: -1000 + y0, heading: dir > 0 ? 90 : 270 };
  }
  const a = (u - legM) / turnR; // radians round the half circle
  const cx = dir > 0 ? 150 : -150;
  const x = cx + dir * turnR * Math.sin(a);
  const y = -1000 + y0 + turnR - turnR * Math.cos(a);
  return { x, y, heading: (dir > 0 ? 90 : 270) - dir * (a * 180) / Math.PI };
}

let next = 0;
let seed = 1;
// Deterministic GNSS-like jitter (a few centimetres), so the track is not perfectly straight
// lines that any renderer would simplify away.
function jitter() {
  seed = (seed * 1103515245 + 12345) % 2147483648;
  return (seed / 2147483648 - 0.5) * 2 * NOISE_M;
}
const NOISE_M = 0.05;

function feed(i) {
  const p = pathPoint(i);
  applyNav({ vehicle_id: state.vehicleId, link: 'LIVE', t_s: i * 0.1, x_m: p.x + jitter(), y_m: p.y + jitter(), heading_deg: ((p.heading % 360) + 360) % 360, speed_mps: 1.0 }, true);
}

let turnRun = null; // the synthetic turn of startTurn: {t0, speed, dheading, k, start}
// The mission a synthetic turn belongs to unless a test names one: none the station has, so that
// what the station says of its own missions (a report without a running turn, a mission message
// without a running cell) never ends it; the page follows the station's turn state.
const SYNTHETIC_MISSION = -1;

let navHistory = null; // the last stored-track read: {missionId, rows}

export function installTestHooks() {
  on('nav-history', (h) => {
    navHistory = { ...h, trackLength: state.track.length };
  });
  window.avkTest = {
    /** Replaces the live track with n synthetic samples; stream nav is ignored from now on. */
    loadTrack(n) {
      state.testFeed = true;
      state.track.clear();
      state.series.clear();
      for (let i = 0; i < n - 1; i++) {
        const p = pathPoint(i);
        state.track.push(i * 0.1, p.x + jitter(), p.y + jitter());
        // The time series too (it keeps the newest hour), so a benchmark draws a full window.
        if (n - 1 - i <= state.series.capacity) state.series.push(i * 0.1, ((p.heading % 360) + 360) % 360, 90, 1.0, 1.0);
      }
      next = n - 1;
      feed(next++); // the last one through applyNav, so the readout and the plot update
      renderNow();
      return state.track.length;
    },
    /** One more nav sample (the test calls it at 10 Hz). */
    pushNav() {
      feed(next++);
      return state.track.length;
    },
    /** A stream message as the server sends it (topic, data), through the page's own handler. */
    streamMessage(topic, data) {
      onMessage({ topic, seq: 0, t: state.nav?.t_s ?? 0, data });
    },
    /** The vehicle's newest nav sample again through the stream's path, with `extra` fields (a
     *  frontseat report): the track does not move. */
    streamNav(extra) {
      onMessage({ topic: 'nav', seq: 0, t: state.nav?.t_s ?? 0, data: { ...state.nav, vehicle_id: state.vehicleId, ...extra } });
    },
    /** A synthetic turn through the stream's path: steady north from (0, -72) to (0, -70), then
     *  the turn's start event at t0 = 1000 s (sim time), of `missionId` (by default of no mission
     *  the station has); stream nav is ignored from now on. */
    startTurn(dheading = 90, speed = 1.0, missionId = SYNTHETIC_MISSION) {
      state.testFeed = true;
      state.track.clear();
      const t0 = 1000;
      for (let i = 0; i <= 20; i++) {
        applyNav({ vehicle_id: state.vehicleId, link: 'LIVE', t_s: t0 - 2 + i * 0.1, x_m: 0, y_m: -72 + i * 0.1 * speed, heading_deg: 0, speed_mps: speed }, true);
      }
      const goal = ((dheading % 360) + 360) % 360;
      // As the server sends it: the report's running_turn (signed Δψ, the start sample).
      const start = { t_s: t0, x_m: 0, y_m: -72 + 2 * speed, heading_deg: 0 };
      onMessage({ topic: 'turn', seq: 0, t: t0, data: { event: 'started', mission_id: missionId, ...start, speed_mps: speed, dheading_deg: dheading, goal_heading_deg: goal, attempt: 1, speed_after_mps: null } });
      turnRun = { t0, speed, dheading, k: 0, start };
      return state.turn !== null;
    },
    /** One nav sample dt_s into the synthetic turn, at its start position moved by (dx, dy) m, on
     *  its start heading: the vehicle a little off where the turn began. */
    turnNavAt(dtS, dxM, dyM) {
      const r = turnRun;
      applyNav({ vehicle_id: state.vehicleId, link: 'LIVE', t_s: r.t0 + dtS, x_m: r.start.x_m + dxM, y_m: r.start.y_m + dyM, heading_deg: r.start.heading_deg, speed_mps: r.speed }, true);
      return state.nav.t_s;
    },
    /** The live track so far set aside as the previous mission's, as when a new mission starts
     *  (tracks.js); stream nav is ignored from now on. */
    retireTrack() {
      state.testFeed = true;
      retireTrack(state.mission?.id ?? 0);
      renderNow();
      return state.previousTrack?.x.length ?? 0;
    },
    /** The REST catch-up, as after a reconnection or a gap in an event topic. */
    catchUp: () => catchUp().then(() => true),
    /** The vehicle 0.5 s further into the synthetic turn: on the new heading at once (the
     *  instantaneous ray), 1 m to port of it. */
    turnNav() {
      const r = turnRun;
      r.k++;
      const t = r.k * 0.5;
      const h = (r.dheading * Math.PI) / 180;
      const along = r.speed * t;
      applyNav({ vehicle_id: state.vehicleId, link: 'LIVE', t_s: r.t0 + t, x_m: along * Math.sin(h) - Math.cos(h), y_m: -70 + along * Math.cos(h) + Math.sin(h), heading_deg: r.dheading, speed_mps: r.speed }, true);
      return t;
    },
    /** One nav sample where the vehicle is, with this heading; stream nav is ignored from now on. */
    setHeading(h) {
      state.testFeed = true;
      const n = state.nav ?? { t_s: 0, x_m: 0, y_m: 0 };
      applyNav({ vehicle_id: state.vehicleId, link: 'LIVE', t_s: (n.t_s ?? 0) + 0.1, x_m: n.x_m, y_m: n.y_m, heading_deg: h, speed_mps: 0 }, true);
      renderNow();
      return h;
    },
    /** A nav message of vehicle `id` (another of a fleet) through the stream's path: at (x, y) m
     *  on `heading`, at station time `t` (by default the shown vehicle's newest). */
    fleetNav(id, x, y, heading = 0, t = null) {
      const tS = t ?? state.nav?.t_s ?? 0;
      onMessage({ topic: 'nav', seq: 0, t: tS, data: { vehicle_id: id, link: 'LIVE', t_s: tS, x_m: x, y_m: y, heading_deg: heading, speed_mps: 1.0 } });
      return state.fleet.get(id)?.nav?.x_m ?? null;
    },
    /** A helm message of vehicle `id` through the stream's path: its mode and command. */
    fleetHelm(id, mode, command = null) {
      onMessage({ topic: 'helm', seq: 0, t: state.nav?.t_s ?? 0, data: { vehicle_id: id, mode, desired_heading_deg: null, desired_speed_mps: null, mission_id: null, command } });
      return state.fleet.get(id)?.helm?.mode ?? null;
    },
    /** The fleet as the page holds it, in the list's order. */
    fleet: () =>
      fleetList().map((v) => ({ id: v.id, link: v.link, mode: v.helm?.mode ?? null, command: v.helm?.command?.kind ?? null, x: v.nav?.x_m ?? null, y: v.nav?.y_m ?? null, trail: v.trail.x.length, selected: v.id === state.vehicleId })),
    /** The vehicles the Live map draws: the selected one and the others (x, y, label, heading). */
    liveVehicles: () => {
      const data = document.getElementById('live-plot')?.data ?? [];
      const others = data.find((t) => t.mode === 'markers+text' && String(t.name).startsWith('other vehicles ('));
      const own = data.find((t) => t.name === 'vehicle');
      return {
        selected: own?.x?.length ? { x: own.x[0], y: own.y[0], text: own.text?.[0] ?? null } : null,
        others: others ? others.x.map((x, i) => ({ x, y: others.y[i], text: others.text[i], angle: others.marker.angle[i] })) : [],
        trail: data.find((t) => t.name === 'other vehicles (trails)')?.x.filter((v) => Number.isFinite(v)).length ?? 0,
      };
    },
    /** Stops taking the stream's navigation (as a tab too loaded to keep up: the link goes STALE);
     *  releaseNav() takes it again. */
    holdNav() {
      state.testFeed = true;
      return true;
    },
    releaseNav() {
      state.testFeed = false;
      return true;
    },
    trackLength: () => state.track.length,
    /** The last read of a mission's stored track ({missionId, rows, trackLength} right after it). */
    navHistory: () => navHistory,
    /** Durations (ms) of the Live plot updates so far; `reset` empties the list. */
    renderTimes: (reset = false) => (reset ? renderTimes.splice(0) : renderTimes.slice()),
    /** Durations (ms) of the time series' redraws so far; `reset` empties the list. */
    seriesTimes: (reset = false) => (reset ? seriesTimes.splice(0) : seriesTimes.slice()),
    trackCapacity: () => state.track.capacity,
    /** The deviations from the prediction the Live view showed while turns ran. */
    deviations: () => deviationLog.slice(),
    state: () => ({ link: state.link, sessionId: state.sessionId, vehicleId: state.vehicleId, fleetIds: state.fleetIds.slice(), mission: state.mission?.id ?? null, okTurns: state.okTurns }),
    /** The event log as shown ({kind, level}) and the levels the hello gave each kind. */
    events: () => state.events.map((e) => ({ kind: e.kind, level: e.level })),
    eventLevels: () => Object.fromEntries(state.eventLevels),
    nav: () => state.nav,
    /** The latitude/longitude readout: as shown, as computed now for the newest nav, the datum. */
    latLon: () => ({ shown: document.getElementById('live-latlon').textContent, text: latLonText(state.nav), nav: state.nav, datum: state.datum }),
    /** The turn Live draws: the one under way (running) or the last one (ended). */
    shownTurn: () => {
      const s = state.shownTurn;
      return s ? { running: s === state.turn, start: s.start, dheading: s.dheading, speed: s.speed, goalHeading: s.goalHeading, predictions: Object.keys(s.predictions), ended: Boolean(s.ended) } : null;
    },
    /** The Live time series: samples held, the newest, the turn marks. */
    series: () => {
      const b = state.series;
      const k = b.length - 1;
      return { length: b.length, last: k >= 0 ? { t: b.at(k, 't'), heading: b.at(k, 'heading'), dheading: b.at(k, 'dheading'), speed: b.at(k, 'speed'), yawRate: b.at(k, 'yawRate') } : null, marks: state.turnMarks.slice() };
    },
    /** Replay: its state, a seek, and the interpolated pose it draws at a time. */
    replay: () => replayState(),
    replaySeek: (t) => {
      replaySeek(t);
      return replayState();
    },
    replayPose: (t) => replayPoseAt(t),
    /** The event log as drawn, oldest first: one entry per happening ({kind, severity, count, message}). */
    eventLog: () => logEntries().map((e) => ({ kind: e.kind, severity: e.severity, count: e.count, message: e.message, t: e.t, vehicle: e.vehicle })),
    /** Alarms: the unacknowledged ones, every kind raised, the beeps played, mute and audio state. */
    alarms: () => alarmsState(),
    /** The station clock -> wall clock mapping from GET /health ({utcMs, clockS, factor}). */
    clock: () => clockMapping(),
    /** The mission shown ({id, status, started_s, live}) and the previous mission's track. */
    mission: () => (state.mission ? { id: state.mission.id, status: state.mission.status, started_s: state.mission.started_s, live: state.mission.live } : null),
    previousTrack: () => (state.previousTrack ? { missionId: state.previousTrack.missionId, points: state.previousTrack.x.length } : null),
  };
}

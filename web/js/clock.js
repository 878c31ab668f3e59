// Time as an operator reads it. Every time the station sends (nav, events,
// turns, a mission's start) is in the station clock, which runs ×realtime_factor on the simulator;
// a new server session continues it from the last stored time. GET /health names the station clock
// beside the wall clock at one moment, so this session's times map to wall-clock time:
//   wall_ms = utc_ms − (clock_s − t_s) / realtime_factor × 1000.
// A mission from an earlier session ran before the station was down (and perhaps at another
// factor): the mapping does not hold for it. Its start and end are still wall-clock times (the
// station stores started_utc and ended_utc with it); other times of it are shown by elapsed time
// and station clock, with its created_utc for a mission stored before those were kept.

import { state } from './state.js';

let mapping = null; // {utcMs, clockS, factor, sessionStartS, offsetMs}

// How far a mission's mapped start may lie from its created_utc (stored some 20 ms before it
// started) and still be of this session. The station clock is exact (start + factor × steady time),
// and a new session continues it from the last stored time + 1 s, so an earlier session's mission
// maps off by the time the station was down: more than this unless it restarted within a second
// or so. A small share of the age allows for the wall clock being slewed meanwhile.
const SAME_SESSION_MS = 1500;
const DRIFT_SHARE = 0.001;

/** Takes the clock of a GET /health answer; an answer without one (an older server, no vehicle)
 *  leaves no mapping: times are then shown on the station clock. */
export function setClockMapping(health) {
  const ok = Number.isFinite(health?.utc_ms) && Number.isFinite(health?.clock_s);
  const factor = Number.isFinite(health?.realtime_factor) && health.realtime_factor > 0 ? health.realtime_factor : 1;
  const sessionStartS = Number.isFinite(health?.session_start_clock_s) ? health.session_start_clock_s : null;
  // The server's wall clock less the page's, as the answer arrived (off by the answer's trip, a
  // few ms): the server's now, for times that keep running while no navigation arrives.
  const offsetMs = ok ? health.utc_ms - Date.now() : 0;
  mapping = ok ? { utcMs: health.utc_ms, clockS: health.clock_s, factor, sessionStartS, offsetMs } : null;
}

/** The server's wall clock now (ms since 1970 UTC); null without a mapping. */
export function serverNowMs() {
  return mapping ? Date.now() + mapping.offsetMs : null;
}

export function clockMapping() {
  return mapping;
}

/** Wall-clock ms since 1970 UTC of station-clock time t_s in this session; null without a mapping. */
export function wallMs(t_s) {
  if (!mapping || typeof t_s !== 'number' || !Number.isFinite(t_s)) return null;
  return mapping.utcMs - ((mapping.clockS - t_s) / mapping.factor) * 1000;
}

/** Whether a mission ran in this server session, so its station-clock times map to wall time. */
export function inSession(m) {
  if (!m) return true; // station status (attach, detach) is always of this session
  if (m.live) return true;
  const created = Date.parse(m.created_utc ?? '');
  const start = wallMs(m.started_s);
  if (start === null || !Number.isFinite(created)) return false;
  // The server says where this session's clock began: exact. Without it (an older server), the
  // mission's created_utc against its mapped start decides.
  if (mapping.sessionStartS !== null) return m.started_s >= mapping.sessionStartS && m.started_s <= Math.max(mapping.clockS, state.nav?.t_s ?? -Infinity) + 1;
  // Started after this session's now (the newest station time seen): another clock.
  if (m.started_s > Math.max(mapping.clockS, state.nav?.t_s ?? -Infinity) + 1) return false;
  const age = Math.max(0, mapping.utcMs - created);
  return Math.abs(start - created) < SAME_SESSION_MS + DRIFT_SHARE * age;
}

const pad = (n, w = 2) => String(n).padStart(w, '0');

/** "14:03:27" local time (with the date when it is not today). */
export function fmtLocal(ms) {
  if (ms === null || !Number.isFinite(ms)) return '–';
  const d = new Date(ms);
  const time = `${pad(d.getHours())}:${pad(d.getMinutes())}:${pad(d.getSeconds())}`;
  const today = new Date();
  const sameDay = d.getFullYear() === today.getFullYear() && d.getMonth() === today.getMonth() && d.getDate() === today.getDate();
  return sameDay ? time : `${d.getFullYear()}-${pad(d.getMonth() + 1)}-${pad(d.getDate())} ${time}`;
}

/** "2025-05-01 12:03:27.4 UTC". */
export function fmtUtc(ms) {
  if (ms === null || !Number.isFinite(ms)) return '–';
  const d = new Date(ms);
  return `${d.getUTCFullYear()}-${pad(d.getUTCMonth() + 1)}-${pad(d.getUTCDate())} ${pad(d.getUTCHours())}:${pad(d.getUTCMinutes())}:${pad(d.getUTCSeconds())}.${Math.floor(d.getUTCMilliseconds() / 100)} UTC`;
}

/** Elapsed time "1:02:03" or "02:03" (minutes:seconds under an hour); '–' when unknown. */
export function fmtElapsed(s) {
  if (typeof s !== 'number' || !Number.isFinite(s) || s < 0) return '–';
  const whole = Math.floor(s);
  const h = Math.floor(whole / 3600);
  const m = Math.floor((whole % 3600) / 60);
  const sec = whole % 60;
  return h > 0 ? `${h}:${pad(m)}:${pad(sec)}` : `${pad(m)}:${pad(sec)}`;
}

export function fmtStation(t_s) {
  return typeof t_s === 'number' && Number.isFinite(t_s) ? `${t_s.toFixed(1)} s` : '–';
}

/** How a station-clock time of a mission (or of the station, mission null) is shown: `text` the
 *  local wall time (or T+elapsed for a mission of an earlier session), `title` the UTC time, the
 *  station clock and the mission's elapsed time, `wall` whether text is wall-clock time. */
export function timeLabel(t_s, mission = null) {
  if (typeof t_s !== 'number' || !Number.isFinite(t_s)) return { text: '', title: '', wall: false };
  const station = `station clock ${fmtStation(t_s)}`;
  const started = mission?.started_s;
  const since = typeof started === 'number' && t_s >= started ? `T+${fmtElapsed(t_s - started)}` : null;
  const ms = inSession(mission) ? wallMs(t_s) : null;
  if (ms !== null) {
    return { text: fmtLocal(ms), title: [fmtUtc(ms), station, since && `mission ${since}`].filter(Boolean).join(' · '), wall: true };
  }
  // Its start and end were stored in wall-clock time as they happened.
  const stored = t_s === mission?.started_s ? mission?.started_utc : t_s === mission?.ended_s ? mission?.ended_utc : null;
  const storedMs = Date.parse(stored ?? '');
  if (Number.isFinite(storedMs)) {
    return { text: fmtLocal(storedMs), title: [fmtUtc(storedMs), station, since && `mission ${since}`, 'stored with the mission (an earlier server session)'].filter(Boolean).join(' · '), wall: true };
  }
  const created = mission?.created_utc ? `mission created ${mission.created_utc}` : null;
  return {
    text: since ?? fmtStation(t_s),
    title: [station, created, 'wall-clock time unknown: an earlier server session'].filter(Boolean).join(' · '),
    wall: false,
  };
}

/** A mission's elapsed time in seconds: to `nowT` (the station clock now) while it is live, else
 *  to its end; null when it never started. */
export function missionElapsed(m, nowT) {
  if (!m || typeof m.started_s !== 'number') return null;
  if (m.live && typeof nowT === 'number') return Math.max(0, nowT - m.started_s);
  if (typeof m.ended_s === 'number') return Math.max(0, m.ended_s - m.started_s);
  if (typeof m.duration_s === 'number') return m.duration_s;
  return null;
}

/** The wall-clock moment (ms since 1970 UTC) a mission started (`which` 'started') or ended
 *  ('ended'): as the station stored it (started_utc, ended_utc), else mapped from the station
 *  clock when this session ran it; null when neither is known. */
export function missionWallMs(m, which) {
  const stored = Date.parse(m?.[`${which}_utc`] ?? '');
  if (Number.isFinite(stored)) return stored;
  const t = m?.[`${which}_s`];
  return typeof t === 'number' && inSession(m) ? wallMs(t) : null;
}

/** A mission's elapsed time by the wall clock, in seconds: to the server's now while it is live,
 *  else to its end; null when either end is unknown. On the simulator the station clock runs
 *  ×realtime factor, so this is not missionElapsed (which is on the station clock). */
export function missionWallElapsed(m, nowMs = serverNowMs()) {
  const start = missionWallMs(m, 'started');
  const end = m?.live ? nowMs : missionWallMs(m, 'ended');
  if (start === null || end === null || typeof end !== 'number') return null;
  return Math.max(0, (end - start) / 1000);
}

// Alarms: what an operator must not miss while looking elsewhere. Containment entered,
// the link stale or lost while a mission runs, the M200's frontseat failsafe, a mission halted.
// Each one shows in a bar under the header (every view) that stays until acknowledged, beeps until
// then unless muted, and is listed in the event log.
//
// Browsers let a page play sound only after a user gesture: the audio context is made (or resumed)
// at the first click or key press; an alarm raised before that is shown, and beeps from then on.

import { state, on, emit } from './state.js';
import { el } from './format.js';
import { namesVehicle } from './fleet.js';

const LINK_GRACE_MS = 3000; // a link this long not LIVE while a mission runs is an alarm
const BEEP_EVERY_MS = 4000; // repeated while unacknowledged
const MUTE_KEY = 'avk-mute';

const active = []; // unacknowledged: {id, kind, title, message, t}
const log = []; // every alarm raised, for the test hook
let nextId = 1;
let audio = null;
let beeps = 0;
let beepTimer = null;
let muted = false;
let linkBadSince = null; // the link not LIVE since (performance.now())
let linkLostSince = null; // DISCONNECTED since
let linkRaised = null; // what the alarm of this bad spell said: 'stale' | 'lost'
let failsafeRaised = null; // the failsafe value already alarmed
let ready = false; // the first catch-up is done: what was already in the log is history, not news
const seenEvents = new WeakSet();

/** Raises an alarm: once per `kind` while it is unacknowledged, unless it now says something else
 *  (the link stale, then lost): then the new one takes the old one's place in the bar, so the bar
 *  shows the state as it is, not the first alarm of the kind. */
export function raise(kind, title, message, { vehicleId = null, key = vehicleId } = {}) {
  // On a fleet, one alarm of a kind per vehicle (or pair of vehicles: `key`).
  const shown = active.findIndex((a) => a.kind === kind && a.key === key);
  if (shown >= 0 && active[shown].title === title) return false;
  const a = { id: nextId++, kind, key, title, message, t: state.nav?.t_s ?? null, vehicleId };
  if (shown >= 0) active.splice(shown, 1, a);
  else active.push(a);
  log.push(a);
  emit('events', state.events); // the log lists it (alarmEntries), beside the station's events
  render();
  beep();
  scheduleBeeps();
  return true;
}

/** Every alarm raised, as event-log entries (kept here: a re-read of the log over REST replaces
 *  the station's events, and must not drop the alarms). */
export function alarmEntries() {
  return log.map((a) => ({ t: a.t, kind: 'alarm', level: 'alarm', message: `${a.title}: ${a.message}`, alarm: a.kind, vehicle_id: a.vehicleId, acknowledged: !active.includes(a) }));
}

export function acknowledge() {
  if (active.length === 0) return false;
  active.splice(0);
  render();
  clearInterval(beepTimer);
  beepTimer = null;
  return true;
}

export function alarmsState() {
  return { active: active.map((a) => ({ id: a.id, kind: a.kind, title: a.title })), raised: log.map((a) => a.kind), beeps, muted, audio: audio?.state ?? 'none' };
}

export function setMuted(m) {
  muted = Boolean(m);
  try {
    localStorage.setItem(MUTE_KEY, muted ? '1' : '0');
  } catch {
    // private mode: the choice lasts for this page
  }
  const b = document.getElementById('mute-toggle');
  if (b) {
    b.setAttribute('aria-pressed', String(muted));
    b.textContent = muted ? '♪ Muted' : '♪ Sound';
    b.title = muted ? 'Alarm sound off (m turns it on)' : 'Alarm sound on (m mutes)';
  }
}

export function toggleMute() {
  setMuted(!muted);
}

// ---------------------------------------------------------------- sound

function unlockAudio() {
  const Ctx = window.AudioContext ?? window.webkitAudioContext;
  if (!Ctx) return;
  try {
    audio ??= new Ctx();
    if (audio.state === 'suspended') audio.resume().catch(() => {});
  } catch {
    audio = null;
  }
}

/** A short two-tone beep (880 Hz then 660 Hz); nothing while muted or before a user gesture. */
function beep() {
  if (muted || !audio || audio.state !== 'running') return;
  const t0 = audio.currentTime;
  for (const [f, dt] of [[880, 0], [660, 0.18]]) {
    const osc = audio.createOscillator();
    const gain = audio.createGain();
    osc.type = 'square';
    osc.frequency.value = f;
    gain.gain.setValueAtTime(0.0001, t0 + dt);
    gain.gain.exponentialRampToValueAtTime(0.15, t0 + dt + 0.01);
    gain.gain.exponentialRampToValueAtTime(0.0001, t0 + dt + 0.16);
    osc.connect(gain).connect(audio.destination);
    osc.start(t0 + dt);
    osc.stop(t0 + dt + 0.17);
  }
  beeps++;
}

function scheduleBeeps() {
  if (beepTimer) return;
  beepTimer = setInterval(() => {
    if (active.length === 0) {
      clearInterval(beepTimer);
      beepTimer = null;
      return;
    }
    beep();
  }, BEEP_EVERY_MS);
}

// ---------------------------------------------------------------- the bar

function render() {
  const bar = document.getElementById('alarm-bar');
  if (!bar) return;
  bar.hidden = active.length === 0;
  document.getElementById('alarm-list').replaceChildren(
    ...active.map((a) => el('li', { 'data-kind': a.kind }, el('strong', { text: a.title }), ` ${a.message}`)),
  );
}

// ---------------------------------------------------------------- conditions

const RUNNING = (m) => m && (m.status === 'running' || m.status === 'created');

/** New status messages from the stream (not the log read over REST: that is history). */
function checkEvents() {
  for (const e of state.events) {
    if (seenEvents.has(e)) continue;
    seenEvents.add(e);
    if (!ready || e.logged) continue;
    // On a fleet an event says which vehicle it is about: so does its alarm.
    const vid = e.vehicle_id ?? null;
    const of = (text) => (vid && !String(text).startsWith(vid) ? `${vid}: ${text}` : text);
    if (e.kind === 'containment') raise('containment', 'Containment', of(e.message || 'the vehicle reached the buffer zone'), { vehicleId: vid });
    if (e.kind === 'halted' || e.kind === 'mission_halted') raise('halted', 'Mission halted', of(e.message || 'the mission stopped itself'), { vehicleId: vid });
    // Two vehicles' predicted closest approach below the standoff, one alarm per pair; a vehicle
    // whose link is lost.
    if (e.kind === 'collision_watch') raise('collision', 'Collision watch', e.message || 'two vehicles are closing', { vehicleId: vid, key: pairOf(e) });
    if (e.kind === 'vehicle_left') raise('vehicle_left', 'Vehicle lost', of(e.message || 'its link is lost'), { vehicleId: vid });
  }
}

/** The vehicles a collision watch names (the fleet's ids in its message), sorted: its pair. */
function pairOf(e) {
  const named = [...state.fleet.keys()].filter((id) => namesVehicle(e.message, id));
  return (named.length ? named : [e.vehicle_id ?? '']).sort().join('+');
}

/** The mission's state: halted as the state change of a mission message, too. */
let lastStatus = null;
function checkMission(m) {
  const s = m ? `${m.id}:${m.status}` : null;
  if (ready && s !== lastStatus && m?.status === 'halted' && lastStatus?.startsWith(`${m.id}:`)) {
    raise('halted', 'Mission halted', m.status_reason || `mission ${m.id} stopped itself`);
  }
  lastStatus = s;
}

/** The link not LIVE for LINK_GRACE_MS while a mission runs: stale (the stream open, navigation
 *  old) or lost (no stream). Lost outranks stale: a link that went stale and then dropped raises
 *  "Link lost", also while the stale alarm is still unacknowledged. */
function checkLink() {
  const bad = state.link !== 'LIVE' && RUNNING(state.mission);
  if (!bad) {
    linkBadSince = null;
    linkLostSince = null;
    linkRaised = null;
    return;
  }
  const now = performance.now();
  linkBadSince ??= now;
  if (state.link === 'DISCONNECTED') linkLostSince ??= now;
  else linkLostSince = null;
  const mission = `while mission ${state.mission.id} runs`;
  if (linkRaised !== 'lost' && linkLostSince !== null && now - linkLostSince >= LINK_GRACE_MS) {
    linkRaised = 'lost';
    raise('link', 'Link lost', `link lost: no stream from the station ${mission}`);
  } else if (linkRaised === null && now - linkBadSince >= LINK_GRACE_MS && state.link === 'STALE') {
    linkRaised = 'stale';
    const vehicle = state.nav?.link && state.nav.link !== 'LIVE' ? ` (vehicle link ${state.nav.link})` : '';
    raise('link', 'Link stale', `link stale: no fresh navigation from the vehicle${vehicle} ${mission}`);
  }
}

function checkFailsafe(nav) {
  const f = nav?.frontseat?.failsafe;
  if (!f || f === 'none') {
    failsafeRaised = null;
    return;
  }
  if (f !== failsafeRaised) {
    failsafeRaised = f;
    raise('failsafe', 'Frontseat failsafe', `the vehicle is in all stop (${f})`);
  }
}

export function initAlarms() {
  let stored = null;
  try {
    stored = localStorage.getItem(MUTE_KEY);
  } catch {
    stored = null;
  }
  setMuted(stored === '1');
  document.getElementById('mute-toggle')?.addEventListener('click', toggleMute);
  document.getElementById('alarm-ack')?.addEventListener('click', acknowledge);
  for (const ev of ['pointerdown', 'keydown']) window.addEventListener(ev, unlockAudio, { capture: true });
  on('events', checkEvents);
  on('mission', checkMission);
  on('nav', checkFailsafe);
  on('synced', () => {
    checkEvents(); // marks what the first read brought as seen
    ready = true;
  });
  setInterval(checkLink, 500);
}

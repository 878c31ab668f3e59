// The mission state banner at the top of Live and the wall-clock readout: what the mission is
// doing, for how long, and how far it got, readable from across a room and above the fold on a
// tablet. Updated at most once a frame, and only what changed.

import { state, on } from './state.js';
import { timeLabel, fmtElapsed, missionElapsed, missionWallElapsed, clockMapping } from './clock.js';

const LOOK = {
  created: { icon: '○', word: 'STARTING' },
  running: { icon: '▶', word: 'RUNNING' },
  paused: { icon: '‖', word: 'PAUSED' },
  done: { icon: '✓', word: 'DONE' },
  aborted: { icon: '✖', word: 'ABORTED' },
  interrupted: { icon: '⚡', word: 'INTERRUPTED' },
  halted: { icon: '■', word: 'HALTED' },
};

let requested = false;

function set(id, text, title) {
  const e = document.getElementById(id);
  if (!e) return;
  if (e.textContent !== text) e.textContent = text;
  if (title !== undefined && e.title !== title) e.title = title;
}

/** Turns done (ok) and planned over the mission's cells; null for a mission without a turn array. */
export function turnsDone(m) {
  const cells = m?.cells ?? [];
  if (cells.length === 0) return null;
  return {
    done: cells.reduce((n, c) => n + Math.min(c.ok ?? 0, c.planned ?? 1), 0),
    planned: cells.reduce((n, c) => n + (c.planned ?? 1), 0),
  };
}

function render() {
  requested = false;
  const m = state.mission;
  const box = document.getElementById('mission-banner');
  if (!box) return;
  const status = m?.status ?? 'none';
  const look = LOOK[status] ?? { icon: '·', word: m ? String(status).toUpperCase() : 'NO MISSION' };
  const cls = `mission-banner ms-${m ? status : 'none'}`;
  if (box.className !== cls) box.className = cls;
  box.dataset.state = m ? status : 'none';
  set('mb-state', `${look.icon} ${look.word}`);
  set('mb-name', m ? `mission ${m.id} “${m.name}”` : 'Start one in the Mission view.');
  // Elapsed by the wall clock (from the stored or mapped start to the server's now, or to the
  // end), labelled so; the station clock's beside it where it runs at another rate (the simulator
  // runs it ×realtime factor: 67 s after a start at ×10 it reads 11:10). Without a wall-clock
  // start (a mission of an earlier session stored before started_utc was kept) the station
  // clock's alone, labelled as such.
  const start = m ? timeLabel(m.started_s, m) : null;
  const wall = missionWallElapsed(m);
  const station = missionElapsed(m, state.nav?.t_s);
  const factor = clockMapping()?.factor ?? 1;
  set('mb-elapsed', fmtElapsed(wall ?? station), start?.text ? `started ${start.text} (${start.title})` : '');
  set('mb-elapsed-clock', wall === null && station !== null ? 'station clock' : 'wall clock');
  const both = wall !== null && station !== null && factor !== 1;
  const extra = document.getElementById('mb-station');
  if (extra && extra.hidden === both) extra.hidden = !both;
  set('mb-station-elapsed', both ? fmtElapsed(station) : '–');
  set('mb-station-clock', `station clock ×${factor}`, 'The station clock: the time base of nav, turns and events; on the simulator it runs ×realtime factor');
  const td = turnsDone(m);
  set('mb-turns', td ? `${td.done} of ${td.planned}` : '–');
  set('mb-mode', m?.live && m.helm_mode ? m.helm_mode : '');
  set('mb-reason', m && !m.live && m.status_reason ? m.status_reason : '');
  // The wall clock of the Live readout, from the station clock of the newest nav sample.
  const now = timeLabel(state.nav?.t_s, null);
  set('live-wall', now.text || '–', now.title);
}

function request() {
  if (requested) return;
  requested = true;
  requestAnimationFrame(render);
}

export function initBanner() {
  for (const ev of ['nav', 'mission', 'missions', 'clock']) on(ev, request);
  // The wall-clock elapsed time runs on while no navigation arrives (a lost link).
  setInterval(request, 1000);
  request();
}

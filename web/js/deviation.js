// The running turn against its prediction (thesis §6.2): about once a second while a
// turn runs, GET /vehicles/{vid}/maneuvers/ongoing with the turn's start pose, heading change and
// speed, the time since it started and the vehicle's position now. The answer (where the vehicle
// should be, how far it is from there, whether it is inside the corridor) goes to
// state.ongoing; the Live view draws it.

import { state, on, emit } from './state.js';
import { getJson } from './api.js';
import { cktCovers, predictionParams } from './predictions.js';
import { num } from './format.js';

const POLL_MS = 1000;

let timer = null;
let asking = false;

export function initDeviation() {
  on('turn', (turn) => {
    clearInterval(timer);
    timer = null;
    state.ongoing = null;
    emit('ongoing', null);
    if (!turn?.start) return;
    poll(turn);
    timer = setInterval(() => poll(turn), POLL_MS);
  });
}

const MAX_ELAPSED_S = 600; // the API's limit on `elapsed` (docs/api.md)

async function poll(turn) {
  const nav = state.nav;
  if (asking || state.turn !== turn || !nav || !state.vehicleId) return;
  // The server evaluates up to MAX_ELAPSED_S into a maneuver; a turn still open after that (its
  // end was missed) is not asked about again.
  if (nav.t_s - turn.start.t > MAX_ELAPSED_S) return;
  // A sample from before the turn's start (a page that read the vehicle before the turn began) is
  // not a position in the turn: the newest one is awaited.
  if (nav.t_s < turn.start.t) return;
  // AVK where the table answers at this speed; else the instantaneous assumption, said so.
  const method = cktCovers(turn.speed) ? 'avk' : 'instantaneous';
  asking = true;
  try {
    const o = await getJson(`/vehicles/${encodeURIComponent(state.vehicleId)}/maneuvers/ongoing`, {
      x: turn.start.x,
      y: turn.start.y,
      heading: turn.start.heading,
      dheading: turn.dheading,
      speed: turn.speed,
      elapsed: Math.max(0, nav.t_s - turn.start.t),
      mx: nav.x_m,
      my: nav.y_m,
      method,
      ...predictionParams(),
    });
    if (state.turn !== turn) return; // the turn ended meanwhile
    state.ongoing = o;
    emit('ongoing', o);
  } catch (e) {
    console.warn('no ongoing evaluation', e.message);
  } finally {
    asking = false;
  }
}

/** Whether the vehicle is inside the band the prediction allows at this moment: the position band
 *  `band_now` at the elapsed time (the corridor's spread along and across the path there, with the
 *  navigation's own position noise), when the prediction has a corridor. Not the lateral half
 *  width at this point alone (`inside_corridor`): at a turn's start that is 0 m, and every 0.1–0.4 m
 *  of GNSS noise read "outside corridor". null when there is no corridor to judge by. */
export function insideBand(o) {
  if (typeof o?.half_width_m !== 'number') return null;
  if (typeof o.band_now?.inside === 'boolean') return o.band_now.inside;
  return typeof o.inside_corridor === 'boolean' ? o.inside_corridor : null;
}

/** "deviation 0.8 m (inside 90 % corridor)"; otherwise the method that predicted, and whether it
 *  had a corridor. */
export function deviationText(o) {
  if (!o || typeof o.deviation_m !== 'number') return '–';
  const pct = Math.round((o.corridor ?? 0.9) * 100);
  const inside = insideBand(o);
  let where = `${o.method} prediction, no corridor`;
  if (typeof inside === 'boolean') where = `${inside ? 'inside' : 'outside'} ${pct} % corridor`;
  else if (typeof o.half_width_m === 'number') where = `${o.method} prediction`;
  return `deviation ${num(o.deviation_m, 1)} m (${where})`;
}

/** The band the deviation was judged against, for the panel's hover. */
export function deviationTitle(o) {
  const b = o?.band_now;
  const base = 'How far the vehicle is from where the prediction of the running turn puts it now (GET /maneuvers/ongoing, once a second)';
  if (typeof insideBand(o) !== 'boolean' || !b) return base;
  const pct = Math.round((o.corridor ?? 0.9) * 100);
  return `${base}; judged against the ${pct} % band ${num(o.elapsed_s, 1)} s into the turn: ${num(b.major_m, 2)} × ${num(b.minor_m, 2)} m (half axes; corridor half width there ${num(o.half_width_m, 2)} m)`;
}

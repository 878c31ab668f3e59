// Live's predictions: which methods answer for a turn (a CKT covering its speed, a stored model),
// the frame they are asked in, and asking them for the shown turn.

import { state, emit } from './state.js';
import { getJson } from './api.js';
import { frameParams } from './frame.js';

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
export async function fetchPredictions(turn) {
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

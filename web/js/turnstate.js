// The turn under way and the last one as the page draws them: adopted from a mission's report
// (a page opened mid-turn, a lost stream message) and ended as the stream or the report says.

import { state, emit } from './state.js';
import { getJson } from './api.js';
import { wrap360 } from './format.js';
import { fetchPredictions } from './predictions.js';

export const markLabel = (speed, dheading) => `${dheading > 0 ? '+' : ''}${Math.round(dheading)}° @ ${speed} m/s`;

/** The turn starts the time series marks: the mission's stored turns, the one under way, and any
 *  the stream started since (kept when the report does not list them yet). */
export function setTurnMarks(m) {
  const marks = (m.turn_list ?? []).map((r) => ({ t: r.start_time_s, label: markLabel(r.speed_mps, r.goal_dheading_deg) }));
  if (m.running_turn) marks.push({ t: m.running_turn.t_s, label: markLabel(m.running_turn.speed_mps, m.running_turn.dheading_deg) });
  const newest = marks.length ? Math.max(...marks.map((k) => k.t)) : -Infinity;
  const sameMission = state.turnMarksMission === m.id;
  if (sameMission) for (const k of state.turnMarks) if (k.t > newest + 1e-6) marks.push(k);
  state.turnMarks = marks.sort((a, b) => a.t - b.t);
  state.turnMarksMission = m.id;
  emit('series');
}

export function turnFromServer(missionId, rt) {
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
export function adoptRunningTurn(m, current = false) {
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
export function endTurn({ event, endT, storedId }) {
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
export async function adoptLastTurn(m) {
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


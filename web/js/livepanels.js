// The Live view's text panels: the vehicle readout, the turn panel and the turn-array progress
// grid.

import { state } from './state.js';
import { METHOD_STYLE } from './plots.js';
import { num, meanSd, headingDiff, el } from './format.js';
import { deviationText, deviationTitle } from './deviation.js';
import { localGrid, formatLatLon } from './geo.js';
import { answersFrameText } from './frame.js';
import { turnsDone } from './banner.js';
import { turnLabel } from './turnlabel.js';

// The deviations shown while a turn ran ({text, expected: [x, y]}), newest last, bounded: the test
// hook reports them (at a high real-time factor a turn is on screen for a moment only).
export const deviationLog = [];

/** "0.20 ± 0.01 m/s toward 182 ± 3°": the station's estimate of the current. */
export function currentText(c) {
  if (!c) return 'not estimated yet';
  const still = c.significant ? '' : ' (not told apart from still water)';
  return `${num(c.speed_mps, 2)} ± ${num(c.speed_sd_mps, 2)} m/s toward ${num(c.toward_deg, 0)} ± ${num(c.toward_sd_deg, 0)}°${still}`;
}

/** What the shown turn's predictions (and the running turn's deviation) move against, as each
 *  answer says it: one line when they agree. */
export function predictionFrameText() {
  const turn = state.shownTurn;
  const answers = {};
  for (const [method, p] of Object.entries(turn?.predictions ?? {})) answers[METHOD_STYLE[method]?.name ?? method] = p;
  if (state.turn && state.ongoing) answers.deviation = state.ongoing;
  return answersFrameText(answers);
}

function text(id, v) {
  const e = document.getElementById(id);
  if (e && e.textContent !== v) e.textContent = v;
}

let gridOf = { datum: null, grid: null };
/** The vehicle's latitude and longitude: the grid point through the station's datum
 *  (`avk serve --datum`); without a datum the grid is all there is. */
export function latLonText(nav) {
  if (!state.datum) return 'no datum (avk serve --datum LAT,LON)';
  if (!nav || !Number.isFinite(nav.x_m)) return '–';
  if (gridOf.datum !== state.datum) gridOf = { datum: state.datum, grid: localGrid(state.datum) };
  return formatLatLon(gridOf.grid.toLatLon(nav.x_m, nav.y_m));
}

export function renderReadout() {
  const nav = state.nav;
  const helm = state.helm;
  text('live-mode', helm?.mode ?? '–');
  text('live-x', num(nav?.x_m, 1));
  text('live-y', num(nav?.y_m, 1));
  text('live-speed', num(nav?.speed_mps, 2));
  text('live-heading', num(nav?.heading_deg, 1));
  text('live-dspeed', num(helm?.desired_speed_mps, 2));
  text('live-dheading', num(helm?.desired_heading_deg, 1));
  text('live-t', num(nav?.t_s, 1));
  text('live-latlon', latLonText(nav));
  text('live-current', currentText(state.current));
  text('live-pred-frame', predictionFrameText());
  // Only a real vehicle (the M200 driver) reports a battery and a frontseat link.
  const fs = nav?.frontseat;
  for (const e of document.querySelectorAll('.frontseat')) e.hidden = !fs;
  if (fs) {
    text('live-battery', num(fs.battery_v, 2));
    text('live-frontseat', `${fs.failsafe === 'none' ? 'ok' : `all stop (${fs.failsafe})`}, ${fs.bad_lines} bad lines, ${fs.disconnects} disconnects`);
  }
}

export function renderTurnPanel() {
  const turn = state.turn;
  const nav = state.nav;
  const last = state.lastTurn;
  const shown = state.shownTurn;
  const preds = shown ? Object.keys(shown.predictions) : [];
  if (turn) {
    text('turn-cmd-speed', num(turn.speed, 2));
    text('turn-cmd-dpsi', num(turn.dheading, 0));
    text('turn-cmd-goal', num(turn.goalHeading, 1));
    text('turn-meas-speed', num(nav?.speed_mps, 2));
    text('turn-meas-dpsi', turn.start && nav ? num(headingDiff(nav.heading_deg, turn.start.heading), 1) : '–');
    text('turn-meas-heading', num(nav?.heading_deg, 1));
    // Numbered as the event log and Replay number it: the next of the plan's turns to be done.
    const done = turn.missionId === state.mission?.id ? turnsDone(state.mission) : null;
    const which = done && done.done < done.planned ? ` · ${turnLabel(done.done + 1, done.planned)}` : '';
    text('turn-status', `Turn running (attempt ${turn.attempt ?? 1})${which} · predictions: ${preds.length ? preds.join(', ') : 'none yet'}`);
    const deviation = deviationText(state.ongoing);
    text('turn-deviation', deviation);
    const devEl = document.getElementById('turn-deviation');
    const devTitle = deviationTitle(state.ongoing);
    if (devEl.title !== devTitle) devEl.title = devTitle;
    const e = state.ongoing?.expected;
    if (e && deviation !== deviationLog.at(-1)?.text) {
      deviationLog.push({ text: deviation, expected: [e.x_m, e.y_m] });
      if (deviationLog.length > 200) deviationLog.shift();
    }
  } else {
    // Between turns (conditioning, containment, the return leg) nothing is a turn: the helm's
    // desired values are in the Vehicle readout, not presented here as one.
    for (const id of ['turn-cmd-speed', 'turn-cmd-dpsi', 'turn-cmd-goal', 'turn-meas-speed', 'turn-meas-dpsi', 'turn-meas-heading']) text(id, '–');
    text('turn-deviation', '–');
    text(
      'turn-status',
      last
        ? `No turn running. Last turn: ${last.event}${last.reason ? ` (${last.reason})` : ''}, ${num(last.speed_mps, 2)} m/s, Δψ ${num(last.goal_dheading_deg, 0)}°, advance ${num(last.advance_m, 1)} m, transfer ${num(last.transfer_m, 1)} m${preds.length ? `; drawn with its predictions: ${preds.join(', ')}` : ''}.`
        : 'No turn running.',
    );
  }
  const parts = [];
  if (state.conditioningSinceT !== null && nav) parts.push(`conditioning for ${num(nav.t_s - state.conditioningSinceT, 1)} s`);
  if (typeof last?.condition_set_time_s === 'number') parts.push(`last ${num(last.condition_set_time_s, 1)} s`);
  if (state.mission?.condition_set_time_s) parts.push(`mission mean ${meanSd(state.mission.condition_set_time_s, 1, ' s', state.mission.condition_set?.episodes?.set)}`);
  // Attempts the mission wasted: conditioning cut short by containment (or a pause, a link loss)
  // and conditions not set in time. A healthy mission shows few of either.
  const episodes = state.mission?.condition_set?.episodes;
  if (episodes) parts.push(`${episodes.interrupted ?? 0} interrupted, ${episodes.timeout ?? 0} timed out`);
  text('live-cst', parts.length ? parts.join(' · ') : '–');
}

/** A cell's state for the grid: running, done, aborted (given up, or tried and then the mission
 *  ended), not run (the mission ended before it was ever tried), pending. Each has a mark as well
 *  as a colour. */
export function cellState(c, missionStatus) {
  if (c.running) return 'running';
  const planned = c.planned ?? 1;
  if ((c.ok ?? 0) >= planned) return 'done';
  if ((c.given_up ?? 0) > 0) return 'aborted';
  const ended = ['done', 'aborted', 'halted'].includes(missionStatus);
  const tried = (c.ok ?? 0) + (c.aborted ?? 0) + (c.rejected ?? 0) > 0;
  if (ended) return tried ? 'aborted' : 'notrun';
  // Aborted attempts that will be re-queued stay pending (the label counts them with ✗n).
  return 'pending';
}

const MARK = { pending: '·', running: '▶', done: '✓', aborted: '✗', notrun: '–' };
const STATE_NAME = { pending: 'pending', running: 'running', done: 'done', aborted: 'aborted', notrun: 'not run' };

export function renderProgress() {
  const grid = document.getElementById('progress-grid');
  const m = state.mission;
  text('progress-title', m ? `· mission ${m.id} “${m.name}” · ${m.status}${m.helm_mode ? ` · ${m.helm_mode}` : ''}` : '');
  if (!m) {
    grid.replaceChildren(el('p', { class: 'small muted', text: 'No mission yet. Start one in the Mission view.' }));
    text('progress-counts', '');
    return;
  }
  const cells = m.cells ?? [];
  if (cells.length === 0) {
    grid.replaceChildren(el('p', { class: 'small muted', text: m.config?.kind === 'persistent_excitation' ? 'Persistent excitation: no turn array.' : 'No cells.' }));
    text('progress-counts', '');
    return;
  }
  const speeds = [...new Set(cells.map((c) => c.speed_mps))].sort((a, b) => a - b);
  const dpsis = [...new Set(cells.map((c) => c.dheading_deg))].sort((a, b) => a - b);
  const counts = { pending: 0, running: 0, done: 0, aborted: 0, notrun: 0 };
  const table = el('table', { 'aria-label': 'Turn array: rows are speeds, columns heading changes' });
  table.append(el('tr', {}, el('th', { scope: 'col', text: 'm/s \\ Δψ' }), ...dpsis.map((d) => el('th', { scope: 'col', text: `${d}°` }))));
  for (const s of speeds) {
    const tr = el('tr', {}, el('th', { scope: 'row', text: s.toFixed(2) }));
    for (const d of dpsis) {
      const c = cells.find((q) => q.speed_mps === s && q.dheading_deg === d);
      if (!c) {
        tr.append(el('td'));
        continue;
      }
      const st = cellState(c, m.status);
      counts[st]++;
      const extra = (c.aborted ?? 0) + (c.rejected ?? 0);
      const label = `${MARK[st]} ${c.ok ?? 0}/${c.planned ?? 1}${extra ? ` ✗${extra}` : ''}`;
      tr.append(
        el('td', {
          class: `st-${st}`,
          text: label,
          title: `${s} m/s, ${d}°: ${STATE_NAME[st]}; ok ${c.ok ?? 0} of ${c.planned ?? 1}, aborted ${c.aborted ?? 0}, rejected ${c.rejected ?? 0}${c.given_up ? `, given up ${c.given_up}` : ''}`,
        }),
      );
    }
    table.append(tr);
  }
  grid.replaceChildren(table);
  text('progress-counts', `pending ${counts.pending} · running ${counts.running} · done ${counts.done} · aborted ${counts.aborted}${counts.notrun ? ` · not run ${counts.notrun}` : ''}`);
}


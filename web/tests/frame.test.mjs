// The frame of an answer as the dashboard says it, and the operator's override as it is sent
// (web/js/frame.js): pure functions, no browser or server.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { frameParams, frameOf, answerFrameText, answersFrameText, currentUsedText, percentText, riskText, marginText, explanationText, colregsText, candidateText } from '../js/frame.js';

test('auto sends nothing, so the station answers over ground; an override sends what was chosen', () => {
  assert.deepEqual(frameParams({ current: 'auto', speedReference: 'auto' }), {});
  assert.deepEqual(frameParams({ current: 'none', speedReference: 'auto' }), { current: 'none' });
  assert.deepEqual(frameParams({ current: 'live', speedReference: 'through_water' }), { current: 'live', speed_reference: 'through_water' });
  assert.deepEqual(frameParams({ current: 'bogus', speedReference: 'sideways' }), {});
});

test("predict's relative_to wins over its placement frame; a maneuver answer's frame is read as is", () => {
  assert.equal(frameOf({ frame: 'world', relative_to: 'water' }), 'water');
  assert.equal(frameOf({ frame: 'ground' }), 'ground');
  assert.equal(frameOf({ frame: 'normalized' }), null);
});

test('an answer over ground in an estimated current reads with the estimate and its 1 sigma', () => {
  const answer = {
    relative_to: 'ground',
    current: { east_mps: 0, north_mps: -0.2, speed_mps: 0.2, toward_deg: 180, source: 'live', speed_sd_mps: 0.012, toward_sd_deg: 3.4 },
    speed_reference: { value: 'over_ground', source: 'default' },
  };
  assert.equal(answerFrameText(answer), 'over ground · current 0.20 ± 0.01 m/s toward 180 ± 3° (live estimate) · speed held over ground (default)');
  const water = { frame: 'water', current: { source: 'none' }, speed_reference: { value: 'through_water', source: 'query' } };
  assert.equal(answerFrameText(water), 'through the water · current none asked · speed held through the water (asked)');
  assert.equal(currentUsedText({ source: 'still_water' }), 'still water (the estimate is not told apart from it)');
  assert.equal(currentUsedText({ east_mps: 0.1, north_mps: 0, speed_mps: 0.1, toward_deg: 90, source: 'query' }), '0.10 m/s toward 90° (given)');
  // Answers that agree read as one line; otherwise each is named.
  assert.equal(answersFrameText({ AVK: answer, instantaneous: answer }), answerFrameText(answer));
  assert.equal(answersFrameText({ AVK: answer, deviation: water }), `AVK: ${answerFrameText(answer)}; deviation: ${answerFrameText(water)}`);
  assert.equal(answersFrameText({}), '–');
});

test('the risk, the margin, the sentence and the COLREGS rule of a choice', () => {
  assert.equal(percentText(0.0234), '2.3 %');
  assert.equal(percentText(0.125), '13 %');
  assert.equal(percentText(0), '0 %');
  assert.equal(percentText(0.0004), '< 0.1 %');
  const chosen = { risk: 0.0234, within_limit: true, margin_m: 4.25, explanation: 'rule 14: the smallest starboard turn (or the held course) with risk <= 5 %', colregs_rule: '14', situations: ['head_on'] };
  assert.equal(riskText(chosen, 0.05), 'risk 2.3 % (within 5.0 %)');
  assert.equal(riskText({ risk: 0.2, within_limit: false }, 0.05), 'risk 20 % (over the 5.0 % limit)');
  assert.equal(marginText(chosen), 'margin 4.3 m');
  assert.equal(explanationText(chosen), 'Rule 14: the smallest starboard turn (or the held course) with risk <= 5 %.');
  assert.equal(colregsText(chosen, true), 'COLREGS rule 14 applied (head-on)');
  assert.equal(colregsText({ ...chosen, colregs_rule: null, situations: [] }, true), 'COLREGS: no starboard rule applied');
  assert.equal(colregsText(chosen, false), '');
  assert.equal(candidateText({ dheading_deg: 35, risk: 0.0234, min_cpa_m: 12.34, min_edge_cpa_m: null }), 'Δψ +35°: risk 2.3 %, CPA 12.3 m');
});

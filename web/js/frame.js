// What a prediction moves against, and the operator's choice of it. The station answers over
// ground by default: with its latest estimate of the current when that is told apart from still
// water, in still water when it is not, and through the water only when it has no estimate at all
// (or is asked `current=none`). Each answer says so: `relative_to` (GET /predict; its `frame` is
// world or normalised) or `frame` (the maneuver answers), `current` (with the estimate's 1σ) and
// `speed_reference` (the speed the vehicle's loop holds). Pure functions: no DOM.

import { num } from './format.js';

/** The operator's default: nothing asked, so the station's default answers. */
export const AUTO_FRAME = Object.freeze({ current: 'auto', speedReference: 'auto' });

/** The choice as GET query parameters (/predict, /maneuvers/ongoing): none for "auto". */
export function frameParams(choice = AUTO_FRAME) {
  const p = {};
  if (choice.current === 'live' || choice.current === 'none') p.current = choice.current;
  if (choice.speedReference === 'over_ground' || choice.speedReference === 'through_water') p.speed_reference = choice.speedReference;
  return p;
}

/** The choice as fields of a maneuver request body (POST /maneuvers/evaluate): the same names. */
export const frameFields = frameParams;

/** "ground" or "water": what the answer's paths move against; null when it does not say. */
export function frameOf(answer) {
  const f = answer?.relative_to ?? answer?.frame;
  return f === 'ground' || f === 'water' ? f : null;
}

export function frameLabel(answer) {
  const f = frameOf(answer);
  return f === 'ground' ? 'over ground' : f === 'water' ? 'through the water' : '–';
}

const SOURCE = { live: 'live estimate', query: 'given' };

/** The current an answer applied: "0.20 ± 0.01 m/s toward 182 ± 3° (live estimate)", or why
 *  none was ("still water", "none asked", "not estimated"). */
export function currentUsedText(c) {
  if (!c) return 'none';
  if (typeof c.speed_mps === 'number') {
    const sd = typeof c.speed_sd_mps === 'number' ? ` ± ${num(c.speed_sd_mps, 2)}` : '';
    const tsd = typeof c.toward_sd_deg === 'number' ? ` ± ${num(c.toward_sd_deg, 0)}` : '';
    return `${num(c.speed_mps, 2)}${sd} m/s toward ${num(c.toward_deg, 0)}${tsd}° (${SOURCE[c.source] ?? c.source ?? 'given'})`;
  }
  switch (c.source) {
    case 'still_water':
      return 'still water (the estimate is not told apart from it)';
    case 'none':
      return 'none asked';
    case 'unknown':
      return 'not estimated yet';
    default:
      return c.source ?? 'none';
  }
}

const REFERENCE_SOURCE = { query: 'asked', default: 'default', identified: 'identified' };

/** "speed held over ground (default)". */
export function speedReferenceText(r) {
  if (!r?.value) return '–';
  const held = r.value === 'over_ground' ? 'over ground' : 'through the water';
  return `speed held ${held} (${REFERENCE_SOURCE[r.source] ?? r.source})`;
}

/** One line for an answer: "over ground · current 0.20 ± 0.01 m/s toward 182 ± 3° (live
 *  estimate) · speed held over ground (default)". */
export function answerFrameText(answer) {
  if (!answer) return '–';
  const parts = [frameLabel(answer), `current ${currentUsedText(answer.current)}`];
  if (answer.speed_reference) parts.push(speedReferenceText(answer.speed_reference));
  return parts.join(' · ');
}

/** The frames of several answers (by name): one line when they agree, else one per name. */
export function answersFrameText(byName) {
  const entries = Object.entries(byName ?? {}).filter(([, a]) => a);
  if (entries.length === 0) return '–';
  const texts = entries.map(([name, a]) => [name, answerFrameText(a)]);
  if (texts.every(([, t]) => t === texts[0][1])) return texts[0][1];
  return texts.map(([name, t]) => `${name}: ${t}`).join('; ');
}

/** A probability as shown: "2.3 %", "0 %" below 0.05 %, "< 0.1 %" for a risk that is not nil. */
export function percentText(p) {
  if (typeof p !== 'number' || !Number.isFinite(p)) return '–';
  const pct = 100 * p;
  if (pct === 0) return '0 %';
  if (pct < 0.1) return '< 0.1 %';
  return `${pct < 10 ? pct.toFixed(1) : pct.toFixed(0)} %`;
}

/** The chosen candidate's risk against the limit: "risk 2.3 % (within 5.0 %)" or "risk 12 %
 *  (over the 5.0 % limit)". */
export function riskText(chosen, maxRisk) {
  if (!chosen || typeof chosen.risk !== 'number') return '–';
  const limit = percentText(maxRisk);
  const within = chosen.within_limit ?? chosen.risk <= maxRisk;
  return `risk ${percentText(chosen.risk)} (${within ? `within ${limit}` : `over the ${limit} limit`})`;
}

/** "margin 4.2 m" (the predicted CPA less the standoff; negative inside it). */
export function marginText(chosen) {
  return typeof chosen?.margin_m === 'number' ? `margin ${num(chosen.margin_m, 1)} m` : '–';
}

/** The choice's sentence as the station gives it, as a sentence. */
export function explanationText(chosen) {
  const e = chosen?.explanation;
  return e ? `${e.charAt(0).toUpperCase()}${e.slice(1)}.` : '–';
}

const SITUATION = { head_on: 'head-on', crossing_give_way: 'crossing, give way', crossing_stand_on: 'crossing, stand on', overtaking: 'overtaking', overtaken: 'overtaken' };

/** "COLREGS rule 14 applied (head-on)" when the choice was kept to starboard; what the contacts'
 *  situations were otherwise, when COLREGS was asked; '' when it was not. */
export function colregsText(chosen, asked) {
  if (!asked || !chosen) return '';
  const situations = (chosen.situations ?? []).filter((s) => s !== 'none').map((s) => SITUATION[s] ?? s);
  const seen = situations.length ? ` (${[...new Set(situations)].join(', ')})` : '';
  return chosen.colregs_rule ? `COLREGS rule ${chosen.colregs_rule} applied${seen}` : `COLREGS: no starboard rule applied${seen}`;
}

/** A candidate as its tooltip reads: "Δψ +35°: risk 2.3 %, CPA 12.3 m". */
export function candidateText(k) {
  const d = k.dheading_deg;
  return `Δψ ${d > 0 ? '+' : ''}${num(d, 0)}°: risk ${percentText(k.risk)}, CPA ${num(k.min_cpa_m, 1)} m${typeof k.min_edge_cpa_m === 'number' ? `, edge ${num(k.min_edge_cpa_m, 1)} m` : ''}`;
}

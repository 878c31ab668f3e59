// A new mission started while the page is open gets a track of its own: the
// previous mission's track is kept aside, simplified, and drawn faded grey under the new one,
// which starts empty in the track colour. Without this the new track continued the old one in
// the same colour and could not be told apart from it.

import { state, emit } from './state.js';
import { simplify } from './decimate.js';

const TOLERANCE_M = 0.2;

/** Moves the samples of the live track older than `fromT` (the new mission's start; all of them
 *  when it is unknown) into state.previousTrack, tagged with the mission they belong to. */
export function retireTrack(previousMissionId, fromT) {
  const tr = state.track;
  const cut = typeof fromT === 'number' ? tr.indexAtOrAfter(fromT) : tr.length;
  if (tr.length === 0 || cut === 0) {
    state.previousTrack = null;
    emit('previous-track', null);
    return;
  }
  const old = tr.arrays(0, cut);
  const keep = simplify(old.x, old.y, 0, cut - 1, TOLERANCE_M);
  state.previousTrack = { missionId: previousMissionId, x: keep.map((i) => old.x[i]), y: keep.map((i) => old.y[i]) };
  // The samples of the new mission that the stream delivered before its detail was read stay.
  const rest = [];
  for (let k = cut; k < tr.length; k++) {
    const j = (tr.start + k) % tr.capacity;
    rest.push([tr.t[j], tr.x[j], tr.y[j]]);
  }
  tr.clear();
  for (const [t, x, y] of rest) tr.push(t, x, y);
  emit('previous-track', state.previousTrack);
}

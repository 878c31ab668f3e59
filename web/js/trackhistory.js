// The stored track of a mission read into the bounded live track, so a page opened mid-mission
// shows the track so far; only what was recorded since is read at the next catch-up.

import { state, emit } from './state.js';
import { getJson } from './api.js';
import { mergeStoredRows } from './timeseries.js';

const NAV_PAGE = 5000;
// How far the stored track of a mission has been read into the live track: the next catch-up
// reads only what was recorded since. Tied to the track's epoch: a cleared track (server restart)
// is read again from the start.
let navCursor = { missionId: null, after: 0, epoch: -1, rows: 0 };

/** The mission's stored track (GET /missions/{id}/nav, page by page) merged into the bounded live
 *  track, so a page opened mid-mission shows the track so far. Samples are merged by time with
 *  what the stream has already delivered; the track is rebuilt once, which restarts its
 *  decimation (TrackDecimator sees the new epoch) like any other clear. */
export async function loadTrackHistory(id) {
  const tr = state.track;
  const resume = navCursor.missionId === id && navCursor.epoch === tr.epoch;
  const vid = state.vehicleId;
  let after = resume ? navCursor.after : 0;
  const t = [];
  const x = [];
  const y = [];
  const stored = [];
  let lastCount = 0;
  let lastAfter = after;
  for (;;) {
    const page = await getJson(`/missions/${id}/nav`, { limit: NAV_PAGE, after: after || undefined });
    for (const r of page.items) {
      t.push(r.t_s);
      x.push(r.x_m);
      y.push(r.y_m);
      stored.push(r);
    }
    lastCount = page.items.length;
    lastAfter = after;
    if (page.next === null || page.next === undefined) break;
    after = page.next;
  }
  // The last page is not full, so it has no cursor: the same page asked with a limit of exactly
  // its row count is full, and its `next` is the rowid to continue after at the next catch-up.
  if (lastCount > 0) {
    const again = await getJson(`/missions/${id}/nav`, { limit: lastCount, after: lastAfter || undefined });
    after = again.next ?? lastAfter;
  }
  if (state.vehicleId !== vid) return; // another vehicle chosen meanwhile: not its track
  const rows = (resume ? navCursor.rows : 0) + t.length;
  if (t.length && !state.testFeed) {
    mergeIntoTrack(t, x, y); // a test hook owns the track then
    mergeStoredRows(state.series, stored);
    emit('series');
  }
  navCursor = { missionId: id, after, epoch: tr.epoch, rows };
  emit('nav-history', { missionId: id, rows });
}

function mergeIntoTrack(ht, hx, hy) {
  const tr = state.track;
  const order = ht.map((_, i) => i).sort((a, b) => ht[a] - ht[b] || a - b);
  const live = { t: [], x: [], y: [] };
  for (let k = 0; k < tr.length; k++) {
    const j = (tr.start + k) % tr.capacity;
    live.t.push(tr.t[j]);
    live.x.push(tr.x[j]);
    live.y.push(tr.y[j]);
  }
  tr.clear();
  let a = 0;
  let lastT = -Infinity;
  let lastX = NaN;
  let lastY = NaN;
  const push = (t, x, y) => {
    if (Math.abs(t - lastT) < 1e-9) return; // the same sample from the stream and from the store
    // As applyNav: a sample that repeats the last position does not take a slot.
    if (Math.abs(lastX - x) < 0.01 && Math.abs(lastY - y) < 0.01 && t - lastT < 5) return;
    tr.push(t, x, y);
    lastT = t;
    lastX = x;
    lastY = y;
  };
  for (const i of order) {
    while (a < live.t.length && live.t[a] <= ht[i]) {
      push(live.t[a], live.x[a], live.y[a]);
      a++;
    }
    push(ht[i], hx[i], hy[i]);
  }
  for (; a < live.t.length; a++) push(live.t[a], live.x[a], live.y[a]);
}

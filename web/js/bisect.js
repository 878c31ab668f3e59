// One binary search for every time-ordered store on the page (the live track ring, the helm
// series ring, a replayed mission's arrays): they differ only in how the i-th time is read.

/** The first index in [0, length) whose time is ≥ t (length when none), for times that never
 *  decrease with the index; timeAt(i) reads the i-th time. */
export function firstAtOrAfter(length, timeAt, t) {
  let lo = 0;
  let hi = length;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (timeAt(mid) < t) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

/** The last index whose time is ≤ t, or 0 when t is before them all (a replay at its start
 *  shows the first sample). */
export function lastAtOrBefore(length, timeAt, t) {
  let lo = 0;
  let hi = length;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (timeAt(mid) <= t) lo = mid + 1;
    else hi = mid;
  }
  return Math.max(0, lo - 1);
}

// What the Live plot draws of the track: the samples reduced to the points that matter for the
// picture, so that 2 hours at 10 Hz (72,000 samples) cost the renderer a few thousand points.
//
// The track is cut into chunks of CHUNK samples; each full chunk is simplified once with
// Douglas-Peucker (every dropped sample lies within TOLERANCE_M of the drawn line: a tenth of a
// metre, under a pixel at any zoom that shows a whole mission) and never touched again. The
// newest, unfinished chunk is drawn raw. Chunks leave when the ring buffer has dropped their samples.

const CHUNK = 600; // one minute at 10 Hz
const TOLERANCE_M = 0.1;

/** Douglas-Peucker on xs/ys[from..to] (inclusive); returns the kept indices in order. */
export function simplify(xs, ys, from, to, tol) {
  const n = to - from + 1;
  if (n <= 2) return Array.from({ length: n }, (_, k) => from + k);
  const keep = new Uint8Array(n);
  keep[0] = 1;
  keep[n - 1] = 1;
  const stack = [[from, to]];
  const tol2 = tol * tol;
  while (stack.length) {
    const [a, b] = stack.pop();
    const ax = xs[a];
    const ay = ys[a];
    const dx = xs[b] - ax;
    const dy = ys[b] - ay;
    const len2 = dx * dx + dy * dy;
    let worst = -1;
    let worstD2 = tol2;
    for (let i = a + 1; i < b; i++) {
      const px = xs[i] - ax;
      const py = ys[i] - ay;
      let d2;
      if (len2 === 0) d2 = px * px + py * py;
      else {
        const cross = px * dy - py * dx;
        d2 = (cross * cross) / len2;
      }
      if (d2 > worstD2) {
        worstD2 = d2;
        worst = i;
      }
    }
    if (worst >= 0) {
      keep[worst - from] = 1;
      stack.push([a, worst], [worst, b]);
    }
  }
  const out = [];
  for (let k = 0; k < n; k++) if (keep[k]) out.push(from + k);
  return out;
}

export class TrackDecimator {
  constructor(track) {
    this.track = track;
    this.reset();
  }

  reset() {
    this.chunks = []; // {endAbs, x: Float64Array, y: Float64Array}, oldest first
    this.doneAbs = null; // absolute index of the last sample covered by a chunk
    this.epoch = this.track.epoch;
    this.olderCache = null;
  }

  /** {older: {x, y}, tail: {x, y}}; `older` keeps its identity until a chunk is added or dropped. */
  update() {
    const t = this.track;
    if (t.epoch !== this.epoch) this.reset();
    const firstAbs = t.total - t.length;
    if (this.doneAbs === null || this.doneAbs < firstAbs) {
      // Start (or restart after the ring overtook us) at the oldest sample held.
      this.chunks = [];
      this.doneAbs = firstAbs;
      this.olderCache = null;
    }
    while (t.total - 1 - this.doneAbs >= CHUNK) {
      const from = this.doneAbs - firstAbs;
      const to = from + CHUNK;
      const a = t.arrays(from, to + 1);
      const idx = simplify(a.x, a.y, 0, CHUNK, TOLERANCE_M);
      // Each chunk starts where the last ended, so the first point is shared: skip it after the first.
      const skip = this.chunks.length > 0 ? 1 : 0;
      const x = new Float64Array(idx.length - skip);
      const y = new Float64Array(idx.length - skip);
      for (let k = skip; k < idx.length; k++) {
        x[k - skip] = a.x[idx[k]];
        y[k - skip] = a.y[idx[k]];
      }
      this.chunks.push({ endAbs: this.doneAbs + CHUNK, x, y });
      this.doneAbs += CHUNK;
      this.olderCache = null;
    }
    // Drop chunks whose samples the ring no longer holds.
    while (this.chunks.length && this.chunks[0].endAbs < firstAbs) {
      this.chunks.shift();
      this.olderCache = null;
    }
    if (!this.olderCache) {
      const n = this.chunks.reduce((s, c) => s + c.x.length, 0);
      const x = new Float64Array(n);
      const y = new Float64Array(n);
      let o = 0;
      for (const c of this.chunks) {
        x.set(c.x, o);
        y.set(c.y, o);
        o += c.x.length;
      }
      this.olderCache = { x, y };
    }
    const tail = t.arrays(Math.max(0, this.doneAbs - firstAbs));
    return { older: this.olderCache, tail };
  }
}

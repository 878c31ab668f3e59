// The AVK corridor as drawn: a band about the predicted path whose half width at each
// point is the corridor's (GET /predict `corridor`: left and right boundaries at the trajectory's
// points, `half_width_m` there). Joined point to point as they come, the boundaries of a tight
// turn (130–160°) drew jagged spikes: the offsets at the trajectory's few points (one every
// 6–10° of heading) turn their normals by that much at once, a short jitter segment at the start
// points a normal sideways, the half width varies from point to point by the noise of a few
// turns (0.8 m beside 1.8 m), and where it exceeds the turn's radius the inner boundary folds
// back across itself. So the band is drawn from the path sampled densely along its length:
// normals from the path's direction over a metre either side, the half width interpolated along
// the length and averaged over a short window (shrinking to the point itself at both ends, so the
// band still starts where the turn does), and the loops of a folded boundary cut out.

const STEP_M = 0.2; // sample spacing along the path (at most MAX_SAMPLES samples)
const MAX_SAMPLES = 600;
const DIRECTION_SPAN_M = 1.0; // the path's direction: the chord over this much either side
const WIDTH_SPAN_M = 1.5; // the half width: a triangular average over this much either side

function cumulative(xs, ys) {
  const s = [0];
  for (let i = 1; i < xs.length; i++) s.push(s[i - 1] + Math.hypot(xs[i] - xs[i - 1], ys[i] - ys[i - 1]));
  return s;
}

/** Linear interpolation of values v (at stations s, increasing) at station q. */
function interp(s, v, q) {
  if (q <= s[0]) return v[0];
  const n = s.length - 1;
  if (q >= s[n]) return v[n];
  let lo = 0;
  let hi = n;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (s[mid] <= q) lo = mid;
    else hi = mid;
  }
  const f = s[hi] > s[lo] ? (q - s[lo]) / (s[hi] - s[lo]) : 0;
  return v[lo] + f * (v[hi] - v[lo]);
}

function segmentsCross(a, b, c, d) {
  const o = (p, q, r) => (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
  const d1 = o(c, d, a);
  const d2 = o(c, d, b);
  const d3 = o(a, b, c);
  const d4 = o(a, b, d);
  if (!(d1 * d2 < 0 && d3 * d4 < 0)) return null;
  const t = d1 / (d1 - d2);
  return [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
}

/** The polyline with every loop cut out: where a later edge crosses an earlier one, the points
 *  between are dropped and the crossing joins the two. What is left never crosses itself. */
export function withoutLoops(points) {
  const out = [];
  for (const p of points) {
    out.push(p);
    // The newest edge against every earlier, non-adjacent one.
    for (let changed = true; changed && out.length >= 4; ) {
      changed = false;
      const b = out[out.length - 1];
      const a = out[out.length - 2];
      for (let i = 0; i + 1 < out.length - 2; i++) {
        const x = segmentsCross(out[i], out[i + 1], a, b);
        if (x) {
          out.splice(i + 1, out.length - (i + 1), x, b);
          changed = true;
          break;
        }
      }
    }
  }
  return out;
}

/** The band's two boundaries {left, right} ([[x, y], …], start to end) of a corridor about its
 *  path; null without one. The path is the middle of the server's left and right points (the
 *  trajectory), the half width its `half_width_m` (or half their distance). */
export function corridorBoundaries(corridor) {
  const L = corridor?.left ?? [];
  const R = corridor?.right ?? [];
  const n = Math.min(L.length, R.length);
  if (n < 2) return null;
  const px = [];
  const py = [];
  const pw = [];
  for (let i = 0; i < n; i++) {
    px.push((L[i][0] + R[i][0]) / 2);
    py.push((L[i][1] + R[i][1]) / 2);
    const w = corridor.half_width_m?.[i];
    pw.push(typeof w === 'number' && Number.isFinite(w) ? w : Math.hypot(L[i][0] - R[i][0], L[i][1] - R[i][1]) / 2);
  }
  const s = cumulative(px, py);
  const length = s[n - 1];
  if (!(length > 0)) return null;
  const step = Math.max(STEP_M, length / MAX_SAMPLES);
  const k = Math.ceil(length / step);
  const q = Array.from({ length: k + 1 }, (_, j) => Math.min(length, j * step));
  // The server's points themselves are kept among the samples, so nothing of the path is cut.
  for (const si of s) q.push(si);
  q.sort((a, b) => a - b);
  const qs = q.filter((v, j) => j === 0 || v - q[j - 1] > 1e-9);
  const at = (v) => [interp(s, px, v), interp(s, py, v)];
  const wRaw = qs.map((v) => interp(s, pw, v));
  const left = [];
  const right = [];
  for (let j = 0; j < qs.length; j++) {
    const v = qs[j];
    const span = Math.min(DIRECTION_SPAN_M, length / 2);
    const a = at(Math.max(0, v - span));
    const b = at(Math.min(length, v + span));
    const dl = Math.hypot(b[0] - a[0], b[1] - a[1]);
    if (!(dl > 0)) continue;
    const nx = -(b[1] - a[1]) / dl; // the left normal
    const ny = (b[0] - a[0]) / dl;
    // Triangular average of the half width, its window shrinking near both ends (a nanometre's
    // slack, so that rounding in the stations never drops one end of the window).
    const h = Math.min(WIDTH_SPAN_M, v, length - v);
    let sum = 0;
    let weight = 0;
    for (let i = j; i >= 0 && v - qs[i] <= h + 1e-9; i--) {
      const wt = 1 - (v - qs[i]) / (h + step);
      sum += wt * wRaw[i];
      weight += wt;
    }
    for (let i = j + 1; i < qs.length && qs[i] - v <= h + 1e-9; i++) {
      const wt = 1 - (qs[i] - v) / (h + step);
      sum += wt * wRaw[i];
      weight += wt;
    }
    const w = weight > 0 ? sum / weight : wRaw[j];
    const [x, y] = at(v);
    left.push([x + w * nx, y + w * ny]);
    right.push([x - w * nx, y - w * ny]);
  }
  if (left.length < 2) return null;
  return { left: withoutLoops(left), right: withoutLoops(right) };
}

/** The band as one closed ring: the left boundary, then the right one reversed, closed; [] without
 *  a corridor. */
export function corridorRing(corridor) {
  const b = corridorBoundaries(corridor);
  return b ? [...b.left, ...[...b.right].reverse(), b.left[0]] : [];
}

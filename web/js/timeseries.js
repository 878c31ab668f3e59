// Time series of the helm: heading and desired heading, speed and desired speed, yaw rate, on the
// station clock. Live fills a bounded ring from the stream (and from the stored track when a page
// opens mid-mission); Replay builds one from a stored mission. Both draw with drawSeries: three
// stacked plots on one time axis, turn starts marked, an optional cursor (Replay's "now").

import { C, baseLayout, axis, draw } from './plots.js';
import { headingDiff } from './format.js';
import { firstAtOrAfter } from './bisect.js';

/** The yaw rate is the heading's change over at least this long: at 10 Hz with a 1° compass a
 *  sample-to-sample difference would be ±14 °/s of noise, over 1 s it is ±1.4 °/s. */
export const YAW_RATE_SPAN_S = 1.0;

const FIELDS = ['t', 'heading', 'dheading', 'speed', 'dspeed', 'yawRate'];

/** A fixed-capacity ring of helm samples (oldest drop out), time-ordered. */
export class SeriesBuffer {
  constructor(capacity) {
    this.capacity = capacity;
    for (const f of FIELDS) this[f] = new Float64Array(capacity);
    this.start = 0;
    this.length = 0;
    this.version = 0;
  }

  clear() {
    this.start = 0;
    this.length = 0;
    this.version++;
  }

  at(k, f) {
    return this[f][(this.start + k) % this.capacity];
  }

  lastT() {
    return this.length ? this.at(this.length - 1, 't') : -Infinity;
  }

  /** Appends a sample (one older than the newest is ignored: the ring stays time-ordered). The
   *  yaw rate is computed here from the heading YAW_RATE_SPAN_S back. Missing desired values are
   *  NaN (drawn as gaps). */
  push(t, heading, dheading, speed, dspeed) {
    if (!(t > this.lastT())) return;
    let yawRate = NaN;
    for (let k = this.length - 1; k >= 0; k--) {
      const tk = this.at(k, 't');
      if (t - tk > 3 * YAW_RATE_SPAN_S) break; // a gap in the data: no rate across it
      if (t - tk >= YAW_RATE_SPAN_S) {
        yawRate = headingDiff(heading, this.at(k, 'heading')) / (t - tk);
        break;
      }
    }
    const i = (this.start + this.length) % this.capacity;
    const v = { t, heading, dheading: dheading ?? NaN, speed, dspeed: dspeed ?? NaN, yawRate };
    for (const f of FIELDS) this[f][i] = v[f];
    if (this.length < this.capacity) this.length++;
    else this.start = (this.start + 1) % this.capacity;
    this.version++;
  }

  /** Index of the first sample at or after t. */
  indexAtOrAfter(t) {
    return firstAtOrAfter(this.length, (i) => this.at(i, 't'), t);
  }

  /** Plain arrays of the samples with from ≤ t ≤ to; with maxPoints, every k-th sample so that
   *  at most about that many remain (the newest always kept). */
  window(from, to, maxPoints = Infinity) {
    const a = this.indexAtOrAfter(from);
    let b = this.indexAtOrAfter(to);
    while (b < this.length && this.at(b, 't') <= to) b++;
    const n = Math.max(0, b - a);
    const step = Math.max(1, Math.ceil(n / maxPoints));
    const idx = [];
    for (let k = b - 1; k >= a; k -= step) idx.push(k);
    idx.reverse();
    const out = {};
    for (const f of FIELDS) out[f] = idx.map((k) => this.at(k, f));
    return out;
  }
}

/** Merges stored rows (GET /missions/{id}/nav items, time-ordered) into a buffer: what it holds
 *  before the first row, the rows, then what it holds after the last one (the stream's samples
 *  since the page opened). */
export function mergeStoredRows(buf, rows) {
  if (!rows.length) return;
  const before = buf.window(-Infinity, rows[0].t_s - 1e-9);
  const after = buf.window(rows[rows.length - 1].t_s + 1e-9, Infinity);
  buf.clear();
  const again = (w) => {
    for (let k = 0; k < w.t.length; k++) buf.push(w.t[k], w.heading[k], w.dheading[k], w.speed[k], w.dspeed[k]);
  };
  again(before);
  for (const r of rows) buf.push(r.t_s, r.heading_deg, r.desired_heading_deg, r.speed_mps, r.desired_speed_mps);
  again(after);
}

/** Headings with a gap where they wrap through north, so a line does not cross the plot. */
export function unwrapGaps(t, h) {
  const x = [];
  const y = [];
  for (let k = 0; k < t.length; k++) {
    if (k > 0 && Number.isFinite(h[k]) && Number.isFinite(h[k - 1]) && Math.abs(h[k] - h[k - 1]) > 180) {
      x.push(NaN);
      y.push(NaN);
    }
    x.push(t[k]);
    y.push(h[k]);
  }
  return { x, y };
}

/** Draws the three panels of window w = {t, heading, …} over [from, to]. marks: [{t, label}]
 *  turn starts; cursor: a time to mark (Replay). */
export function drawSeries(el, w, { from, to, marks = [], cursor = null, xTitle = 'station clock (s)' }) {
  const h = unwrapGaps(w.t, w.heading);
  const dh = unwrapGaps(w.t, w.dheading);
  const line = (name, x, y, yaxis, color, extra = {}) => ({
    type: 'scatter',
    mode: 'lines',
    name,
    x,
    y,
    xaxis: 'x',
    yaxis,
    line: { color, width: 1.8, ...extra },
    connectgaps: false,
    hovertemplate: `%{y:.1f}<extra>${name}</extra>`,
  });
  const traces = [
    line('heading (°)', h.x, h.y, 'y', C.blue),
    line('desired heading (°)', dh.x, dh.y, 'y', C.vermillion, { dash: 'dash', shape: 'hv' }),
    line('speed (m/s)', w.t, w.speed, 'y2', C.green),
    line('desired speed (m/s)', w.t, w.dspeed, 'y2', C.orange, { dash: 'dash', shape: 'hv' }),
    line('yaw rate (°/s)', w.t, w.yawRate, 'y3', C.purple),
  ];
  const shapes = [];
  const annotations = [];
  for (const m of marks) {
    if (m.t < from || m.t > to) continue;
    shapes.push({ type: 'line', xref: 'x', yref: 'paper', x0: m.t, x1: m.t, y0: 0, y1: 1, line: { color: C.grey, width: 1, dash: 'dot' } });
    annotations.push({ x: m.t, xref: 'x', y: 1, yref: 'paper', yanchor: 'bottom', text: m.label, showarrow: false, font: { size: 10, color: '#555' } });
  }
  if (cursor !== null) shapes.push({ type: 'line', xref: 'x', yref: 'paper', x0: cursor, x1: cursor, y0: 0, y1: 1, line: { color: C.black, width: 1.5 } });
  const layout = {
    ...baseLayout({ margin: { l: 56, r: 10, t: 30, b: 86 } }),
    showlegend: true,
    // Below the axis title, not over it.
    legend: { orientation: 'h', x: 0, y: -0.2, yanchor: 'top', font: { size: 11 } },
    xaxis: axis(xTitle, { range: [from, to], anchor: 'y3' }),
    yaxis: axis('heading (°)', { domain: [0.7, 1], range: [0, 360], dtick: 90 }),
    yaxis2: axis('speed (m/s)', { domain: [0.37, 0.63], rangemode: 'tozero' }),
    yaxis3: axis('yaw rate (°/s)', { domain: [0, 0.3] }),
    shapes,
    annotations,
  };
  return draw(el, traces, layout);
}

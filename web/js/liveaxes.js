// The track plot's axes in the Live view: fitted to what the current mission draws, held while
// the operator's zoom or pan stands, and kept while what is fitted stays inside them.

import { equalAxes } from './plots.js';

let lastAxes = null; // the axes last given to Plotly
let operatorAxes = null; // the fit held while the operator's zoom or pan stands

let zoomBound = false;

/** Plotly keeps a zoom across redraws only while the figure's own range stays the same, and the
 *  fit moves with every sample: once the operator zooms or pans, the fit is held where it was (the
 *  operator's view wins) until Fit view. Redraws by react() fire no relayout event. */
export function axesToDraw(plotEl, traces) {
  if (!zoomBound && plotEl.on) {
    zoomBound = true;
    plotEl.on('plotly_relayout', (e) => {
      if (e && Object.keys(e).some((k) => k.startsWith('xaxis.') || k.startsWith('yaxis.'))) operatorAxes = lastAxes;
    });
  }
  lastAxes = operatorAxes || fittedAxes(traces);
  return lastAxes;
}

const FIT_MARGIN = 0.06; // of the larger span, each side
const FIT_MIN_SPAN_M = 20;

/** The equal axes of the track plot, fitted to `traces`: the current mission (its region, track,
 *  stored turns, the turn drawn with its predictions) and the vehicle. Plotly's own autorange took
 *  in every trace, the previous mission's track too, which shrank the current turn into a corner;
 *  that track is still drawn, faded, wherever it lies. The operator's zoom is kept (uirevision)
 *  until Fit view. */
function fittedAxes(traces) {
  let x0 = Infinity;
  let x1 = -Infinity;
  let y0 = Infinity;
  let y1 = -Infinity;
  for (const t of traces) {
    if (t.visible === false || t.visible === 'legendonly' || !t.x) continue;
    for (let i = 0; i < t.x.length; i++) {
      const x = t.x[i];
      const y = t.y[i];
      if (!Number.isFinite(x) || !Number.isFinite(y)) continue;
      if (x < x0) x0 = x;
      if (x > x1) x1 = x;
      if (y < y0) y0 = y;
      if (y > y1) y1 = y;
    }
  }
  const axes = equalAxes();
  if (!Number.isFinite(x0)) {
    lastFit = null;
    return axes;
  }
  const span = Math.max(x1 - x0, y1 - y0, FIT_MIN_SPAN_M);
  const pad = FIT_MARGIN * span;
  const cx = (x0 + x1) / 2;
  const cy = (y0 + y1) / 2;
  const half = (v0, v1) => Math.max((v1 - v0) / 2, FIT_MIN_SPAN_M / 2) + pad;
  let fit = { x: [cx - half(x0, x1), cx + half(x0, x1)], y: [cy - half(y0, y1), cy + half(y0, y1)] };
  const edge = pad / 3; // what is fitted stays this far inside a kept fit
  if (lastFit && holds(lastFit.x, x0 - edge, x1 + edge, fit.x) && holds(lastFit.y, y0 - edge, y1 + edge, fit.y)) fit = lastFit;
  lastFit = fit;
  axes.xaxis = { ...axes.xaxis, range: fit.x.slice(), autorange: false };
  axes.yaxis = { ...axes.yaxis, range: fit.y.slice(), autorange: false };
  return axes;
}

// The last fit is kept while what is fitted stays inside it and it is not much larger than a
// fresh fit: the heading ray swinging at the edge of the track moved the fit by a metre at every
// sample, and each move costs a full redraw of the plot (axes, labels, legend) instead of the
// traces alone.
const FIT_SLACK = 1.25;
let lastFit = null;

function holds(range, v0, v1, fresh) {
  return range[0] <= v0 && v1 <= range[1] && range[1] - range[0] <= FIT_SLACK * (fresh[1] - fresh[0]);
}

/** Fit view: the operator's zoom or pan is dropped and the next fit starts afresh. */
export function resetAxes() {
  operatorAxes = null;
  lastFit = null;
}

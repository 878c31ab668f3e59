// Plotly helpers: the palette, common layouts, equal-aspect axes for trajectories, a PNG button on
// every plot, and the registry of plots the Export view lists.

import { corridorRing } from './corridor.js';

/** Okabe-Ito: distinguishable with the common colour-vision deficiencies. */
export const C = {
  black: '#000000',
  orange: '#E69F00',
  sky: '#56B4E9',
  green: '#009E73',
  yellow: '#F0E442',
  blue: '#0072B2',
  vermillion: '#D55E00',
  purple: '#CC79A7',
  grey: '#8a8f98',
};

/** The vehicle as a long, narrow arrow whose tip is the vehicle's position, rotated by its heading
 *  (Plotly turns a marker clockwise from up, as headings turn from north, and the axes are
 *  equal). An equilateral triangle looks the same turned by 120 deg, so it could be read as
 *  pointing two other ways. */
export function vehicleMarker(nav, size) {
  return { symbol: 'arrow', size, angle: nav?.heading_deg ?? 0, color: C.yellow, line: { color: C.black, width: 2 } };
}

/** One colour per speed, in order; with a marker symbol each so the series differ without colour. */
export const SERIES = [C.blue, C.orange, C.green, C.vermillion, C.purple, C.sky, C.black, C.yellow];
export const SYMBOLS = ['circle', 'square', 'diamond', 'triangle-up', 'cross', 'x', 'star', 'hexagon'];

/** The prediction methods, drawn the same way in every view. */
export const METHOD_STYLE = {
  avk: { color: C.black, dash: 'solid', name: 'AVK (CKT)' },
  model: { color: C.purple, dash: 'dash', name: 'model' },
  instantaneous: { color: C.orange, dash: 'dot', name: 'instantaneous' },
};

const plots = new Map(); // element id -> {el, title, file}
let onRegistryChange = () => {};

export function onPlotsChanged(fn) {
  onRegistryChange = fn;
}

export function drawnPlots() {
  return [...plots.values()].filter((p) => p.drawn);
}

function Plotly() {
  // Loaded by a classic <script defer> before the modules run; looked up lazily all the same.
  if (!window.Plotly) throw new Error('Plotly did not load (web/node_modules missing? run scripts/web-deps)');
  return window.Plotly;
}

/** Wraps a .plot element in a frame with its title and a PNG button (once). */
export function framePlot(el) {
  if (plots.has(el.id)) return;
  const title = el.dataset.title || el.id;
  const file = el.dataset.file || el.id;
  const frame = document.createElement('div');
  frame.className = 'plot-frame';
  const tools = document.createElement('div');
  tools.className = 'plot-tools';
  const label = document.createElement('span');
  label.className = 'plot-title';
  label.textContent = title;
  const btn = document.createElement('button');
  btn.type = 'button';
  btn.className = 'png';
  btn.textContent = 'PNG';
  btn.setAttribute('aria-label', `Download “${title}” as PNG`);
  btn.addEventListener('click', () => downloadPng(el));
  const buttons = document.createElement('span');
  buttons.className = 'plot-buttons';
  buttons.append(btn);
  tools.append(label, buttons);
  el.replaceWith(frame);
  frame.append(tools, el);
  el.setAttribute('role', 'img');
  el.setAttribute('aria-label', title);
  plots.set(el.id, { el, title, file, drawn: false, button: btn });
  btn.disabled = true;
}

export function downloadPng(el) {
  const p = plots.get(el.id);
  if (!p?.drawn) return Promise.resolve();
  return Plotly().downloadImage(el, {
    format: 'png',
    filename: p.file,
    width: Math.max(600, el.clientWidth),
    height: Math.max(400, el.clientHeight),
    scale: 2,
  });
}

// The plots' own colours, light or dark (theme.js): the page's background and ink, the grid.
const PLOT_THEMES = {
  light: { ink: '#1b1f24', bg: '#ffffff', grid: '#e3e7ee', zero: '#b9c0ca', black: '#000000' },
  dark: { ink: '#d8dee6', bg: '#1b2129', grid: '#333c48', zero: '#566273', black: '#e8ecf1' },
};
let plotTheme = PLOT_THEMES.light;

/** Switches the plots to a theme: new figures take its colours, drawn ones are relaid out, and
 *  what is drawn in "black" (the region, AVK) becomes the theme's ink so it stays visible. */
export function applyPlotTheme(name) {
  plotTheme = PLOT_THEMES[name] ?? PLOT_THEMES.light;
  const before = C.black;
  C.black = plotTheme.black;
  METHOD_STYLE.avk.color = plotTheme.black;
  const i = SERIES.indexOf(before);
  if (i >= 0) SERIES[i] = plotTheme.black;
  if (!window.Plotly) return;
  for (const p of plots.values()) {
    const fl = p.el._fullLayout;
    if (!p.drawn || !fl) continue;
    const update = { paper_bgcolor: plotTheme.bg, plot_bgcolor: plotTheme.bg, 'font.color': plotTheme.ink };
    for (const k of Object.keys(fl)) {
      if (/^[xy]axis\d*$/.test(k)) {
        update[`${k}.gridcolor`] = plotTheme.grid;
        update[`${k}.zerolinecolor`] = plotTheme.zero;
      }
    }
    window.Plotly.relayout(p.el, update).catch(() => {});
  }
}

export function baseLayout(extra = {}) {
  return {
    margin: { l: 58, r: 14, t: 34, b: 48 },
    font: { family: 'system-ui, sans-serif', size: 12, color: plotTheme.ink },
    paper_bgcolor: plotTheme.bg,
    plot_bgcolor: plotTheme.bg,
    // Above the plot: below it the legend collides with the x-axis title.
    legend: { orientation: 'h', x: 0, y: 1.01, yanchor: 'bottom' },
    hovermode: 'closest',
    ...extra,
  };
}

/** An axis with its title. Tick labels are never hidden for overflowing the plot (`allow`):
 *  Plotly's default measures every label's box at every redraw to decide, a forced layout that
 *  cost the Live view a fifth of each update, and with automargin no label overflows anyway. */
export function axis(title, extra = {}) {
  return { title: { text: title }, gridcolor: plotTheme.grid, zerolinecolor: plotTheme.zero, automargin: true, ticklabeloverflow: 'allow', ...extra };
}

/** Metres on both axes, one metre the same length on each (trajectories are never distorted). */
export function equalAxes(xTitle = 'x east (m)', yTitle = 'y north (m)') {
  return {
    xaxis: axis(xTitle, { constrain: 'domain' }),
    yaxis: axis(yTitle, { scaleanchor: 'x', scaleratio: 1, constrain: 'domain' }),
  };
}

const CONFIG = {
  responsive: true,
  displaylogo: false,
  modeBarButtonsToRemove: ['lasso2d', 'select2d'],
};

// What each figure drawn with `tracesOnly` looked like apart from its data: element -> {layout,
// traces, config} as JSON.
const shapes = new WeakMap();
const DATA_KEYS = new Set(['x', 'y', 'angle']);
const withoutData = (k, v) => (DATA_KEYS.has(k) ? undefined : v);

let angleAnimates = false;
/** Plotly redraws only the traces (its animation path) when every change is "animatable": x and
 *  y are, a marker's angle is not, so each new heading of the vehicle would cost the whole figure
 *  again. The angle is drawn by the same per-point styling either way, so it is declared
 *  animatable here, once. */
function markerAngleAnimates(el) {
  if (!angleAnimates) {
    const trace = el._fullData?.find((t) => t.type === 'scatter');
    const attr = trace && Plotly().PlotSchema?.getTraceValObject?.(trace, ['marker', 'angle']);
    if (attr) {
      attr.anim = true;
      angleAnimates = true;
    }
  }
  return angleAnimates;
}

/** Whether only the data (x, y, a marker's angle) changed since the last draw of `el`, on axes
 *  with fixed ranges: then nothing but the traces needs drawing again. */
function onlyDataChanged(el, traces, layout, config) {
  const now = { layout: JSON.stringify(layout), traces: traces.map((t) => JSON.stringify(t, withoutData)), config: JSON.stringify(config) };
  const before = shapes.get(el);
  shapes.set(el, now);
  if (!before || !el._fullLayout || !markerAngleAnimates(el)) return false;
  const axes = Object.keys(layout).filter((k) => /^[xy]axis\d*$/.test(k));
  if (axes.length === 0 || !axes.every((k) => layout[k].autorange === false)) return false;
  return before.layout === now.layout && before.config === now.config && before.traces.length === now.traces.length && before.traces.every((t, i) => t === now.traces[i]);
}

/** Draws (or redraws in place: Plotly.react diffs) a figure into a framed plot element. With
 *  `tracesOnly`, a redraw where only the traces' data changed (a figure updated at 10 Hz) goes
 *  through Plotly's transition path with no duration: the traces are drawn again, the axes, tick
 *  labels, legend and margins (most of a full redraw) are left as they are. Every array in such
 *  a figure other than x and y must keep its identity between draws: Plotly takes a new array as
 *  a change that needs a full redraw. */
export function draw(el, traces, layout, config = {}, { tracesOnly = false } = {}) {
  if (el.classList.contains('plot-empty')) {
    el.classList.remove('plot-empty');
    el.textContent = '';
  }
  const p = plots.get(el.id);
  const fast = tracesOnly && onlyDataChanged(el, traces, layout, config);
  const res = Plotly().react(el, traces, fast ? { ...layout, transition: { duration: 0 } } : layout, { ...CONFIG, ...config });
  if (p && !p.drawn) {
    p.drawn = true;
    p.button.disabled = false;
    onRegistryChange();
  }
  return res;
}

/** Replaces a plot with a short message (no data yet, an error). */
export function showEmpty(el, message) {
  if (window.Plotly && el._fullLayout) window.Plotly.purge(el);
  shapes.delete(el);
  el.classList.add('plot-empty');
  el.textContent = message;
  const p = plots.get(el.id);
  if (p?.drawn) {
    p.drawn = false;
    p.button.disabled = true;
    onRegistryChange();
  }
}

/** Plots drawn while their view was hidden have the wrong size: fit them once shown. */
export function resizeWithin(container) {
  if (!window.Plotly) return;
  for (const el of container.querySelectorAll('.plot')) {
    if (el._fullLayout) window.Plotly.Plots.resize(el);
  }
}

/** Creates a framed plot element on the fly (the Compare view has one per speed). */
export function makePlot(parent, id, title, file) {
  const el = document.createElement('div');
  el.id = id;
  el.className = 'plot';
  el.dataset.title = title;
  el.dataset.file = file;
  const panel = document.createElement('div');
  panel.className = 'panel';
  panel.append(el);
  parent.append(panel);
  framePlot(el);
  return el;
}

export function forgetPlot(id) {
  if (plots.delete(id)) onRegistryChange();
}

export function onPlotClick(el, fn) {
  if (el.dataset.clickBound) return;
  el.dataset.clickBound = '1';
  el.on?.('plotly_click', fn);
}

/** A colour with an alpha: '#rrggbb' -> 'rgba(r, g, b, a)'. */
export function withAlpha(hex, alpha) {
  const n = parseInt(hex.slice(1), 16);
  return `rgba(${(n >> 16) & 255}, ${(n >> 8) & 255}, ${n & 255}, ${alpha})`;
}

/** The legend name of an AVK corridor: "AVK 90 % corridor (7 turns)". */
export function corridorName(corridor) {
  const pct = Math.round((corridor?.share ?? 0.9) * 100);
  const n = corridor?.n_turns;
  return `AVK ${pct} % corridor${typeof n === 'number' ? ` (${n} turn${n === 1 ? '' : 's'})` : ''}`;
}

const rings = new WeakMap(); // corridor -> {x, y}: a band is worked out once, not at every frame

/** The band of an AVK prediction's corridor (GET /predict: `corridor.left`, `corridor.right`, in
 *  the frame of the prediction's trajectory) as one filled polygon: the left boundary, then the
 *  right one reversed, closed, smoothed along the path and without folds (corridor.js). An empty
 *  trace (nothing drawn, no legend entry) when there is no corridor, so a figure keeps the same
 *  traces in the same order either way. */
export function corridorTrace(corridor, extra = {}) {
  const has = (corridor?.left?.length ?? 0) >= 2 && (corridor?.right?.length ?? 0) >= 2;
  let xy = has ? rings.get(corridor) : { x: [], y: [] };
  if (!xy) {
    const ring = corridorRing(corridor);
    xy = { x: ring.map((p) => p[0]), y: ring.map((p) => p[1]) };
    rings.set(corridor, xy);
  }
  return {
    type: 'scatter',
    mode: 'lines',
    name: has ? corridorName(corridor) : 'AVK corridor',
    x: xy.x,
    y: xy.y,
    fill: 'toself',
    fillcolor: withAlpha(METHOD_STYLE.avk.color, 0.16),
    line: { color: withAlpha(METHOD_STYLE.avk.color, 0.35), width: 0.5 },
    hoverinfo: 'name',
    showlegend: has,
    visible: has,
    ...extra,
  };
}

/** A scale bar over an equal-axes plot (metres): a round length (1, 2 or 5 × 10^k m) about a
 *  fifth of the plot's width, bottom left of the plotting area, kept right as the operator zooms.
 *  Drawn as HTML over the plot, not in the figure: it must not move with the data. */
export function updateScaleBar(el, lengthFor) {
  const xa = el._fullLayout?.xaxis;
  if (!xa || !xa.range || !(xa._length > 0)) return;
  let bar = el.parentElement.querySelector('.scale-bar');
  if (!bar) {
    bar = document.createElement('div');
    bar.className = 'scale-bar';
    bar.setAttribute('aria-hidden', 'true');
    bar.append(document.createElement('span'), document.createElement('span'));
    bar.firstChild.className = 'scale-bar-line';
    bar.lastChild.className = 'scale-bar-label';
    el.parentElement.append(bar);
    el.on?.('plotly_relayout', () => updateScaleBar(el, lengthFor));
  }
  const metresPerPx = Math.abs(xa.range[1] - xa.range[0]) / xa._length;
  const m = lengthFor(metresPerPx * xa._length * 0.2);
  if (!m) return;
  const px = m / metresPerPx;
  const ya = el._fullLayout.yaxis;
  bar.style.left = `${xa._offset + 10}px`;
  bar.style.top = `${el.offsetTop + ya._offset + ya._length - 30}px`;
  bar.firstChild.style.width = `${px}px`;
  bar.lastChild.textContent = m >= 1000 ? `${m / 1000} km` : `${m} m`;
  bar.dataset.metres = String(m);
  bar.dataset.px = String(px);
}

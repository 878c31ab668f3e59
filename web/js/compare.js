// The Compare view. By default the fair comparison (GET /compare's `predictive` part): every
// method scored on held-out turns (AVK leave-one-out), per speed the mean path distance at equal
// arc length (m) against the heading change, error bars ± 1 sd over the cell's held-out turns. A
// control switches to the thesis' y(x) MSE on the same held-out turns, or to the thesis'
// in-sample MSE (the old `cells`: Figures 5-8, A-6, A-7, log axis). The medians, the AVK
// corridor's measured coverage and the table beneath follow the chosen metric (the same numbers as
// `avk compare` and docs/results.md).

import { state, on } from './state.js';
import { getJson } from './api.js';
import { METHOD_STYLE, SYMBOLS, baseLayout, axis, draw, makePlot, forgetPlot } from './plots.js';
import { el, fillTable, num, setStatus } from './format.js';
import { refreshTurnCount } from './sync.js';

const $ = (id) => document.getElementById(id);
const METHODS = ['avk', 'model', 'instantaneous'];

/** The metrics the control offers: where each reads its numbers and how it is drawn. */
export const METRICS = {
  path_m: {
    title: (s) => `Mean path distance on held-out turns at ${s} m/s`,
    file: (s) => `avk-compare-${s}mps-path`,
    yTitle: 'mean distance at equal arc length (m), ± 1 sd',
    log: false,
    unit: 'm',
    median: 'Median path distance (held out)',
    fmt: (v) => num(v, 2),
  },
  yx_mse_m2: {
    title: (s) => `y(x) MSE on held-out turns at ${s} m/s`,
    file: (s) => `avk-compare-${s}mps-yx-mse`,
    yTitle: 'y(x) MSE (m², log), ± 1 sd',
    log: true,
    unit: 'm²',
    median: 'Median y(x) MSE (held out)',
    fmt: fmtSci,
  },
  in_sample: {
    title: (s) => `MSE per heading change at ${s} m/s (thesis, in sample)`,
    file: (s) => `avk-compare-${s}mps`,
    yTitle: 'MSE (m², log)',
    log: true,
    unit: 'm²',
    median: 'Median MSE (thesis, in sample)',
    fmt: fmtSci,
  },
};

/** What each metric scores against, said in the view: an in-sample number on a
 *  repeatable vehicle is near zero for AVK by construction, not because AVK is right. */
export const BASIS = {
  held_out:
    'Scored on turns each method was not built from: AVK predicts each turn from the mean of its cell’s other turns (leave-one-out); the model is identified on other data (persistent excitation) and flown from a steady course; the instantaneous turn is the ray along the goal heading. Points are the mean over a cell’s held-out turns, bars ± 1 sd, n per cell in the table.',
  in_sample:
    'In sample, as in the thesis: AVK is graded against the mean of the very turns it was built from, so on a vehicle that repeats its turns its error is near zero by construction. Use a held-out metric to compare methods.',
};

/** The lowest value a log axis shows (m²): the variance of a GNSS fix (σ 0.1 m, a good RTK-less
 *  receiver is worse). Errors below it are below what the measurement can tell apart; they are
 *  drawn on the floor, hollow, and named in the hover, rather than stretching the axis to 1e-30. */
export const LOG_FLOOR_M2 = 0.01;

let visible = false;
let plotKey = '';
let plotIds = [];
let last = null; // the last GET /compare answer: a metric change redraws it without a request

export function initCompare() {
  $('cmp-refresh').addEventListener('click', load);
  $('cmp-model').addEventListener('change', load);
  $('cmp-metric').addEventListener('change', () => {
    if (last) render(last);
    else load();
  });
  on('models', renderModelChoice);
  on('turns-changed', () => {
    if (visible) load();
  });
  on('vehicle-changed', () => {
    last = null; // another vehicle's comparison: read again at the catch-up's end (below)
  });
  // A page opened at #compare shows the view before it knows the vehicle: load once it does.
  on('synced', () => {
    if (visible && !last) load();
  });
}

export function showCompare(isVisible) {
  visible = isVisible;
  if (visible) load();
}

function renderModelChoice() {
  const sel = $('cmp-model');
  const keep = sel.value;
  sel.replaceChildren(
    el('option', { value: '', text: 'latest' }),
    ...[...state.models].sort((a, b) => b.id - a.id).map((m) => el('option', { value: m.id, text: `model ${m.id} (${m.form}, ${m.history} samples)` })),
  );
  sel.value = keep;
}

function fmtSci(v) {
  return typeof v === 'number' && Number.isFinite(v) ? v.toPrecision(3) : '–';
}

function metricKey() {
  const k = $('cmp-metric').value;
  return k in METRICS ? k : 'path_m';
}

export async function load() {
  const status = $('cmp-status');
  const plots = $('cmp-plots');
  if (!state.vehicleId) return;
  await refreshTurnCount().catch(() => {});
  if (state.okTurns === 0) {
    setStatus(status, 'No ok turns yet: run a mission first.');
    last = null;
    clearPlots(plots);
    $('cmp-table').replaceChildren();
    $('cmp-median').textContent = '';
    $('cmp-corridor').textContent = '';
    return;
  }
  setStatus(status, 'Loading…');
  try {
    const model = $('cmp-model').value;
    const cmp = await getJson(`/vehicles/${encodeURIComponent(state.vehicleId)}/compare`, { model: model || undefined });
    setStatus(status, cmp.model_id ? `Model ${cmp.model_id}.` : 'No model stored: AVK and instantaneous only.');
    last = cmp;
    render(cmp);
  } catch (e) {
    setStatus(status, e.message, 'error');
  }
}

/** The rows of the chosen metric: {speed_mps, dheading_deg, n_turns, value(m) -> {mean, sd}|null}. */
function rowsOf(cmp, key) {
  if (key === 'in_sample') {
    return (cmp.cells ?? []).map((c) => ({
      speed_mps: c.speed_mps,
      dheading_deg: c.dheading_deg,
      n_turns: c.n_turns,
      value: (m) => (typeof c[m]?.mse_m2 === 'number' ? { mean: c[m].mse_m2, sd: null } : null),
    }));
  }
  return (cmp.predictive?.cells ?? []).map((c) => ({
    speed_mps: c.speed_mps,
    dheading_deg: c.dheading_deg,
    n_turns: c.n_turns,
    value: (m) => (typeof c[m]?.[key]?.mean === 'number' ? c[m][key] : null),
  }));
}

function medianOf(cmp, key) {
  if (key === 'in_sample') return cmp.median_mse_m2 ?? {};
  return cmp.predictive?.[key === 'path_m' ? 'median_path_m' : 'median_yx_mse_m2'] ?? {};
}

function render(cmp) {
  const key = metricKey();
  const metric = METRICS[key];
  const plots = $('cmp-plots');
  const med = medianOf(cmp, key);
  $('cmp-median').textContent = `${metric.median}: ${METHODS.map((m) => `${METHOD_STYLE[m].name} ${typeof med[m] === 'number' ? `${metric.fmt(med[m])} ${metric.unit}` : 'none'}`).join(' · ')}`;
  $('cmp-corridor').textContent = corridorLine(cmp.predictive?.corridor);
  $('cmp-basis').textContent = BASIS[key === 'in_sample' ? 'in_sample' : 'held_out'];
  if (key !== 'in_sample' && !cmp.predictive) {
    setStatus($('cmp-status'), 'This server sends no held-out (predictive) scoring: choose the thesis in-sample MSE.', 'error');
  }
  renderPlots(plots, rowsOf(cmp, key), key);
  if (key === 'in_sample') renderInSampleTable(cmp);
  else renderPredictiveTable(cmp);
}

/** "90 % corridor holds 88.1 % of held-out points over cells with ≥ 5 turns; 0 cells below 70 %". */
export function corridorLine(c) {
  if (!c) return '';
  const nominal = `${Math.round((c.share_nominal ?? 0.9) * 100)} %`;
  const minTurns = c.min_turns ?? 5;
  if (!c.total || typeof c.share !== 'number') {
    return `${nominal} corridor: no cell with ≥ ${minTurns} turns yet, so its coverage of held-out turns is not measured.`;
  }
  const below = c.cells_below_70_pct ?? 0;
  return `${nominal} corridor holds ${num(c.share * 100, 1)} % of held-out points over cells with ≥ ${minTurns} turns (${c.inside} of ${c.total}); ${below} cell${below === 1 ? '' : 's'} below 70 %.`;
}

function clearPlots(plots) {
  plotIds.forEach(forgetPlot);
  plotIds = [];
  plotKey = '';
  plots.replaceChildren();
}

function renderPlots(plots, rows, key) {
  const metric = METRICS[key];
  const speeds = [...new Set(rows.map((c) => c.speed_mps))].sort((a, b) => a - b);
  const wanted = speeds.map((s) => `cmp-plot-${String(s).replace('.', '_')}`);
  // A plot's title and PNG file name are set when it is made: a new metric makes them again.
  const wantedKey = `${key}|${wanted.join()}`;
  if (wantedKey !== plotKey) {
    clearPlots(plots);
    speeds.forEach((s, i) => {
      const p = makePlot(plots, wanted[i], metric.title(s), metric.file(s));
      p.dataset.metric = key;
    });
    plotIds = wanted;
    plotKey = wantedKey;
  }
  speeds.forEach((s, i) => {
    const cells = rows.filter((c) => c.speed_mps === s).sort((a, b) => a.dheading_deg - b.dheading_deg);
    const traces = METHODS.map((m, k) => {
      const pts = cells.filter((c) => {
        const v = c.value(m);
        return v && Number.isFinite(v.mean) && v.mean >= 0;
      });
      const vals = pts.map((c) => c.value(m));
      const st = METHOD_STYLE[m];
      const sds = vals.map((v) => (typeof v.sd === 'number' && Number.isFinite(v.sd) ? v.sd : 0));
      // On a log axis a value below the floor sits on it, hollow; the hover says the real value.
      const floored = vals.map((v) => metric.log && v.mean < LOG_FLOOR_M2);
      const shown = vals.map((v, j) => (floored[j] ? LOG_FLOOR_M2 : v.mean));
      const trace = {
        type: 'scatter',
        mode: 'lines+markers',
        name: st.name,
        x: pts.map((c) => c.dheading_deg),
        y: shown,
        customdata: pts.map((c, j) => [c.n_turns, sds[j], floored[j] ? ` (below the ${LOG_FLOOR_M2} m² floor)` : '', vals[j].mean]),
        line: { color: st.color, dash: st.dash, width: 2 },
        marker: { color: st.color, symbol: pts.map((_, j) => (floored[j] ? `${SYMBOLS[k]}-open` : SYMBOLS[k])), size: 8 },
        hovertemplate:
          key === 'in_sample'
            ? `${st.name}, Δψ %{x}°: %{customdata[3]:.3g} m²%{customdata[2]}<extra></extra>`
            : `${st.name}, Δψ %{x}°: %{customdata[3]:.3g} ± %{customdata[1]:.2g} ${metric.unit} (n %{customdata[0]})%{customdata[2]}<extra></extra>`,
      };
      if (key !== 'in_sample') {
        // On the log axis a bar cannot reach below the floor: its lower half stops there.
        const minus = metric.log ? sds.map((sd, j) => Math.max(0, Math.min(sd, shown[j] - LOG_FLOOR_M2))) : sds;
        trace.error_y = { type: 'data', symmetric: false, array: sds, arrayminus: minus, visible: true, color: st.color, thickness: 1.2, width: 4 };
      }
      return trace;
    });
    draw($(wanted[i]), traces, {
      ...baseLayout(),
      xaxis: axis('heading change Δψ (°)', { range: [0, 185], dtick: 20 }),
      yaxis: axis(metric.yTitle, metric.log ? logAxis(traces) : { rangemode: 'tozero' }),
      showlegend: true,
    });
  });
}

/** A log axis from the floor (GNSS noise) to a little above the largest value drawn. */
function logAxis(traces) {
  let top = LOG_FLOOR_M2 * 10;
  for (const t of traces)
    for (let j = 0; j < t.y.length; j++) top = Math.max(top, t.y[j] + (t.error_y?.array?.[j] ?? 0));
  return { type: 'log', exponentformat: 'power', range: [Math.log10(LOG_FLOOR_M2) - 0.05, Math.log10(top) + 0.15] };
}

const sorted = (cells) => [...(cells ?? [])].sort((a, b) => a.speed_mps - b.speed_mps || a.dheading_deg - b.dheading_deg);

function msd(v, fmt) {
  if (!v || typeof v.mean !== 'number') return '–';
  return typeof v.sd === 'number' ? `${fmt(v.mean)} ± ${fmt(v.sd)}` : fmt(v.mean);
}

function renderPredictiveTable(cmp) {
  const p2 = (v) => num(v, 2);
  const cols = [
    { key: 'speed_mps', label: 'speed (m/s)' },
    { key: 'dheading_deg', label: 'Δψ (°)' },
    { key: 'n_turns', label: 'n' },
    { key: 'span_m', label: 'span (m)', fmt: (v) => num(v, 1) },
    ...METHODS.map((m) => ({ get: (c) => c[m]?.path_m, label: `${m} path (m)`, fmt: (v) => msd(v, p2) })),
    ...METHODS.map((m) => ({ get: (c) => c[m]?.yx_mse_m2, label: `${m} y(x) MSE (m²)`, fmt: (v) => msd(v, fmtSci) })),
    {
      get: (c) => c.corridor_coverage,
      label: `AVK ${Math.round((cmp.predictive?.corridor?.share_nominal ?? 0.9) * 100)} % corridor holds`,
      fmt: (v) => (v && typeof v.share === 'number' ? `${num(v.share * 100, 0)} % (${v.inside}/${v.total})` : '–'),
    },
  ];
  fillTable($('cmp-table'), cols, sorted(cmp.predictive?.cells));
  $('cmp-table').dataset.metric = 'predictive';
}

function renderInSampleTable(cmp) {
  const cols = [
    { key: 'speed_mps', label: 'speed (m/s)' },
    { key: 'dheading_deg', label: 'Δψ (°)' },
    { key: 'n_turns', label: 'n' },
    { key: 'outliers', label: 'outliers' },
    ...METHODS.map((m) => ({ get: (c) => c[m]?.mse_m2, label: `${m} MSE (m²)`, fmt: fmtSci })),
    ...['avk', 'model'].map((m) => ({ get: (c) => c[m]?.improvement_pct, label: `${m} improvement (%)`, fmt: (v) => num(v, 1) })),
    ...METHODS.map((m) => ({ get: (c) => c[m]?.advance_error_m, label: `${m} advance err (m)`, fmt: (v) => num(v, 2) })),
    ...METHODS.map((m) => ({ get: (c) => c[m]?.transfer_error_m, label: `${m} transfer err (m)`, fmt: (v) => num(v, 2) })),
  ];
  fillTable($('cmp-table'), cols, sorted(cmp.cells));
  $('cmp-table').dataset.metric = 'in_sample';
}

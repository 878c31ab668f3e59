// The Compare view: the mean squared error of each prediction method per heading change, one
// plot per speed on a log axis (thesis Figures 5-8, A-6, A-7), and the comparison table beneath
// (the same numbers as `avk compare` and docs/results.md).

import { state, on } from './state.js';
import { getJson } from './api.js';
import { METHOD_STYLE, SYMBOLS, baseLayout, axis, draw, makePlot, forgetPlot } from './plots.js';
import { el, fillTable, num, setStatus } from './format.js';
import { refreshTurnCount } from './sync.js';

const $ = (id) => document.getElementById(id);
const METHODS = ['avk', 'model', 'instantaneous'];
let visible = false;
let plotIds = [];

export function initCompare() {
  $('cmp-refresh').addEventListener('click', load);
  $('cmp-model').addEventListener('change', load);
  on('models', renderModelChoice);
  on('turns-changed', () => {
    if (visible) load();
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

export async function load() {
  const status = $('cmp-status');
  const plots = $('cmp-plots');
  if (!state.vehicleId) return;
  await refreshTurnCount().catch(() => {});
  if (state.okTurns === 0) {
    setStatus(status, 'No ok turns yet: run a mission first.');
    clearPlots(plots);
    $('cmp-table').replaceChildren();
    $('cmp-median').textContent = '';
    return;
  }
  setStatus(status, 'Loading…');
  try {
    const model = $('cmp-model').value;
    const cmp = await getJson(`/vehicles/${encodeURIComponent(state.vehicleId)}/compare`, { model: model || undefined });
    setStatus(status, cmp.model_id ? `Model ${cmp.model_id}.` : 'No model stored: AVK and instantaneous only.');
    const med = cmp.median_mse_m2 ?? {};
    $('cmp-median').textContent = `Median MSE: ${METHODS.map((m) => `${METHOD_STYLE[m].name} ${typeof med[m] === 'number' ? `${fmtSci(med[m])} m²` : 'none'}`).join(' · ')}`;
    renderPlots(plots, cmp);
    renderTable(cmp);
  } catch (e) {
    setStatus(status, e.message, 'error');
  }
}

function clearPlots(plots) {
  plotIds.forEach(forgetPlot);
  plotIds = [];
  plots.replaceChildren();
}

function renderPlots(plots, cmp) {
  const speeds = [...new Set(cmp.cells.map((c) => c.speed_mps))].sort((a, b) => a - b);
  const wanted = speeds.map((s) => `cmp-plot-${String(s).replace('.', '_')}`);
  if (wanted.join() !== plotIds.join()) {
    clearPlots(plots);
    speeds.forEach((s, i) => makePlot(plots, wanted[i], `MSE per heading change at ${s} m/s`, `avk-compare-${s}mps`));
    plotIds = wanted;
  }
  speeds.forEach((s, i) => {
    const cells = cmp.cells.filter((c) => c.speed_mps === s).sort((a, b) => a.dheading_deg - b.dheading_deg);
    const traces = METHODS.map((m, k) => {
      const pts = cells.filter((c) => typeof c[m]?.mse_m2 === 'number' && c[m].mse_m2 > 0);
      const st = METHOD_STYLE[m];
      return {
        type: 'scatter',
        mode: 'lines+markers',
        name: st.name,
        x: pts.map((c) => c.dheading_deg),
        y: pts.map((c) => c[m].mse_m2),
        line: { color: st.color, dash: st.dash, width: 2 },
        marker: { color: st.color, symbol: SYMBOLS[k], size: 8 },
        hovertemplate: `${st.name}, Δψ %{x}°: %{y:.3g} m²<extra></extra>`,
      };
    });
    draw($(wanted[i]), traces, {
      ...baseLayout(),
      xaxis: axis('heading change Δψ (°)', { range: [0, 185], dtick: 20 }),
      yaxis: axis('MSE (m², log)', { type: 'log', exponentformat: 'power' }),
      showlegend: true,
    });
  });
}

function renderTable(cmp) {
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
  const rows = [...cmp.cells].sort((a, b) => a.speed_mps - b.speed_mps || a.dheading_deg - b.dheading_deg);
  fillTable($('cmp-table'), cols, rows);
}

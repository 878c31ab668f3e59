// The CKT view: the table's grid as a heat map (n, AVK error, advance, transfer) with an accessible
// table of the same cells; a chosen cell shows its turns (blue), the mean turn (red), the fit, the
// CKT's piecewise-linear trajectory with the AVK prediction's corridor (the band that holds 90 %
// of the cell's turns), and the model and instantaneous predictions (thesis Figures 5-6, 5-7);
// advance and transfer against the heading change per speed with ±1 sd error bars
// (Figures 5-4, 5-5).

import { state, on } from './state.js';
import { getJson } from './api.js';
import { C, SERIES, SYMBOLS, METHOD_STYLE, baseLayout, axis, equalAxes, draw, showEmpty, onPlotClick, corridorTrace } from './plots.js';
import { el, meanSd, setStatus } from './format.js';
import { refreshTurnCount } from './sync.js';

const $ = (id) => document.getElementById(id);
const METRICS = {
  n: { label: 'n turns', get: (c) => c.n_turns, fmt: (v) => String(v) },
  avk: { label: 'AVK error (m²)', get: (c) => c.avk_error_m2, fmt: (v) => v.toPrecision(2) },
  advance: { label: 'advance (m)', get: (c) => c.advance_m?.mean, fmt: (v) => v.toFixed(1) },
  transfer: { label: 'transfer (m)', get: (c) => c.transfer_m?.mean, fmt: (v) => v.toFixed(1) },
};

let visible = false;
let table = null; // GET /vehicles/{vid}/ckt
let chosen = null; // {speed, dheading}
let loading = null;

export function initCkt() {
  showEmpty($('ckt-cell-plot'), 'No cell chosen.');
  $('ckt-metric').addEventListener('change', renderGrid);
  $('ckt-refresh').addEventListener('click', () => load());
  // New turns change the table: reload it if it is on screen (sync.js debounces the event).
  on('turns-changed', () => {
    if (visible) load();
  });
  on('restart', () => {
    table = null;
  });
  // Another vehicle: its own table, read at the catch-up's end (below).
  on('vehicle-changed', () => {
    table = null;
    chosen = null;
  });
  // A page opened at #ckt shows the view before it knows the vehicle: load once it does.
  on('synced', () => {
    if (visible && !table) load();
  });
}

export function showCkt(isVisible) {
  visible = isVisible;
  if (visible) load();
}

export async function load() {
  if (loading) return loading;
  loading = (async () => {
    const status = $('ckt-status');
    if (!state.vehicleId) {
      setStatus(status, 'No vehicle.');
      return;
    }
    try {
      await refreshTurnCount();
      if (state.okTurns === 0 && !table) {
        // Without stored turns the table is a 404 (unless a CKT was imported: Refresh asks anyway).
        setStatus(status, 'No turns yet: run a mission.');
        emptyAll('No turns yet.');
        return;
      }
      setStatus(status, 'Loading…');
      table = await getJson(`/vehicles/${encodeURIComponent(state.vehicleId)}/ckt`);
      const nTurns = table.cells.reduce((s, c) => s + (c.n_turns || 0), 0);
      setStatus(status, `${state.vehicleId}: ${table.speeds_mps.length} speeds × ${table.dheadings_deg.length} heading changes, ${nTurns} turns.`);
      renderGrid();
      renderAdvanceTransfer();
      // Open the chosen cell again, or else the one with the most turns: never an empty panel.
      const pick = chosen ?? busiestCell();
      if (pick) await openCell(pick.speed, pick.dheading);
    } catch (e) {
      setStatus(status, e.message, 'error');
      emptyAll(e.message);
    }
  })().finally(() => {
    loading = null;
  });
  return loading;
}

function emptyAll(msg) {
  showEmpty($('ckt-heatmap'), msg);
  showEmpty($('ckt-advance'), msg);
  showEmpty($('ckt-transfer'), msg);
  if (!chosen) showEmpty($('ckt-cell-plot'), 'No cell chosen.');
  $('ckt-table').replaceChildren();
}

function busiestCell() {
  const best = [...table.cells].sort((a, b) => (b.n_turns || 0) - (a.n_turns || 0))[0];
  return best?.n_turns ? { speed: best.speed_mps, dheading: best.dheading_deg } : null;
}

function cellAt(speed, dheading) {
  return table?.cells.find((c) => c.speed_mps === speed && c.dheading_deg === dheading) ?? null;
}

/** Colour-bar ticks for a count: whole numbers, about eight at most. */
export function countTicks(z) {
  const max = Math.max(1, ...z.flat().filter((v) => typeof v === 'number'));
  return { tickmode: 'linear', tick0: 0, dtick: Math.max(1, Math.ceil(max / 8)), tickformat: 'd' };
}

function renderGrid() {
  if (!table) return;
  const metric = METRICS[$('ckt-metric').value];
  const speeds = table.speeds_mps;
  const dpsis = table.dheadings_deg;
  const xs = dpsis.map((d) => `${d}°`);
  const ys = speeds.map((s) => `${s} m/s`);
  const z = speeds.map((s) => dpsis.map((d) => {
    const c = cellAt(s, d);
    const v = c ? metric.get(c) : null;
    return typeof v === 'number' ? v : null;
  }));
  const text = z.map((row) => row.map((v) => (v === null ? '' : metric.fmt(v))));
  const heat = $('ckt-heatmap');
  draw(
    heat,
    [{
      type: 'heatmap',
      x: xs,
      y: ys,
      z,
      text,
      texttemplate: '%{text}',
      colorscale: 'Viridis',
      zmin: $('ckt-metric').value === 'n' ? 0 : undefined,
      // Turns are counted: integer ticks (a colour bar at 0.5-turn steps reads as nonsense).
      colorbar: { title: { text: metric.label }, ...($('ckt-metric').value === 'n' ? countTicks(z) : {}) },
      hovertemplate: '%{y}, Δψ %{x}: %{text}<extra></extra>',
      xgap: 2,
      ygap: 2,
    }],
    { ...baseLayout({ margin: { l: 70, r: 10, t: 10, b: 50 } }), xaxis: axis('heading change Δψ', { type: 'category' }), yaxis: axis('speed', { type: 'category' }) },
  );
  onPlotClick(heat, (ev) => {
    const p = ev.points?.[0];
    if (!p) return;
    const s = speeds[ys.indexOf(p.y)];
    const d = dpsis[xs.indexOf(p.x)];
    if (s !== undefined && d !== undefined) openCell(s, d);
  });

  // The same grid as a table of buttons: reachable by keyboard, readable without colour.
  const t = $('ckt-table');
  t.replaceChildren(
    el('thead', {}, el('tr', {}, el('th', { scope: 'col', text: 'm/s \\ Δψ' }), ...dpsis.map((d) => el('th', { scope: 'col', text: `${d}°` })))),
  );
  const tb = el('tbody');
  for (const s of speeds) {
    const tr = el('tr', {}, el('th', { scope: 'row', text: String(s) }));
    for (const d of dpsis) {
      const c = cellAt(s, d);
      if (!c || !c.n_turns) {
        tr.append(el('td', { class: 'empty', text: '—' }));
        continue;
      }
      const v = metric.get(c);
      const label = `n=${c.n_turns}${metric !== METRICS.n && typeof v === 'number' ? ` · ${metric.fmt(v)}` : ''}`;
      const pressed = chosen && chosen.speed === s && chosen.dheading === d;
      tr.append(el('td', {}, el('button', {
        type: 'button',
        'data-n': c.n_turns,
        'data-speed': s,
        'data-dheading': d,
        'aria-pressed': pressed ? 'true' : 'false',
        'aria-label': `${s} m/s, ${d}°: ${c.n_turns} turns`,
        text: label,
        onclick: () => openCell(s, d),
      })));
    }
    tb.append(tr);
  }
  t.append(tb);
}

async function openCell(speed, dheading) {
  chosen = { speed, dheading };
  for (const b of document.querySelectorAll('#ckt-table button')) {
    b.setAttribute('aria-pressed', Number(b.dataset.speed) === speed && Number(b.dataset.dheading) === dheading ? 'true' : 'false');
  }
  const vid = encodeURIComponent(state.vehicleId);
  const plot = $('ckt-cell-plot');
  $('ckt-cell-title').textContent = `Cell ${speed} m/s, Δψ ${dheading}°`;
  const cellSummary = cellAt(speed, dheading);
  showShortOfGoal(false);
  if (!cellSummary || !cellSummary.n_turns) {
    $('ckt-cell-info').textContent = 'No turns in this cell.';
    delete plot.dataset.cell;
    showEmpty(plot, 'No turns in this cell.');
    return;
  }
  try {
    const cell = await getJson(`/vehicles/${vid}/ckt/cells`, { speed, dheading });
    const preds = {};
    // AVK too, for its corridor and short_of_goal (its trajectory is the cell's own, drawn above).
    // In the table's own frame, as its turns are drawn (current=none): the station would
    // otherwise carry them by its estimate of the current, over ground.
    const methods = ['avk', 'instantaneous', ...(state.models.length ? ['model'] : [])];
    await Promise.all(methods.map(async (m) => {
      try {
        preds[m] = await getJson(`/vehicles/${vid}/predict`, { speed, dheading, method: m, current: 'none' });
      } catch {
        // A method that cannot answer is left out of the plot.
      }
    }));
    if (chosen?.speed !== speed || chosen?.dheading !== dheading) return; // another cell was chosen meanwhile
    const noCorridor = preds.avk && !preds.avk.corridor ? ` · no corridor (${cell.n_turns < 2 ? 'needs 2 turns' : 'none in the table'})` : '';
    $('ckt-cell-info').textContent =
      `${cell.n_turns} turn${cell.n_turns === 1 ? '' : 's'} · advance ${meanSd(cell.advance_m, 2, ' m', cell.n_turns)} · transfer ${meanSd(cell.transfer_m, 2, ' m', cell.n_turns)} · AVK error ${typeof cell.avk_error_m2 === 'number' ? cell.avk_error_m2.toPrecision(3) + ' m²' : '– (needs 2 turns)'}${noCorridor}`;
    showShortOfGoal(preds.avk?.short_of_goal === true);
    // The corridor first, so the turns and the trajectories are drawn over it.
    const traces = [corridorTrace(preds.avk?.corridor)];
    (cell.turns ?? []).forEach((t, i) => {
      traces.push({
        type: 'scatter',
        mode: 'lines',
        name: 'turns',
        legendgroup: 'turns',
        showlegend: i === 0,
        x: t.points.map((p) => p[0]),
        y: t.points.map((p) => p[1]),
        line: { color: C.blue, width: 1 },
        opacity: 0.7,
        hovertemplate: `turn of mission ${t.mission_id}<extra></extra>`,
      });
    });
    const xy = (pts) => ({ x: (pts ?? []).map((p) => p[0]), y: (pts ?? []).map((p) => p[1]) });
    traces.push({ type: 'scatter', mode: 'lines', name: 'mean turn', ...xy(cell.mean), line: { color: C.vermillion, width: 3.5 } });
    traces.push({ type: 'scatter', mode: 'lines', name: 'fit', ...xy(cell.fit), line: { color: C.green, width: 2, dash: 'dashdot' } });
    traces.push({ type: 'scatter', mode: 'lines+markers', name: METHOD_STYLE.avk.name, ...xy(cell.trajectory), line: { color: METHOD_STYLE.avk.color, width: 1.5 }, marker: { size: 4 } });
    for (const m of ['model', 'instantaneous']) {
      if (!preds[m]) continue;
      const s = METHOD_STYLE[m];
      traces.push({ type: 'scatter', mode: 'lines', name: s.name, ...xy(preds[m].trajectory), line: { color: s.color, dash: s.dash, width: 2.5 } });
    }
    draw(plot, traces, {
      ...baseLayout(),
      ...equalAxes('x: to the right of the start (m)', 'y: ahead of the start (m)'),
      showlegend: true,
    });
    plot.dataset.cell = `${speed}|${dheading}`; // which cell is drawn (the browser tests wait for it)
  } catch (e) {
    $('ckt-cell-info').textContent = e.message;
    delete plot.dataset.cell;
    showEmpty(plot, e.message);
  }
}

/** The cell's turns stopped short of their goal: the prediction's end is the mean turn extended
 *  along the goal heading, not measured. */
function showShortOfGoal(on) {
  const w = $('ckt-cell-warning');
  if (w) w.hidden = !on;
}

function renderAdvanceTransfer() {
  const series = (key) => table.speeds_mps.map((s, i) => {
    const cells = table.cells.filter((c) => c.speed_mps === s && c.n_turns > 0 && c[key]).sort((a, b) => a.dheading_deg - b.dheading_deg);
    return {
      type: 'scatter',
      mode: 'lines+markers',
      name: `${s} m/s`,
      x: cells.map((c) => c.dheading_deg),
      y: cells.map((c) => c[key].mean),
      error_y: { type: 'data', array: cells.map((c) => c[key].sd ?? 0), visible: true, thickness: 1.2, width: 4 },
      line: { color: SERIES[i % SERIES.length] },
      marker: { symbol: SYMBOLS[i % SYMBOLS.length], size: 8, color: SERIES[i % SERIES.length] },
      hovertemplate: `${s} m/s, Δψ %{x}°: %{y:.2f} m<extra></extra>`,
    };
  });
  const layout = (title) => ({ ...baseLayout(), xaxis: axis('heading change Δψ (°)'), yaxis: axis(title), showlegend: true });
  draw($('ckt-advance'), series('advance_m'), layout('advance (m), mean ± 1 sd'));
  draw($('ckt-transfer'), series('transfer_m'), layout('transfer (m), mean ± 1 sd'));
}

export function cktTable() {
  return table;
}

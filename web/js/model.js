// The Model view: the stored black-box yaw models (thesis §3.4), the validation error per history
// length for chosen missions (Figure 3-9), a form to fit a new model from chosen missions, and a
// model's identification data: measured, desired, one-step and simulated heading against time.

import { state, on } from './state.js';
import { getJson, postJson } from './api.js';
import { C, baseLayout, axis, draw, showEmpty, makePlot } from './plots.js';
import { el, fillTable, num, setStatus } from './format.js';
import { refreshModels } from './sync.js';

const $ = (id) => document.getElementById(id);
let visible = false;
let autoSwept = false;

export function initModel() {
  $('model-form').addEventListener('submit', fit);
  $('model-sweep-run').addEventListener('click', sweep);
  on('models', renderModels);
  on('missions', renderMissions);
  // Another vehicle: its own missions are swept (the one drawn was of the other).
  on('vehicle-changed', () => {
    autoSwept = false;
    showEmpty($('model-sweep'), 'Choose missions and press “Sweep history”.');
  });
  initHeadings();
}

// ---------------------------------------------------------------- identification data plot

let headingsPlot = null;

/** The panel is built here (index.html stays as it is): model and mission pickers, a button,
 *  and a framed plot with the usual PNG button. */
function initHeadings() {
  const panel = el(
    'div',
    { class: 'panel', id: 'model-headings-panel' },
    el('h3', { text: 'Identification data' }),
    el('p', { class: 'small', text: 'A mission’s guided navigation at the model’s rate: measured and desired heading, the model’s one-step-ahead prediction from measured history, and its free-run simulation driven by the desired heading (restarted from measured history at each desired-heading step). Headings are unwrapped.' }),
    el('div', { class: 'row' },
      el('div', { class: 'field' }, el('label', { for: 'model-h-model', text: 'Model' }), el('select', { id: 'model-h-model' })),
      el('div', { class: 'field' }, el('label', { for: 'model-h-mission', text: 'Mission' }), el('select', { id: 'model-h-mission' })),
      el('button', { type: 'button', id: 'model-h-show', class: 'secondary', text: 'Show headings' })),
    el('p', { id: 'model-h-status', class: 'small', role: 'status', 'aria-live': 'polite' }),
  );
  $('view-model').append(panel);
  headingsPlot = makePlot($('view-model'), 'model-headings', 'Heading: measured, desired, one-step and simulated', 'avk-headings');
  showEmpty(headingsPlot, 'Choose a model and a mission and press “Show headings”.');
  $('model-h-show').addEventListener('click', showHeadings);
}

function fillSelect(select, options) {
  const keep = select.value;
  select.replaceChildren(...options.map(([value, label]) => el('option', { value, text: label })));
  if (options.some(([v]) => String(v) === keep)) select.value = keep;
}

function renderHeadingPickers() {
  const models = [...state.models].sort((a, b) => b.id - a.id);
  fillSelect($('model-h-model'), models.map((m) => [m.id, `${m.id} · ${m.form}, history ${historyText(m)}`]));
  const mine = state.missions.filter((m) => !state.vehicleId || m.vehicle_id === state.vehicleId).sort((a, b) => b.id - a.id);
  fillSelect($('model-h-mission'), mine.map((m) => [m.id, `${m.id} · ${m.name}`]));
  $('model-h-show').disabled = models.length === 0 || mine.length === 0;
}

async function showHeadings() {
  const out = $('model-h-status');
  const model = $('model-h-model').value;
  const mission = $('model-h-mission').value;
  if (!model || !mission) {
    setStatus(out, 'Choose a model and a mission.', 'error');
    return;
  }
  setStatus(out, 'Loading…');
  try {
    const h = await getJson(`/models/${model}/headings`, { mission });
    // Segments joined with a null between them: the lines break at gaps instead of bridging them.
    const t = [];
    const cols = { heading_deg: [], desired_heading_deg: [], one_step_deg: [], simulated_deg: [] };
    let n = 0;
    for (const seg of h.segments) {
      if (t.length) {
        t.push(null);
        for (const c of Object.values(cols)) c.push(null);
      }
      seg.heading_deg.forEach((_, k) => t.push(seg.t0_s + k * h.dt_s));
      for (const [k, c] of Object.entries(cols)) c.push(...seg[k]);
      n += seg.heading_deg.length;
    }
    const line = (name, y, style) => ({ type: 'scatter', mode: 'lines', name, x: t, y, connectgaps: false, line: style });
    draw(headingsPlot, [
      line('measured', cols.heading_deg, { color: C.blue, width: 2 }),
      line('desired', cols.desired_heading_deg, { color: C.black, width: 1.5, dash: 'dash' }),
      line('one-step', cols.one_step_deg, { color: C.green, width: 1.5, dash: 'dot' }),
      line('simulated', cols.simulated_deg, { color: C.vermillion, width: 2, dash: 'dashdot' }),
    ], {
      ...baseLayout(),
      xaxis: axis('mission time (s)'),
      yaxis: axis('heading (°, unwrapped)'),
      showlegend: true,
    });
    setStatus(out, `Model ${model} on mission ${mission}: ${n} samples in ${h.segments.length} segment(s) at ${num(1 / h.dt_s, 1)} Hz; predictions start after ${num(h.warmup_samples * h.dt_s, 1)} s (${h.warmup_samples} samples) of history.`, 'ok');
  } catch (e) {
    showEmpty(headingsPlot, e.message);
    setStatus(out, e.message, 'error');
  }
}

export function showModel(isVisible) {
  visible = isVisible;
  if (visible) {
    renderModels();
    renderMissions();
    renderHeadingPickers();
    if (!autoSwept && !$('model-sweep')._fullLayout) showEmpty($('model-sweep'), 'Choose missions and press “Sweep history”.');
    maybeAutoSweep();
    refreshModels().catch(() => {});
  }
}

/** A model's history in seconds, as the fit form asks for it, with its samples: "10.0 s (100 samples)". */
export function historyText(m) {
  const n = m?.history;
  if (typeof n !== 'number') return '–';
  const s = typeof m.rate_hz === 'number' && m.rate_hz > 0 ? n / m.rate_hz : null;
  return s === null ? `${n} samples` : `${num(s, 1)} s (${n} samples)`;
}

function renderModels() {
  if (!visible) return;
  renderHeadingPickers();
  const models = [...state.models].sort((a, b) => b.id - a.id);
  fillTable(
    $('models-table'),
    [
      { key: 'id', label: 'id' },
      { key: 'form', label: 'form' },
      // Asked for in seconds (the form), so shown in seconds, the samples beside them.
      { key: 'history', label: 'history (s)', fmt: (v, m) => historyText(m) },
      { key: 'rate_hz', label: 'rate (Hz)', fmt: (v) => num(v, 1) },
      { key: 'refined', label: 'refined', fmt: (v) => (v ? 'yes' : 'no') },
      { key: 'ridge_lambda', label: 'ridge λ', fmt: (v) => (typeof v === 'number' ? v.toExponential(1) : '–') },
      { key: 'train_one_step_rms_deg', label: 'one-step rms (°)', fmt: (v) => num(v, 2) },
      { key: 'validation_heading_rms_deg', label: 'validation heading rms (°)', fmt: (v) => num(v, 2) },
      { key: 'validation_mse_m2', label: 'validation MSE (m²)', fmt: (v) => num(v, 2) },
      { key: 'training_missions', label: 'missions', fmt: (v) => (Array.isArray(v) ? v.join(', ') : '–') },
      { key: 'created_utc', label: 'created (UTC)' },
    ],
    models,
  );
  if (models.length === 0) $('models-table').append(el('caption', { class: 'small muted', text: 'No model stored yet.' }));
}

function renderMissions() {
  if (!visible) return;
  renderHeadingPickers();
  const box = $('model-missions');
  const checked = new Set([...box.querySelectorAll('input:checked')].map((i) => Number(i.value)));
  const mine = state.missions.filter((m) => !state.vehicleId || m.vehicle_id === state.vehicleId).sort((a, b) => b.id - a.id);
  // By default the persistent-excitation missions: they are what identification is meant for.
  const preselect = checked.size === 0 ? new Set(mine.filter((m) => /excitation/i.test(m.name)).map((m) => m.id)) : checked;
  box.replaceChildren(
    el('legend', { class: 'visually-hidden', text: 'Missions' }),
    ...mine.map((m) =>
      el('label', {},
        el('input', { type: 'checkbox', value: m.id, checked: preselect.has(m.id) }),
        ` ${m.id} · ${m.name} · ${m.status}`),
    ),
  );
  if (mine.length === 0) box.append(el('p', { class: 'small muted', text: 'No missions yet.' }));
  maybeAutoSweep();
}

/** The first visit sweeps the preselected (persistent excitation) missions, once; the mission
 *  list may arrive after the view is shown. */
function maybeAutoSweep() {
  if (!visible || autoSwept || chosenMissions().length === 0) return;
  autoSwept = true;
  sweep();
}

function chosenMissions() {
  return [...$('model-missions').querySelectorAll('input:checked')].map((i) => Number(i.value));
}

async function sweep() {
  const out = $('model-result');
  const missions = chosenMissions();
  if (missions.length === 0) {
    setStatus(out, 'Choose at least one mission.', 'error');
    return;
  }
  setStatus(out, 'Sweeping history lengths…');
  try {
    const rows = await getJson(`/vehicles/${encodeURIComponent(state.vehicleId)}/models/sweep`, { mission: missions });
    setStatus(out, `Sweep of missions ${missions.join(', ')}: ${rows.length} history lengths.`, 'ok');
    const x = rows.map((r) => r.history_s);
    draw($('model-sweep'), [
      { type: 'scatter', mode: 'lines+markers', name: 'validation MSE (m²)', x, y: rows.map((r) => r.validation_mse_m2), line: { color: C.blue }, marker: { symbol: 'circle', size: 7 } },
      { type: 'scatter', mode: 'lines+markers', name: 'validation heading rms (°)', x, y: rows.map((r) => r.validation_heading_rms_deg), yaxis: 'y2', line: { color: C.vermillion, dash: 'dash' }, marker: { symbol: 'square', size: 7 } },
      { type: 'scatter', mode: 'lines+markers', name: 'one-step rms (°, training)', x, y: rows.map((r) => r.train_one_step_rms_deg), yaxis: 'y2', line: { color: C.green, dash: 'dot' }, marker: { symbol: 'diamond', size: 7 } },
    ], {
      ...baseLayout({ margin: { l: 58, r: 58, t: 34, b: 48 } }),
      xaxis: axis('history length (s)'),
      yaxis: axis('validation MSE (m²)', { rangemode: 'tozero' }),
      yaxis2: axis('heading rms (°)', { overlaying: 'y', side: 'right', rangemode: 'tozero', showgrid: false, tickmode: 'auto' }),
      showlegend: true,
    });
  } catch (e) {
    setStatus(out, e.message, 'error');
  }
}

async function fit(ev) {
  ev.preventDefault();
  const out = $('model-result');
  const missions = chosenMissions();
  if (missions.length === 0) {
    setStatus(out, 'Choose at least one mission.', 'error');
    return;
  }
  const body = { missions, form: $('model-form-kind').value, refine: $('model-refine').checked };
  const h = $('model-history').value.trim();
  if (h !== '') body.history_s = Number(h);
  setStatus(out, 'Fitting…');
  $('model-fit').disabled = true;
  try {
    const m = await postJson(`/vehicles/${encodeURIComponent(state.vehicleId)}/models`, body);
    setStatus(out, `Model ${m.id ?? ''} stored: validation MSE ${num(m.validation_mse_m2, 2)} m², heading rms ${num(m.validation_heading_rms_deg, 2)}°.`, 'ok');
    await refreshModels();
  } catch (e) {
    setStatus(out, e.message, 'error');
  } finally {
    $('model-fit').disabled = false;
  }
}

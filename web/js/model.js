// The Model view: the stored black-box yaw models (thesis §3.4), the validation error per history
// length for chosen missions (Figure 3-9), and a form to fit a new model from chosen missions.

import { state, on } from './state.js';
import { getJson, postJson } from './api.js';
import { C, baseLayout, axis, draw, showEmpty } from './plots.js';
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
}

export function showModel(isVisible) {
  visible = isVisible;
  if (visible) {
    renderModels();
    renderMissions();
    if (!autoSwept && !$('model-sweep')._fullLayout) showEmpty($('model-sweep'), 'Choose missions and press “Sweep history”.');
    maybeAutoSweep();
    refreshModels().catch(() => {});
  }
}

function renderModels() {
  if (!visible) return;
  const models = [...state.models].sort((a, b) => b.id - a.id);
  fillTable(
    $('models-table'),
    [
      { key: 'id', label: 'id' },
      { key: 'form', label: 'form' },
      { key: 'history', label: 'history (samples)' },
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

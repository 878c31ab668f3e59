// The Export view: the CKT (JSON, CSV), the turns (CSV, every page), a mission as an MCAP
// recording, its track (CSV) and event log (CSV, JSON), and the comparison (CSV) as downloads,
// and a PNG of every plot drawn so far.

import { state, on } from './state.js';
import { getAllItems, getBlob, getText } from './api.js';
import { drawnPlots, downloadPng, onPlotsChanged } from './plots.js';
import { el, setStatus } from './format.js';
import { refreshTurnCount } from './sync.js';

const $ = (id) => document.getElementById(id);
let visible = false;

/** Saves a URL (same origin) as a file through a temporary <a download>. */
function downloadUrl(url, filename) {
  const a = el('a', { href: url, download: filename });
  document.body.append(a);
  a.click();
  a.remove();
}

function downloadBlob(blob, filename) {
  const url = URL.createObjectURL(blob);
  downloadUrl(url, filename);
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

function downloadText(text, filename, type) {
  downloadBlob(new Blob([text], { type }), filename);
}

async function needTurns() {
  await refreshTurnCount().catch(() => {});
  if (state.okTurns > 0) return true;
  setStatus($('exp-status'), 'No ok turns yet: there is nothing to export.', 'error');
  return false;
}

async function cktDownload(format) {
  if (!state.vehicleId || !(await needTurns())) return;
  const vid = encodeURIComponent(state.vehicleId);
  // Fetched (with the token, which a plain link cannot send off loopback) and saved from memory.
  try {
    const type = format === 'csv' ? 'text/csv' : 'application/json';
    const { text } = await getText(`/vehicles/${vid}/ckt/export`, { format }, type);
    downloadText(text, `ckt-${state.vehicleId}.${format}`, type);
    setStatus($('exp-status'), `CKT ${format.toUpperCase()} saved.`, 'ok');
  } catch (e) {
    setStatus($('exp-status'), e.message, 'error');
  }
}

/** Every page of a paged CSV collection (at most `limit` rows a page, the cursor in
 *  X-Next-After) joined into one file: the header once, then every row. */
async function allCsvPages(path, params, limit) {
  let after;
  let header = null;
  const lines = [];
  for (let page = 0; page < 10000; page++) {
    const { text, headers } = await getText(path, { ...params, format: 'csv', limit, after });
    const rows = text.split('\n').filter((l) => l.length > 0);
    if (rows.length === 0) break;
    if (header === null) header = rows[0];
    lines.push(...rows.slice(1));
    const next = headers.get('X-Next-After');
    if (!next) break;
    after = next;
  }
  return { text: `${[header ?? '', ...lines].join('\n')}\n`, rows: lines.length };
}

/** Turns as CSV: the collection is paged (at most 1000 a page), so the pages are joined. */
async function turnsCsv() {
  const mission = $('exp-turns-mission').value;
  const status = $('exp-status');
  setStatus(status, 'Collecting turns…');
  try {
    const { text, rows } = await allCsvPages('/turns', { mission: mission || undefined }, 1000);
    downloadText(text, `turns${mission ? `-mission-${mission}` : ''}.csv`, 'text/csv');
    setStatus(status, `Turns CSV: ${rows} turns.`, 'ok');
  } catch (e) {
    setStatus(status, e.message, 'error');
  }
}

/** The chosen mission's id, or null (with the reason shown) when there is none yet. */
function chosenMission() {
  const id = $('exp-mcap-mission').value;
  if (!id) setStatus($('exp-status'), 'No mission yet: there is nothing to export.', 'error');
  return id || null;
}

/** The mission's stored track as one CSV file: every page of /missions/{id}/nav. */
async function trackCsv() {
  const id = chosenMission();
  if (!id) return;
  const status = $('exp-status');
  setStatus(status, `Collecting the track of mission ${id}…`);
  try {
    const { text, rows } = await allCsvPages(`/missions/${encodeURIComponent(id)}/nav`, {}, 10000);
    downloadText(text, `mission-${id}-track.csv`, 'text/csv');
    setStatus(status, `Mission ${id} track CSV: ${rows} samples.`, 'ok');
  } catch (e) {
    setStatus(status, e.message, 'error');
  }
}

/** The mission's event log, every page, as CSV or as a JSON array of the REST items. */
async function eventsDownload(format) {
  const id = chosenMission();
  if (!id) return;
  const status = $('exp-status');
  const path = `/missions/${encodeURIComponent(id)}/events`;
  setStatus(status, `Collecting the event log of mission ${id}…`);
  try {
    if (format === 'csv') {
      const { text, rows } = await allCsvPages(path, {}, 1000);
      downloadText(text, `mission-${id}-events.csv`, 'text/csv');
      setStatus(status, `Mission ${id} event log CSV: ${rows} entries.`, 'ok');
    } else {
      const items = await getAllItems(path, {}, Number.MAX_SAFE_INTEGER);
      downloadText(`${JSON.stringify(items, null, 1)}\n`, `mission-${id}-events.json`, 'application/json');
      setStatus(status, `Mission ${id} event log JSON: ${items.length} entries.`, 'ok');
    }
  } catch (e) {
    setStatus(status, e.message, 'error');
  }
}

/** A mission as an MCAP recording (GET /missions/{id}/export?format=mcap), fetched with the token
 *  like the other downloads and saved as the server names it. */
async function missionMcap() {
  const id = chosenMission();
  if (!id) return;
  const status = $('exp-status');
  setStatus(status, `Writing mission ${id} as MCAP…`);
  try {
    const { blob } = await getBlob(`/missions/${encodeURIComponent(id)}/export`, { format: 'mcap' }, 'application/vnd.mcap');
    downloadBlob(blob, `mission-${id}.mcap`);
    setStatus(status, `Mission ${id} MCAP saved (${blob.size} bytes).`, 'ok');
  } catch (e) {
    setStatus(status, e.message, 'error');
  }
}

/** The comparison as CSV: the held-out (predictive) table, or the thesis' in-sample one. */
async function compareCsv(scoring) {
  if (!state.vehicleId || !(await needTurns())) return;
  try {
    const { text } = await getText(`/vehicles/${encodeURIComponent(state.vehicleId)}/compare`, { format: 'csv', scoring: scoring === 'in_sample' ? 'in_sample' : undefined });
    downloadText(text, `compare-${state.vehicleId}${scoring === 'in_sample' ? '-in-sample' : ''}.csv`, 'text/csv');
    setStatus($('exp-status'), 'Comparison CSV saved.', 'ok');
  } catch (e) {
    setStatus($('exp-status'), e.message, 'error');
  }
}

function renderPlotList() {
  if (!visible) return;
  const list = $('exp-plots');
  const plots = drawnPlots();
  list.replaceChildren(
    ...plots.map((p) => el('li', {}, el('button', { type: 'button', class: 'secondary', text: `PNG: ${p.title}`, onclick: () => downloadPng(p.el) }))),
  );
  if (plots.length === 0) list.append(el('li', { class: 'small muted', text: 'No plot drawn yet: open the other views first.' }));
}

function renderMissionChoice() {
  const options = () => [...state.missions].sort((a, b) => b.id - a.id).map((m) => el('option', { value: m.id, text: `${m.id} · ${m.name}` }));
  const turns = $('exp-turns-mission');
  const keepTurns = turns.value;
  turns.replaceChildren(el('option', { value: '', text: 'all' }), ...options());
  turns.value = keepTurns;
  const mcap = $('exp-mcap-mission');
  const keepMcap = mcap.value;
  mcap.replaceChildren(...options());
  if (keepMcap) mcap.value = keepMcap;
}

export function initExport() {
  $('exp-ckt-json').addEventListener('click', () => cktDownload('json'));
  $('exp-ckt-csv').addEventListener('click', () => cktDownload('csv'));
  $('exp-turns-csv').addEventListener('click', turnsCsv);
  $('exp-mission-mcap').addEventListener('click', missionMcap);
  $('exp-track-csv').addEventListener('click', trackCsv);
  $('exp-events-csv').addEventListener('click', () => eventsDownload('csv'));
  $('exp-events-json').addEventListener('click', () => eventsDownload('json'));
  $('exp-compare-csv').addEventListener('click', () => compareCsv('predictive'));
  $('exp-compare-insample-csv').addEventListener('click', () => compareCsv('in_sample'));
  on('missions', renderMissionChoice);
  onPlotsChanged(renderPlotList);
}

export function showExport(isVisible) {
  visible = isVisible;
  if (visible) {
    renderMissionChoice();
    renderPlotList();
  }
}

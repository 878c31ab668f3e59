// Commands that keep a boat safe (docs/api.md, "Vehicle commands"): Hold, Go to, Return and Stop
// for the selected vehicle. Each is confirmed in the page first, naming the vehicle and what it
// will do; then sent, and the station's answer (the vehicle's helm mode and command) or its error
// is shown. They are control calls: without the token the buttons are off and say why. Go to
// takes x and y (metres on the local grid, x east, y north), typed or picked on the Live map.

import { state, on, emit } from './state.js';
import { postJson } from './api.js';
import { getToken, onTokenChange, requestToken } from './auth.js';
import { applyVehicleAnswer } from './sync.js';
import { commandText } from './fleet.js';
import { setStatus } from './format.js';

const $ = (id) => document.getElementById(id);
const PATHS = { hold: 'hold', go_to: 'go-to', return: 'return', stop: 'stop' };
const NAMES = { hold: 'Hold', go_to: 'Go to', return: 'Return', stop: 'Stop' };
const DEFAULT_RADIUS_M = 5;

let asked = null; // the command waiting for its confirmation: {vid, kind, body}
let sending = false;
let picking = false;
let pending = null; // {x, y}: the Go to point typed or picked, not sent yet

/** The Go to point typed or picked and not sent yet (drawn on the Live map), or null. */
export function pendingPoint() {
  return pending;
}

/** A number typed in a field; undefined when empty, NaN when not a number. */
function field(id) {
  const raw = $(id).value.trim();
  return raw === '' ? undefined : Number(raw);
}

const m1 = (v) => (Math.round(v * 10) / 10).toFixed(1);

/** The body of a command from the fields, or {error}. */
function bodyOf(kind) {
  if (kind === 'stop') return { body: {} };
  const body = {};
  const radius = field('cmd-radius');
  if (radius !== undefined) {
    if (!Number.isFinite(radius)) return { error: 'the radius is not a number' };
    body.radius_m = radius;
  }
  if (kind === 'hold') return { body };
  const speed = field('cmd-speed');
  if (speed !== undefined) {
    if (!Number.isFinite(speed)) return { error: 'the speed is not a number' };
    body.speed_mps = speed;
  }
  if (kind === 'return') return { body };
  const x = field('cmd-x');
  const y = field('cmd-y');
  if (x === undefined || y === undefined) return { error: 'Go to needs the point: x and y (m), typed or picked on the map' };
  if (!Number.isFinite(x) || !Number.isFinite(y)) return { error: 'x and y must be numbers (m)' };
  return { body: { x_m: x, y_m: y, ...body } };
}

/** What the operator confirms: the vehicle, what it will do, and what it ends. */
function question(kind, vid, body) {
  const v = state.fleet.get(vid);
  const mission = v?.helm?.mission_id ? ` Mission ${v.helm.mission_id} running on it is aborted first.` : '';
  const r = body.radius_m ?? DEFAULT_RADIUS_M;
  const speed = body.speed_mps !== undefined ? ` at ${body.speed_mps} m/s` : '';
  switch (kind) {
    case 'hold':
      return `Hold ${vid}: it keeps station where it is now, within ${r} m.${mission}`;
    case 'go_to':
      return `Go to: ${vid} goes to (${m1(body.x_m)}, ${m1(body.y_m)})${speed}, then holds there within ${r} m.${mission}`;
    case 'return':
      return `Return ${vid}: it goes back to the last mission's return point${speed}, then holds there within ${r} m.${mission}`;
    default:
      return `Stop ${vid}: all stop, it will drift.${mission}`;
  }
}

function ask(kind) {
  const vid = state.vehicleId;
  const out = $('cmd-result');
  if (!vid || !canCommand().ok) return;
  const { body, error } = bodyOf(kind);
  if (error) {
    setStatus(out, `${NAMES[kind]}: ${error}.`, 'error');
    out.dataset.state = 'error';
    return;
  }
  asked = { vid, kind, body };
  const box = $('cmd-confirm');
  box.dataset.kind = kind;
  box.dataset.vehicle = vid;
  $('cmd-question').textContent = question(kind, vid, body);
  $('cmd-yes').textContent = `${NAMES[kind]} ${vid}`;
  $('cmd-yes').className = kind === 'stop' ? 'danger' : '';
  box.hidden = false;
  $('cmd-no').focus();
}

function hideConfirm() {
  asked = null;
  const box = $('cmd-confirm');
  box.hidden = true;
  delete box.dataset.kind;
  delete box.dataset.vehicle;
}

async function send() {
  const a = asked;
  hideConfirm();
  if (!a) return;
  const out = $('cmd-result');
  setStatus(out, `${a.vid}: ${NAMES[a.kind]} sent…`);
  out.dataset.state = 'sending';
  sending = true;
  update();
  try {
    const v = await postJson(`/vehicles/${encodeURIComponent(a.vid)}/${PATHS[a.kind]}`, a.body);
    applyVehicleAnswer(v);
    setStatus(out, `${a.vid}: ${NAMES[a.kind]} taken: ${v.helm_mode ?? 'idle'}, ${commandText(v.command)}.`, 'ok');
    out.dataset.state = 'ok';
    if (a.kind === 'go_to') setPending(null);
  } catch (e) {
    // The station's own words: a 409 (no return point yet, a vehicle it does not drive), a 422
    // naming the field, a refused token.
    setStatus(out, `${a.vid}: ${NAMES[a.kind]} refused: ${e.message}`, 'error');
    out.dataset.state = 'error';
  } finally {
    sending = false;
    update();
  }
}

/** Whether the selected vehicle can be commanded from here, and why not. */
function canCommand() {
  const vid = state.vehicleId;
  if (!getToken()) return { ok: false, why: 'Commands need the control token.' };
  if (!vid) return { ok: false, why: 'No vehicle.' };
  const v = state.fleet.get(vid);
  if (v?.stored || v?.link === 'DISCONNECTED') return { ok: false, why: `${vid} is not connected to this station.` };
  if (sending) return { ok: false, why: 'A command is on its way.' };
  return { ok: true, why: '' };
}

let shown = '';
function update() {
  const { ok, why } = canCommand();
  const vid = state.vehicleId;
  const key = `${ok}|${why}|${vid}`;
  if (key !== shown) {
    shown = key;
    for (const kind of Object.keys(PATHS)) {
      const b = $(`cmd-${kind.replace('_', '')}`);
      b.disabled = !ok;
      b.title = ok ? `${NAMES[kind]} ${vid} (asks first)` : why;
    }
    $('cmd-pick').disabled = !ok;
    $('cmd-vehicle').textContent = vid ? `· ${vid}` : '';
    $('cmd-token-note').hidden = Boolean(getToken());
    if (!ok && asked) hideConfirm();
  }
  const helm = state.helm;
  const current = vid ? `${helm?.mode ?? 'idle'} · ${commandText(helm?.command)}` : '–';
  if ($('cmd-current').textContent !== current) $('cmd-current').textContent = current;
}

function setPending(p) {
  pending = p;
  emit('command-point', p);
}

function pendingFromFields() {
  const x = field('cmd-x');
  const y = field('cmd-y');
  setPending(Number.isFinite(x) && Number.isFinite(y) ? { x, y } : null);
}

function setPicking(on_) {
  picking = on_;
  const b = $('cmd-pick');
  b.setAttribute('aria-pressed', String(picking));
  b.textContent = picking ? 'Click the map…' : 'Pick on map';
  document.getElementById('live-plot')?.classList.toggle('picking', picking);
}

/** A click on the Live map while picking: its grid position becomes the Go to point. */
function pickAt(ev) {
  if (!picking || ev.button !== 0) return;
  const plot = document.getElementById('live-plot');
  const fl = plot._fullLayout;
  if (!fl?.xaxis?.p2c) return;
  const r = plot.getBoundingClientRect();
  const px = ev.clientX - r.left - fl.xaxis._offset;
  const py = ev.clientY - r.top - fl.yaxis._offset;
  if (px < 0 || py < 0 || px > fl.xaxis._length || py > fl.yaxis._length) return;
  ev.preventDefault();
  ev.stopPropagation();
  $('cmd-x').value = m1(fl.xaxis.p2c(px));
  $('cmd-y').value = m1(fl.yaxis.p2c(py));
  setPicking(false);
  pendingFromFields();
}

export function initCommands() {
  for (const kind of Object.keys(PATHS)) $(`cmd-${kind.replace('_', '')}`).addEventListener('click', () => ask(kind));
  $('cmd-yes').addEventListener('click', send);
  $('cmd-no').addEventListener('click', () => {
    hideConfirm();
    setStatus($('cmd-result'), 'Cancelled: nothing sent.');
    $('cmd-result').dataset.state = 'cancelled';
  });
  $('cmd-pick').addEventListener('click', () => setPicking(!picking));
  for (const id of ['cmd-x', 'cmd-y']) $(id).addEventListener('input', pendingFromFields);
  $('cmd-token').addEventListener('click', () => requestToken().catch(() => {}));
  // On the press, before Plotly's drag layer takes it (its cover gets the release and the click).
  document.getElementById('live-plot').addEventListener('mousedown', pickAt, true);
  onTokenChange(update);
  on('helm', update);
  on('fleet', update);
  on('vehicle-changed', () => {
    hideConfirm(); // a question about the other vehicle is not answered for this one
    setPicking(false);
    update();
  });
  update();
}

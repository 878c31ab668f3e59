// The vehicle list: in the Live view every vehicle of the station with its link, helm mode and
// command, each a button that shows it; in the header a selector, on every view, once there are
// several. Choosing one switches everything that is of a vehicle (sync.js selectVehicle).
// Updated in place, at most once a frame: a list rebuilt at 10 Hz would swallow the clicks on it.

import { state, on } from './state.js';
import { el } from './format.js';
import { fleetList, helmText, linkOf } from './fleet.js';
import { selectVehicle } from './sync.js';

const $ = (id) => document.getElementById(id);
let requested = false;

function text(e, v) {
  if (e.textContent !== v) e.textContent = v;
}

function choose(id) {
  selectVehicle(id).catch((e) => console.warn('switching vehicles failed', e));
}

function request() {
  if (requested) return;
  requested = true;
  requestAnimationFrame(render);
}

function itemFor(list, id) {
  let li = list.querySelector(`li[data-vehicle="${CSS.escape(id)}"]`);
  if (!li) {
    const button = el(
      'button',
      { type: 'button', class: 'fleet-item', 'aria-pressed': 'false' },
      el('strong', { class: 'fleet-id', text: id }),
      el('span', { class: 'fleet-link' }),
      el('span', { class: 'fleet-helm' }),
    );
    button.addEventListener('click', () => choose(id));
    li = el('li', { 'data-vehicle': id }, button);
  }
  return li;
}

function render() {
  requested = false;
  const vehicles = fleetList();
  const list = $('fleet-list');
  const items = vehicles.map((v) => {
    const li = itemFor(list, v.id);
    const link = linkOf(v);
    li.dataset.link = link;
    li.dataset.mode = v.helm?.mode ?? '';
    li.dataset.command = v.helm?.command?.kind ?? '';
    const b = li.firstChild;
    const selected = v.id === state.vehicleId;
    if (b.getAttribute('aria-pressed') !== String(selected)) b.setAttribute('aria-pressed', String(selected));
    b.title = selected ? `${v.id}: shown in every view` : `Show ${v.id} in every view`;
    const linkEl = b.querySelector('.fleet-link');
    text(linkEl, link);
    linkEl.className = `fleet-link link-${link.toLowerCase()}`;
    text(b.querySelector('.fleet-helm'), helmText(v));
    return li;
  });
  if (items.length === 0) items.push(el('li', { class: 'muted small', text: 'No vehicle.' }));
  // Moved only when the order or the vehicles changed: a replaced button loses a click under way.
  const now = [...list.children];
  if (now.length !== items.length || now.some((c, i) => c !== items[i])) list.replaceChildren(...items);
  renderSelect(vehicles);
}

/** The header's selector: on every view, once the station has several vehicles. */
function renderSelect(vehicles) {
  const sel = $('vehicle-select');
  const wrap = $('vehicle-select-wrap');
  wrap.hidden = vehicles.length < 2;
  const labels = vehicles.map((v) => `${v.id} · ${linkOf(v)} · ${v.helm?.mode ?? (v.stored ? 'stored' : 'idle')}`);
  const opts = [...sel.options];
  if (opts.length !== vehicles.length || opts.some((o, i) => o.value !== vehicles[i].id)) {
    sel.replaceChildren(...vehicles.map((v, i) => el('option', { value: v.id, text: labels[i] })));
  } else {
    opts.forEach((o, i) => text(o, labels[i]));
  }
  if (state.vehicleId && sel.value !== state.vehicleId) sel.value = state.vehicleId;
}

export function initFleetPanel() {
  $('vehicle-select').addEventListener('change', (ev) => choose(ev.target.value));
  on('fleet', request);
  on('helm', request);
  on('vehicle-changed', request);
  on('synced', request);
  setInterval(request, 1000); // a vehicle gone quiet reads STALE without a message to say so
  request();
}

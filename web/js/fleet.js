// The station's vehicles (a fleet): the latest navigation and helm of each, with a short trail,
// whichever is selected. The selected vehicle (state.vehicleId) is the one every view shows; the
// others are drawn on the Live map and listed with their link, helm mode and command. The choice is
// kept in the address (?vehicle=bravo), so a reload keeps it.
//
// Only sync.js writes here (from REST and the stream), as it does the rest of the state.

import { state, emit } from './state.js';

export const MAX_VEHICLES = 64; // vehicles kept; the longest unheard of (never the selected) go
const TRAIL_POINTS = 200; // per vehicle
const TRAIL_STEP_M = 1; // a trail point every metre moved: 200 m of trail, whatever the rate

let version = 0; // bumped on every change: drawings keep theirs until it moves

export function fleetVersion() {
  return version;
}

/** The vehicle the address asks for (?vehicle=), or null. */
export function wantedVehicle() {
  return new URLSearchParams(window.location.search).get('vehicle');
}

/** Keeps the choice in the address (the token and the view are left as they are). */
export function setWantedVehicle(id) {
  const url = new URL(window.location.href);
  if (id) url.searchParams.set('vehicle', id);
  else url.searchParams.delete('vehicle');
  history.replaceState(history.state, '', url.pathname + url.search + url.hash);
}

function entry(id) {
  let v = state.fleet.get(id);
  if (!v) {
    v = { id, kind: null, maxSpeed: null, link: null, nav: null, helm: null, trail: { x: [], y: [] }, heardMs: 0 };
    state.fleet.set(id, v);
    bound();
  }
  return v;
}

function bound() {
  while (state.fleet.size > MAX_VEHICLES) {
    let oldest = null;
    for (const v of state.fleet.values()) {
      if (v.id === state.vehicleId) continue;
      if (!oldest || v.heardMs < oldest.heardMs) oldest = v;
    }
    if (!oldest) return;
    state.fleet.delete(oldest.id);
  }
}

function changed() {
  clearTimeout(soon);
  soon = null;
  lastEmitMs = performance.now();
  version++;
  emit('fleet', state.fleet);
}

// The stream's nav and helm of ten vehicles at x10 are a thousand messages a second: the map and
// the list follow the other vehicles at most every FLEET_REDRAW_MS (the selected vehicle is
// followed at once, as its own track is), so the page keeps its frame rate with a fleet.
const FLEET_REDRAW_MS = 250;
let soon = null;
let lastEmitMs = 0;
function changedSoon() {
  if (soon) return;
  const wait = FLEET_REDRAW_MS - (performance.now() - lastEmitMs);
  if (wait <= 0) return changed();
  soon = setTimeout(changed, wait);
}

function pushTrail(v, x, y) {
  const t = v.trail;
  const n = t.x.length;
  if (n > 0 && Math.hypot(x - t.x[n - 1], y - t.y[n - 1]) < TRAIL_STEP_M) return;
  t.x.push(x);
  t.y.push(y);
  if (t.x.length > TRAIL_POINTS) {
    t.x.shift();
    t.y.shift();
  }
}

/** A nav message (the stream's or REST's) of any vehicle. */
export function noteFleetNav(d) {
  if (!d?.vehicle_id) return;
  const v = entry(d.vehicle_id);
  v.heardMs = performance.now();
  if (d.link) v.link = d.link;
  if (Number.isFinite(d.x_m) && Number.isFinite(d.y_m)) {
    v.nav = d;
    pushTrail(v, d.x_m, d.y_m);
  }
  if (d.vehicle_id === state.vehicleId) changed();
  else changedSoon();
}

/** A helm message of any vehicle: its mode, desired values, mission and command. */
export function noteFleetHelm(d) {
  if (!d?.vehicle_id) return;
  const v = entry(d.vehicle_id);
  v.heardMs = performance.now();
  v.helm = d;
  if (d.vehicle_id === state.vehicleId) changed();
  else changedSoon();
}

/** The helm message a vehicle of GET /vehicles amounts to. */
export function helmOf(v) {
  return {
    vehicle_id: v.id,
    mode: v.helm_mode ?? null,
    desired_heading_deg: v.desired_heading_deg ?? null,
    desired_speed_mps: v.desired_speed_mps ?? null,
    mission_id: v.mission_id ?? null,
    command: v.command ?? null,
  };
}

/** GET /vehicles (or one vehicle of it, a command's answer): what each vehicle is and its last
 *  state. A vehicle known only from stored missions is DISCONNECTED, with no helm. */
export function noteVehicles(list) {
  for (const r of list) {
    if (!r?.id) continue;
    const v = entry(r.id);
    v.kind = r.kind ?? null;
    v.maxSpeed = r.max_speed_mps ?? null;
    v.link = r.link ?? v.link;
    v.stored = r.link === 'DISCONNECTED' && !('helm_mode' in r);
    if (r.nav && Number.isFinite(r.nav.x_m)) {
      v.nav = { ...r.nav, link: r.link, vehicle_id: r.id };
      pushTrail(v, r.nav.x_m, r.nav.y_m);
    } else if (v.stored) {
      v.nav = null;
    }
    v.helm = v.stored ? null : helmOf(r);
  }
  changed();
}

/** The ids of the station's live vehicles in a GET /health answer: `vehicles`, or on an older
 *  station its one `vehicle_id`. */
export function fleetIdsOf(health) {
  if (Array.isArray(health?.vehicles)) return health.vehicles.filter((id) => typeof id === 'string');
  return health?.vehicle_id ? [health.vehicle_id] : [];
}

/** The station's live vehicles (GET /health `vehicles`; an older station names its one). */
export function noteFleetIds(ids) {
  if (ids.length === state.fleetIds.length && ids.every((id, i) => id === state.fleetIds[i])) return;
  state.fleetIds = ids;
  for (const id of ids) entry(id);
  changed();
}

/** The vehicles to list: the station's live ones in its order, then the others by id. */
export function fleetList() {
  const live = state.fleetIds.filter((id) => state.fleet.has(id)).map((id) => state.fleet.get(id));
  const rest = [...state.fleet.values()].filter((v) => !state.fleetIds.includes(v.id)).sort((a, b) => a.id.localeCompare(b.id));
  return [...live, ...rest];
}

const QUIET_MS = 3000; // a vehicle heard LIVE but not since this long reads STALE

/** A vehicle's link as the page can vouch for it: the station's word, STALE when the stream has
 *  said nothing of it for a while. */
export function linkOf(v) {
  if (v.stored) return 'DISCONNECTED';
  if (v.link === 'LIVE' && v.heardMs > 0 && performance.now() - v.heardMs > QUIET_MS) return 'STALE';
  return v.link ?? '–';
}

/** Whether a vehicle is drawn on the map: it has a position and the station hears it. */
export function onMap(v) {
  return Boolean(v.nav) && v.link !== 'DISCONNECTED' && !v.stored;
}

/** Whether a message names vehicle `id` as a word ("alpha and bravo closing": alpha, not alp). */
export function namesVehicle(message, id) {
  const word = id.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');
  return new RegExp(`(^|[^\\w-])${word}($|[^\\w-])`).test(String(message ?? ''));
}

/** "hold at (12.0, -3.5) r 5 m, 1.2 m away": a vehicle command as an operator reads it. */
export function commandText(c) {
  if (!c) return 'none';
  const at = Number.isFinite(c.x_m) && Number.isFinite(c.y_m) ? ` (${c.x_m.toFixed(1)}, ${c.y_m.toFixed(1)})` : '';
  const what = { hold: `hold${at ? ` at${at}` : ''}`, go_to: `go to${at}`, return: `return to${at || ' the return point'}`, stop: 'all stop' }[c.kind] ?? String(c.kind);
  const radius = c.kind !== 'stop' && Number.isFinite(c.radius_m) ? ` r ${c.radius_m.toFixed(0)} m` : '';
  const speed = Number.isFinite(c.speed_mps) ? ` at ${c.speed_mps.toFixed(1)} m/s` : '';
  const away = c.kind !== 'stop' && Number.isFinite(c.distance_m) ? `, ${c.distance_m.toFixed(1)} m away` : '';
  return `${what}${radius}${speed}${away}`;
}

/** The helm mode and command of a vehicle in one line ("HOLDING · hold at (0.0, 0.0) r 5 m"). */
export function helmText(v) {
  if (v.stored) return 'not connected';
  const mode = v.helm?.mode ?? 'idle';
  const mission = v.helm?.mission_id ? ` · mission ${v.helm.mission_id}` : '';
  const cmd = v.helm?.command ? ` · ${commandText(v.helm.command)}` : '';
  return `${mode}${mission}${cmd}`;
}

// The dashboard's shared state and a tiny event bus. Views read the state and redraw on events;
// only stream.js and sync.js write the live parts, so there is one source of truth per field.

import { SeriesBuffer } from './timeseries.js';
import { firstAtOrAfter } from './bisect.js';

/** The live track: a fixed-size ring of (t, x, y). A 2-hour track at 10 Hz is 72,000 samples;
 *  beyond the capacity the oldest samples drop out (history is read from REST, not kept here). */
export class TrackBuffer {
  constructor(capacity) {
    this.capacity = capacity;
    this.t = new Float64Array(capacity);
    this.x = new Float64Array(capacity);
    this.y = new Float64Array(capacity);
    this.start = 0;   // index of the oldest sample
    this.length = 0;
    this.total = 0;   // samples pushed since the last clear (absolute index of the next one)
    this.epoch = 0;   // bumped by clear(), so derived data knows to start over
    this.version = 0; // bumped on every change so renderers can skip unchanged frames
  }

  clear() {
    this.start = 0;
    this.length = 0;
    this.total = 0;
    this.epoch++;
    this.version++;
  }

  push(t, x, y) {
    const i = (this.start + this.length) % this.capacity;
    this.t[i] = t;
    this.x[i] = x;
    this.y[i] = y;
    if (this.length < this.capacity) this.length++;
    else this.start = (this.start + 1) % this.capacity;
    this.total++;
    this.version++;
  }

  last() {
    if (this.length === 0) return null;
    const i = (this.start + this.length - 1) % this.capacity;
    return { t: this.t[i], x: this.x[i], y: this.y[i] };
  }

  /** Oldest-first copies as plain typed arrays (what the plot takes) of samples [from, to)
   *  (0 = oldest). */
  arrays(from = 0, to = this.length) {
    const n = Math.max(0, Math.min(to, this.length) - from);
    const xs = new Float64Array(n);
    const ys = new Float64Array(n);
    for (let k = 0; k < n; k++) {
      const i = (this.start + from + k) % this.capacity;
      xs[k] = this.x[i];
      ys[k] = this.y[i];
    }
    return { x: xs, y: ys };
  }

  /** Index (0 = oldest) of the first sample at or after time t; length when none. */
  indexAtOrAfter(t) {
    return firstAtOrAfter(this.length, (i) => this.t[(this.start + i) % this.capacity], t);
  }
}

export const TRACK_CAPACITY = 72000;
// The Live time series: an hour at 10 Hz (the longest window offered is 30 minutes).
export const SERIES_CAPACITY = 36000;

export const state = {
  sessionId: null,       // the server's session; a new one means it restarted
  serverVersion: null,
  vehicleId: null,       // the selected vehicle: every view but the fleet's is of it
  vehicle: null,         // GET /vehicles/{vid} (max speed, kind …)
  fleetIds: [],          // the station's live vehicles, in its order (GET /health `vehicles`)
  // Every vehicle heard of, by id (fleet.js): {id, kind, link, nav, helm, trail, …}; bounded.
  fleet: new Map(),
  link: 'DISCONNECTED',  // LIVE | STALE | DISCONNECTED, from the socket and the nav age
  nav: null,             // latest nav message data
  navWallMs: 0,          // performance.now() when it arrived
  helm: null,            // latest helm message data
  mission: null,         // GET /missions/{id} of the current (running or latest) mission
  missions: [],          // GET /missions
  models: [],            // GET /vehicles/{vid}/models
  turn: null,            // the turn in progress: {speed, dheading, goalHeading, start:{t,x,y,heading}, predictions}
  ongoing: null,         // GET /maneuvers/ongoing of the running turn (deviation.js), null between turns
  current: null,         // the station's estimate of the current (stream `current`, GET /vehicles/{vid}/current)
  // The operator's choice for Live's predictions (frame.js): current auto|live|none, speed
  // reference auto|over_ground|through_water; auto leaves it to the station (over ground).
  predictionFrame: { current: 'auto', speedReference: 'auto' },
  shownTurn: null,       // the turn drawn in Live: the one in progress, else the last one (ended: true)
  lastTurn: null,        // the last finished / aborted turn event
  recordedTurns: [],     // raw paths of the current mission's stored turns (history from REST)
  conditioningSinceT: null, // sim time the helm entered CONDITIONING
  events: [],            // the event log, newest last, bounded
  eventLevels: new Map(), // event kind -> 'info' | 'warning', from the stream's hello
  track: new TrackBuffer(TRACK_CAPACITY),
  series: new SeriesBuffer(SERIES_CAPACITY), // heading, speed, their desired values, yaw rate
  turnMarks: [],         // [{t, label}] turn starts of the current mission, for the time series
  turnMarksMission: null, // the mission turnMarks belong to
  previousTrack: null,   // {missionId, x, y}: the track of the mission before, drawn faded (tracks.js)
  okTurns: 0,            // stored ok turns of the vehicle (0: the CKT and the comparison 404)
  datum: null,           // {lat_deg, lon_deg} of avk serve --datum (GET /health), else null
  traffic: null,         // GET /traffic: the AIS contacts the station watches (traffic.js)
  testFeed: false,       // a ?test=1 hook feeds nav (the stream's nav is dropped meanwhile)
};

export const MAX_EVENTS = 500;

const listeners = new Map();

export function on(event, fn) {
  if (!listeners.has(event)) listeners.set(event, new Set());
  listeners.get(event).add(fn);
  return () => listeners.get(event).delete(fn);
}

export function emit(event, data) {
  const set = listeners.get(event);
  if (!set) return;
  for (const fn of set) {
    try {
      fn(data);
    } catch (e) {
      // One broken view must not stop the others from updating.
      console.warn(`handler for ${event} failed`, e);
    }
  }
}

export function addEvent(e) {
  state.events.push(e);
  if (state.events.length > MAX_EVENTS) state.events.splice(0, state.events.length - MAX_EVENTS);
  emit('events', state.events);
}

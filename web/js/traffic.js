// AIS traffic on the Live map (GET /api/v1/traffic, docs/ais.md): every vessel the station
// watches through gpsd, an arrow along its course (a circle when it reports none) with its name or
// MMSI. Polled every 2 s while the station watches a source, at which AIS's fastest reports
// (2 s under way) show within one update; every 30 s while it does not, since a restarted station
// may have one.
import { getJson } from './api.js';
import { state, emit } from './state.js';
import { C } from './plots.js';

const WATCHING_MS = 2000;
const IDLE_MS = 30000;
let timer = null;

export function initTraffic() {
  if (timer === null) poll();
}

async function poll() {
  let next = IDLE_MS;
  try {
    const t = await getJson('/traffic');
    // An unchanged answer (a station that watches nothing) redraws nothing.
    if (JSON.stringify(t) !== JSON.stringify(state.traffic)) {
      state.traffic = t;
      emit('traffic', t);
    }
    if (t.watching) next = WATCHING_MS;
  } catch {
    // The link badge says when the station is away; the next poll tries again.
  }
  timer = setTimeout(poll, next);
}

// The trace of the last answer: Live redraws at 10 Hz through Plotly's traces-only path, which
// takes any new array but x and y for a change of the whole figure, so the trace keeps its
// identity until a new answer arrives.
let cached = { traffic: undefined, trace: null };

/** The contacts as one Plotly trace: hidden from the legend while the station watches nothing. */
export function trafficTrace() {
  if (cached.traffic !== state.traffic) cached = { traffic: state.traffic, trace: buildTrace() };
  return cached.trace;
}

function buildTrace() {
  const contacts = state.traffic?.contacts ?? [];
  const label = (c) => c.name || String(c.mmsi);
  return {
    type: 'scatter',
    mode: 'markers+text',
    name: `AIS (${contacts.length})`,
    x: contacts.map((c) => c.x_m),
    y: contacts.map((c) => c.y_m),
    text: contacts.map(label),
    textposition: 'top center',
    textfont: { size: 11, color: C.black },
    marker: {
      symbol: contacts.map((c) => (c.course_deg === null ? 'circle' : 'arrow')),
      angle: contacts.map((c) => c.course_deg ?? 0),
      size: 16,
      color: C.sky,
      line: { color: C.black, width: 1.5 },
    },
    customdata: contacts.map((c) => [c.mmsi, c.speed_mps ?? NaN, c.course_deg ?? NaN, c.age_s]),
    hovertemplate:
      '%{text}<br>MMSI %{customdata[0]}<br>%{customdata[1]:.1f} m/s toward %{customdata[2]:.0f}°' +
      '<br>heard %{customdata[3]:.0f} s ago<extra>AIS</extra>',
    showlegend: Boolean(state.traffic?.watching),
    visible: state.traffic?.watching ? true : 'legendonly',
  };
}

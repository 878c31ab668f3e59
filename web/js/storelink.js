// The station's link to its store (GET /health `store`, docs/postgresql.md). A station that stores
// into a shared PostgreSQL database names the engine in the header; while it cannot reach the
// server it keeps flying the mission and records into a local spool file, and a bar under the
// header (every view) says so, with the writes waiting there and the last error on hover. The bar
// cannot be dismissed: it is a state, not news, and it goes when the station is connected again
// (the spool replayed). A SQLite station shows nothing of this.
//
// /health is read at every catch-up (sync.js emits `clock` with it); a PostgreSQL station's is read
// again every 2 s (the server answers /health on its I/O threads), a SQLite station's never.

import { getJson } from './api.js';
import { state, on } from './state.js';

const POLL_MS = 2000;

let store = null; // the last `store` of /health, null before one (or from an older server)
let timer = null;

/** What the page shows of a /health `store`: the engine's label for the header (null for SQLite
 *  and an older server), whether the station spools, and the bar's text and tooltip. */
export function storeNotice(s) {
  const engine = s?.engine === 'postgresql' ? 'PostgreSQL' : null;
  if (s?.state !== 'spooling') return { engine, spooling: false, text: '', title: '' };
  const n = Number.isFinite(s.spooled) && s.spooled >= 0 ? s.spooled : null;
  const waiting = n === null ? 'writes waiting' : `${n} ${n === 1 ? 'write' : 'writes'} waiting`;
  const text = `Database unreachable — recording into the local spool (${waiting}); they are written when the server is back`;
  const title = [s.last_error ? `Last error: ${s.last_error}` : 'The database server cannot be reached', s.spool ? `Spool: ${s.spool}` : null]
    .filter(Boolean)
    .join('\n');
  return { engine, spooling: true, text, title };
}

/** Whether the page reads /health on its own for this `store`: only a PostgreSQL station's link
 *  changes while the page is open (a SQLite file is always there). */
export function pollsHealth(s) {
  return s?.engine === 'postgresql' || s?.state === 'spooling';
}

function set(e, text, title) {
  if (!e) return;
  if (e.textContent !== text) e.textContent = text;
  if (e.title !== title) e.title = title;
}

function render() {
  const n = storeNotice(store);
  const bar = document.getElementById('store-bar');
  if (bar) {
    set(document.getElementById('store-text'), n.text, '');
    if (bar.title !== n.title) bar.title = n.title; // the last error on hover, over the whole bar
    if (bar.hidden === n.spooling) bar.hidden = !n.spooling;
  }
  const badge = document.getElementById('store-engine');
  if (badge) {
    set(badge, n.engine ? `db: ${n.engine}${n.spooling ? ' ⚠ spooling' : ''}` : '', n.engine ? `The station stores into a shared ${n.engine} database${n.spooling ? ': unreachable, recording into the local spool' : ': connected'}` : '');
    badge.dataset.state = n.spooling ? 'spooling' : 'connected';
    if (badge.hidden === Boolean(n.engine)) badge.hidden = !n.engine;
  }
}

function apply(s) {
  const next = s ?? null;
  if (JSON.stringify(next) !== JSON.stringify(store)) {
    store = next;
    render();
  }
  schedule();
}

function schedule() {
  clearTimeout(timer);
  timer = pollsHealth(store) ? setTimeout(poll, POLL_MS) : null;
}

async function poll() {
  timer = null;
  // Without the stream the station itself is away (the link badge says so), and a hidden tab
  // needs no news: the catch-up on reconnection, or the next poll, reads /health again.
  if (state.link !== 'DISCONNECTED' && !document.hidden) {
    try {
      apply((await getJson('/health')).store);
      return;
    } catch {
      // The next poll tries again.
    }
  }
  if (timer === null) schedule();
}

export function initStoreLink() {
  on('clock', (health) => apply(health?.store));
}

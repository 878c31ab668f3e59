// The live stream (WebSocket /api/v1/stream). Reconnects by itself with exponential backoff and
// jitter; each (re)connection is reported with the hello's session_id so the caller can tell a
// server restart (new session) from a dropped connection and re-read the state over REST.
// Browsers cannot set headers on a WebSocket, so the token (needed off loopback) goes in the
// query (?token=), which the server accepts on the upgrade only.

import { getToken } from './auth.js';

const TOPICS = ['nav', 'helm', 'mission', 'turn', 'status', 'current'];
const MIN_DELAY_MS = 500;
const MAX_DELAY_MS = 10000;

export class Stream {
  /**
   * @param {object} handlers onHello(hello), onMessage(msg), onOpen(), onClose(event)
   */
  constructor(handlers) {
    this.handlers = handlers;
    this.ws = null;
    this.delay = MIN_DELAY_MS;
    this.timer = null;
    this.stopped = false;
    this.started = false;
    this.open = false;
    this.lastSeq = {}; // per topic, to notice gaps
    this.gaps = 0;
    this.maxHz = null; // the telemetry rate asked of the server per vehicle; null: all of it
  }

  /** Asks the server for at most hz nav and helm messages a second per vehicle (null: every
   *  one), now and on every reconnection. */
  setTelemetryRate(hz) {
    if (hz === this.maxHz) return;
    this.maxHz = hz;
    if (this.open && this.ws) this.ws.send(JSON.stringify({ max_hz: hz ?? 0 }));
  }

  start() {
    this.stopped = false;
    this.started = true;
    this.connect();
    // A tab brought back to the front should not wait out a long backoff.
    document.addEventListener('visibilitychange', () => {
      if (!document.hidden && !this.open && !this.stopped) this.reconnectNow();
    });
    window.addEventListener('online', () => this.reconnectNow());
  }

  stop() {
    this.stopped = true;
    clearTimeout(this.timer);
    if (this.ws) this.ws.close(1000);
  }

  reconnectNow() {
    if (!this.started || this.stopped) return; // start() connects
    clearTimeout(this.timer);
    this.delay = MIN_DELAY_MS;
    if (!this.ws || this.ws.readyState === WebSocket.CLOSED) this.connect();
  }

  connect() {
    const proto = window.location.protocol === 'https:' ? 'wss:' : 'ws:';
    let ws;
    try {
      const token = getToken();
      const query = token ? `?token=${encodeURIComponent(token)}` : '';
      ws = new WebSocket(`${proto}//${window.location.host}/api/v1/stream${query}`);
    } catch (e) {
      this.scheduleReconnect();
      return;
    }
    this.ws = ws;
    ws.addEventListener('open', () => {
      this.open = true;
      ws.send(JSON.stringify(this.maxHz ? { subscribe: TOPICS, max_hz: this.maxHz } : { subscribe: TOPICS }));
      this.handlers.onOpen?.();
    });
    ws.addEventListener('message', (ev) => {
      let msg;
      try {
        msg = JSON.parse(ev.data);
      } catch {
        return;
      }
      if (msg.type === 'hello') {
        this.delay = MIN_DELAY_MS; // a server that says hello is up: start the backoff afresh
        this.lastSeq = {};
        this.handlers.onHello?.(msg);
        return;
      }
      if (msg.type) return; // subscribed / error acknowledgements
      if (typeof msg.seq === 'number') {
        const prev = this.lastSeq[msg.topic];
        if (prev !== undefined && msg.seq > prev + 1 && msg.topic !== 'nav' && msg.topic !== 'helm' && msg.topic !== 'current') {
          // Telemetry is latest-value-wins, so nav/helm gaps are expected; event gaps are not.
          this.gaps++;
          this.handlers.onGap?.(msg.topic);
        }
        this.lastSeq[msg.topic] = msg.seq;
      }
      this.handlers.onMessage?.(msg);
    });
    ws.addEventListener('close', (ev) => {
      if (this.ws !== ws) return;
      this.open = false;
      this.handlers.onClose?.(ev);
      if (!this.stopped) this.scheduleReconnect();
    });
    // 'error' is always followed by 'close', where the reconnect is scheduled.
  }

  scheduleReconnect() {
    clearTimeout(this.timer);
    const jitter = 0.5 + Math.random() * 0.5;
    const wait = this.delay * jitter;
    this.delay = Math.min(MAX_DELAY_MS, this.delay * 2);
    this.timer = setTimeout(() => this.connect(), wait);
  }
}

// Start-up: the token, the plots' frames, the views, the router, the REST catch-up and the stream.

import { state, on } from './state.js';
import { adoptTokenFromUrl, initTokenBar, onTokenChange } from './auth.js';
import { framePlot } from './plots.js';
import { Stream } from './stream.js';
import { attachStream, catchUp, onHello, onMessage, onStreamClose, onGap, updateLink } from './sync.js';
import { initRouter } from './router.js';
import { initLive, showLive } from './live.js';
import { initTraffic } from './traffic.js';
import { initReplay, showReplay } from './replay.js';
import { initMission, showMission } from './mission.js';
import { initCkt, showCkt } from './ckt.js';
import { initCompare, showCompare } from './compare.js';
import { initModel, showModel } from './model.js';
import { initExport, showExport } from './export.js';
import { initEncounter, showEncounter } from './encounter.js';
import { initDeviation } from './deviation.js';
import { installTestHooks } from './testhooks.js';
import { initTheme } from './theme.js';
import { initBanner } from './banner.js';
import { initEventLog } from './eventlog.js';
import { initAlarms } from './alarms.js';
import { initKeys } from './keys.js';
import { initFleetPanel } from './fleetpanel.js';
import { initCommands } from './commands.js';
import { initStoreLink } from './storelink.js';

function renderBadge(link) {
  const b = document.getElementById('link-badge');
  b.textContent = link;
  b.className = `badge badge-${link.toLowerCase()}`;
  b.title = {
    LIVE: 'Stream connected, navigation fresh',
    STALE: 'Stream connected, but no fresh navigation from the vehicle',
    DISCONNECTED: 'No stream: reconnecting with backoff',
  }[link];
}

function renderVehicle() {
  const v = state.vehicle;
  document.getElementById('vehicle-name').textContent = v
    ? `${v.id} (${v.kind ?? 'kind unknown'}, ≤ ${v.max_speed_mps ?? '?'} m/s)`
    : state.vehicleId ?? 'no vehicle';
  // The kind in the Vehicle panel too: which plant (or real boat) the track comes from matters
  // when reading its turns.
  const kind = document.getElementById('live-kind');
  if (kind) kind.textContent = v?.kind ?? '–';
}

function main() {
  adoptTokenFromUrl();
  const params = new URLSearchParams(window.location.search);
  if (params.get('test') === '1') installTestHooks();
  initTokenBar();
  initTheme(); // before anything is drawn: the plots take its colours
  for (const el of document.querySelectorAll('.plot')) framePlot(el);
  initLive();
  initFleetPanel();
  initCommands();
  initTraffic();
  initReplay();
  initMission();
  initCkt();
  initCompare();
  initModel();
  initExport();
  initEncounter();
  initDeviation();
  initEventLog();
  initBanner();
  initAlarms();
  initStoreLink();
  on('link', renderBadge);
  on('vehicle', renderVehicle);
  renderBadge(state.link);

  initRouter({ live: showLive, replay: showReplay, mission: showMission, ckt: showCkt, compare: showCompare, model: showModel, encounter: showEncounter, export: showExport });
  initKeys();

  const stream = new Stream({
    onHello,
    onMessage,
    onClose: onStreamClose,
    onOpen: updateLink,
    onGap,
  });
  attachStream(stream);
  // A stream refused for want of the token (off loopback) retries at once with the one entered.
  onTokenChange(() => {
    if (!stream.open) stream.reconnectNow();
  });
  // REST first (the views have something to show at once), then the stream, whose hello triggers
  // another catch-up that fills anything missed in between.
  catchUp()
    .catch((e) => console.warn('initial read failed; the stream will retry', e))
    .finally(() => stream.start());
  // The link badge ages by itself: no message for 2 s turns LIVE into STALE.
  setInterval(updateLink, 500);
}

main();

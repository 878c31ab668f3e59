// AIS traffic on the Live map: the example traffic scenario encoded as AIVDM (make_ais_log),
// served by a real gpsd through gpsfake on a free loopback port, watched by
// `avk serve --sim --datum … --ais 127.0.0.1:PORT`. Every vessel must appear on the Live plot with
// its name, where GET /traffic places it, within one poll of the page after the API has it.
//
// Environment: AVK_BINARY (default build/server/avk), AVK_CHROMIUM (browser.mjs).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, execFileSync } from 'node:child_process';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';

import { until } from './wait.mjs';
import { startAvkServer, freeLoopbackPort } from './avk_server.mjs';
import { AVK, repo, webDir, launchBrowser, tearDown, killServerOnExit, showView } from './browser.mjs';

const MAKE_AIS_LOG = path.join(path.dirname(AVK), '..', 'tests', 'make_ais_log');
const SCENARIO = path.join(repo, 'examples', 'traffic-charles.json');
const DATUM = '42.358456,-71.087589';

const tmp = mkdtempSync(path.join(tmpdir(), 'avk-web-traffic-'));
let gpsfake = null;
let server = null;
let b = null;
let page = null;


before(async () => {
  const log = path.join(tmp, 'traffic.aivdm');
  // The vessels at one moment, played over and over: they stay where the station first puts them.
  writeFileSync(log, execFileSync(MAKE_AIS_LOG, [SCENARIO, '0', '2']));
  const port = await freeLoopbackPort();
  // Its own process group, gpsd included, so that one signal ends both.
  gpsfake = spawn('gpsfake', ['-q', '-c', '0.05', '-P', String(port), '-W', '600', log], { detached: true, stdio: 'ignore' });
  b = await launchBrowser();
  server = await startAvkServer(AVK, ['serve', '--db', path.join(tmp, 'station.db'), '--sim', '--datum', DATUM, '--ais', `127.0.0.1:${port}`, '--port', '0', '--web', webDir]);
  page = await b.newPage();
});

after(async () => {
  if (gpsfake) {
    try {
      process.kill(-gpsfake.pid, 'SIGKILL');
    } catch {
      // already gone
    }
  }
  await tearDown({ browser: b?.browser, server, dir: tmp });
});
killServerOnExit(() => server);
process.on('exit', () => {
  try {
    if (gpsfake) process.kill(-gpsfake.pid, 'SIGKILL');
  } catch {
    // already gone
  }
});

test('every AIS vessel is drawn on the Live map with its name, where the station places it', async () => {
  const headers = { Authorization: `Bearer ${server.token}` };
  const api = await until('the station to hear every vessel by name', async () => {
    const t = await (await fetch(`${server.base}/api/v1/traffic`, { headers })).json();
    return t.contacts.length === 4 && t.contacts.every((c) => c.name) ? t : null;
  }, 60000);
  assert.equal(api.watching, true);
  assert.equal(api.link_up, true);

  await page.goto(`${server.base}/?token=${server.token}#live`);
  await showView(page, 'live');
  const drawn = await until('the Live plot to draw the four vessels', () =>
    page.evaluate(() => {
      const t = document.getElementById('live-plot')?.data?.find((d) => String(d.name).startsWith('AIS'));
      return t && t.x.length === 4 && t.text.every((s) => s && !/^\d+$/.test(s)) ? { x: t.x, y: t.y, text: t.text, visible: t.visible } : null;
    }), 30000);
  assert.equal(drawn.visible, true);
  const now = await (await fetch(`${server.base}/api/v1/traffic`, { headers })).json();
  for (const c of now.contacts) {
    const i = drawn.text.indexOf(c.name);
    assert.ok(i >= 0, `${c.name} is not drawn (drawn: ${drawn.text.join(', ')})`);
    const off = Math.hypot(drawn.x[i] - c.x_m, drawn.y[i] - c.y_m);
    assert.ok(off < 0.01, `${c.name} drawn ${off.toFixed(3)} m from where the station places it`);
  }
  assert.deepEqual([...drawn.text].sort(), now.contacts.map((c) => c.name).sort());
});

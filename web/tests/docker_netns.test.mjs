// The dashboard as the Docker deployment serves it: `avk serve` started with the Dockerfile's own
// ENTRYPOINT (`--bind 0.0.0.0`), and Debian's Chromium driving the page from a network namespace
// this test creates, so the browser is a non-loopback client as it is through `docker run -p`. The server then wants the token for reads and for the stream too.
//
// The namespace is joined to the root namespace by a veth pair with private 10.213.x.y addresses
// that exist only on this machine; nothing leaves it. Needs root and iproute2 (`ip netns`): CI
// runs as root; anywhere else the test fails and says why, it does not skip.
//
// Environment: AVK_BINARY (default build/server/avk), AVK_CHROMIUM (default /usr/bin/chromium).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, execFileSync } from 'node:child_process';
import { chmodSync, existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:net';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { sleep, until } from './wait.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const webDir = path.resolve(here, '..');
const repo = path.resolve(webDir, '..');
const AVK = path.resolve(process.env.AVK_BINARY || path.join(repo, 'build/server/avk'));
const CHROMIUM = process.env.AVK_CHROMIUM || '/usr/bin/chromium';

// One /30 per process: sibling runs (other worktrees, ctest -j) never share names or addresses.
const id = process.pid % 100000;
const NS = `avkdn${id}`;
const VETH_ROOT = `avkd${id}r`; // interface names are at most 15 characters
const VETH_NS = `avkd${id}n`;
const SUBNET_HI = (process.pid >> 6) & 255;
const SUBNET_LO = (process.pid & 63) * 4;
const ROOT_IP = `10.213.${SUBNET_HI}.${SUBNET_LO + 1}`;
const NS_IP = `10.213.${SUBNET_HI}.${SUBNET_LO + 2}`;

const tmp = mkdtempSync(path.join(tmpdir(), 'avk-docker-netns-'));
let server = null; // {child, log, exited}
let browser = null;
let port = 0;
let token = '';
let vehicleId = '';
let netnsUp = false;
const pageErrors = [];

// ---------------------------------------------------------------- helpers

function ip(...args) {
  return execFileSync('ip', args, { stdio: ['ignore', 'pipe', 'pipe'] }).toString();
}

/** Removes the namespace and the veth pair (deleting one end deletes both); never throws. */
function teardownNetns() {
  for (const args of [['link', 'del', VETH_ROOT], ['netns', 'del', NS]]) {
    try {
      execFileSync('ip', args, { stdio: 'ignore' });
    } catch {
      // already gone
    }
  }
  netnsUp = false;
}

function setupNetns() {
  teardownNetns(); // a run killed before its clean-up left these behind
  netnsUp = true;
  ip('netns', 'add', NS);
  ip('link', 'add', VETH_ROOT, 'type', 'veth', 'peer', 'name', VETH_NS);
  ip('link', 'set', VETH_NS, 'netns', NS);
  ip('addr', 'add', `${ROOT_IP}/30`, 'dev', VETH_ROOT);
  ip('link', 'set', VETH_ROOT, 'up');
  ip('netns', 'exec', NS, 'ip', 'addr', 'add', `${NS_IP}/30`, 'dev', VETH_NS);
  ip('netns', 'exec', NS, 'ip', 'link', 'set', VETH_NS, 'up');
  ip('netns', 'exec', NS, 'ip', 'link', 'set', 'lo', 'up');
}

/** The Dockerfile's ENTRYPOINT (exec form) as an argument list. */
function dockerEntrypoint() {
  const text = readFileSync(path.join(repo, 'Dockerfile'), 'utf8');
  const m = text.match(/^ENTRYPOINT\s+(\[.*\])\s*$/m);
  assert.ok(m, 'the Dockerfile has no exec-form ENTRYPOINT ["avk", …]');
  const argv = JSON.parse(m[1]);
  assert.equal(argv[0], 'avk', `the ENTRYPOINT runs ${argv[0]}, not avk`);
  return argv;
}

/** The ENTRYPOINT with this machine's paths: the built binary, a temporary database, this web/
 *  and a free port (8080 may be taken by a parallel run). Everything else stays as written. */
function entrypointHere(argv, freePort) {
  const out = [AVK];
  const replace = { '--db': path.join(tmp, 'station.db'), '--web': webDir, '--port': String(freePort) };
  for (let i = 1; i < argv.length; i++) {
    out.push(argv[i]);
    if (argv[i] in replace && i + 1 < argv.length) {
      out.push(replace[argv[i]]);
      i++;
    }
  }
  return out;
}

function freePort() {
  return new Promise((resolve, reject) => {
    const s = createServer();
    s.once('error', reject);
    s.listen(0, '0.0.0.0', () => {
      const p = s.address().port;
      s.close(() => resolve(p));
    });
  });
}

async function startServer(argv) {
  const child = spawn(argv[0], argv.slice(1), { stdio: ['ignore', 'pipe', 'pipe'] });
  const s = { child, log: '', exited: null };
  const onData = (chunk) => {
    s.log = (s.log + chunk.toString()).slice(-20000); // keep draining: a full pipe would block it
  };
  child.stdout.on('data', onData);
  child.stderr.on('data', onData);
  child.on('exit', (code, sig) => {
    s.exited = { code, sig };
  });
  server = s;
  // Health from loopback needs no token; the token file is written before the server listens.
  const health = await until('avk serve to answer /health on loopback', async () => {
    if (s.exited) throw new Error(`avk serve exited (${s.exited.code ?? s.exited.sig}):\n${s.log}`);
    const res = await fetch(`http://127.0.0.1:${port}/api/v1/health`, { signal: AbortSignal.timeout(5000) });
    return res.ok ? res.json() : null;
  }, 30000);
  return health;
}

async function stopServer() {
  if (!server || server.exited) return;
  const exited = new Promise((r) => server.child.once('exit', r));
  server.child.kill('SIGTERM');
  if (!(await Promise.race([exited.then(() => true), sleep(8000).then(() => false)]))) {
    server.child.kill('SIGKILL');
    await Promise.race([exited, sleep(3000)]);
  }
}

async function newPage(context) {
  const p = await context.newPage();
  await p.setViewportSize({ width: 1280, height: 800 });
  p.setDefaultTimeout(15000);
  p.on('pageerror', (e) => pageErrors.push(e.message));
  return p;
}

// ---------------------------------------------------------------- set-up and tear-down

// Clean-up whatever ends the run: the namespace and the server never outlive it.
process.on('exit', () => {
  if (server && !server.exited) server.child.kill('SIGKILL');
  if (netnsUp) teardownNetns();
});
for (const sig of ['SIGINT', 'SIGTERM']) {
  process.once(sig, () => {
    if (server && !server.exited) server.child.kill('SIGKILL');
    if (netnsUp) teardownNetns();
    process.exit(130);
  });
}

before(async () => {
  assert.ok(existsSync(AVK), `the avk binary is missing: ${AVK} (build it, or set AVK_BINARY)`);
  assert.ok(existsSync(CHROMIUM), `Chromium is missing: ${CHROMIUM} (scripts/setup installs Debian's chromium)`);
  assert.ok(existsSync(path.join(webDir, 'node_modules/playwright-core')), 'web/node_modules is missing: run scripts/web-deps');
  assert.equal(
    process.getuid?.(),
    0,
    'this test creates a network namespace and a veth pair, which needs root (CI runs it as root); ' +
      'run it as root or with sudo: it does not skip',
  );
  try {
    ip('netns', 'list');
  } catch (e) {
    assert.fail(`\`ip netns\` is unavailable (install iproute2): ${e.message}`);
  }
  setupNetns();

  port = await freePort();
  const argv = entrypointHere(dockerEntrypoint(), port);
  assert.deepEqual(argv.slice(argv.indexOf('--bind'), argv.indexOf('--bind') + 2), ['--bind', '0.0.0.0']);
  const health = await startServer(argv);
  vehicleId = health.vehicle_id;
  assert.ok(vehicleId, 'the Docker server runs a simulated vehicle (--sim)');
  token = readFileSync(path.join(tmp, 'station.db.token'), 'utf8').trim();
  assert.ok(token.length >= 16, 'the token file holds a token');

  // Chromium in the namespace: playwright-core starts the executable it is given, so that is a
  // wrapper which enters the namespace first (its debugging pipe, fds 3 and 4, is inherited).
  const wrapper = path.join(tmp, 'chromium-in-netns');
  writeFileSync(wrapper, `#!/bin/sh\nexec ip netns exec ${NS} ${CHROMIUM} "$@"\n`);
  chmodSync(wrapper, 0o755);
  const { chromium } = await import('playwright-core');
  browser = await chromium.launch({
    executablePath: wrapper,
    headless: true,
    timeout: 30000,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
});

after(async () => {
  await Promise.race([browser?.close(), sleep(10000)]).catch(() => {});
  await stopServer().catch(() => {});
  teardownNetns();
  rmSync(tmp, { recursive: true, force: true });
});

const base = () => `http://${ROOT_IP}:${port}`;

// ---------------------------------------------------------------- the tests

test('from the namespace the server is off loopback: a read without the token is 401', async () => {
  const context = await browser.newContext();
  try {
    const p = await newPage(context);
    // A bare API read from the page's origin: nothing of the dashboard's own code involved.
    await p.goto(`${base()}/favicon.svg`, { waitUntil: 'load', timeout: 20000 });
    const status = await p.evaluate(async () => (await fetch('/api/v1/health')).status);
    assert.equal(status, 401, 'a non-loopback read without the token');
    const withToken = await p.evaluate(async (t) => (await fetch('/api/v1/health', { headers: { Authorization: `Bearer ${t}` } })).status, token);
    assert.equal(withToken, 200);
    // The stream: refused without the token, opened with it as ?token= (a browser cannot set
    // headers on a WebSocket).
    const opened = (q) =>
      p.evaluate(
        (query) =>
          new Promise((resolve) => {
            const ws = new WebSocket(`ws://${location.host}/api/v1/stream${query}`);
            ws.onopen = () => {
              ws.close();
              resolve(true);
            };
            ws.onclose = () => resolve(false);
          }),
        q,
      );
    assert.equal(await opened(''), false, 'the stream without the token');
    assert.equal(await opened(`?token=${encodeURIComponent(token)}`), true, 'the stream with ?token=');
  } finally {
    await context.close();
  }
});

test('with ?token= the page shows the vehicle, reads, streams and starts a mission', { timeout: 90000 }, async () => {
  const context = await browser.newContext();
  try {
    const p = await newPage(context);
    const refused = [];
    p.on('response', (r) => {
      if (r.status() === 401) refused.push(r.url());
    });
    await p.goto(`${base()}/?token=${token}#live`, { waitUntil: 'load', timeout: 20000 });
    await p.waitForFunction((vid) => document.getElementById('vehicle-name')?.textContent.startsWith(vid), vehicleId, { timeout: 20000 });
    // LIVE needs the stream open and fresh navigation from it.
    await p.waitForFunction(() => document.getElementById('link-badge')?.textContent === 'LIVE', null, { timeout: 20000 });
    assert.ok(await p.isHidden('#token-bar'), 'no token prompt: the page had the token');
    assert.deepEqual(refused, [], 'no request was refused');

    await p.evaluate(() => {
      window.location.hash = '#mission';
    });
    await p.waitForSelector('#view-mission:not([hidden])', { timeout: 5000 });
    await p.fill('#m-name', 'docker-netns');
    await p.fill('#m-speeds', '1.0');
    await p.fill('#m-dheadings', '40');
    await p.click('#m-start');
    await p.waitForFunction(() => /Mission \d+ started/.test(document.getElementById('m-result')?.textContent ?? ''), null, { timeout: 20000 });
    const missionId = Number((await p.textContent('#m-result')).match(/Mission (\d+)/)[1]);
    // The station agrees (read on loopback, outside the page).
    const m = await (await fetch(`http://127.0.0.1:${port}/api/v1/missions/${missionId}`)).json();
    assert.equal(m.name, 'docker-netns');
    assert.equal(m.vehicle_id, vehicleId);
    assert.deepEqual(refused, [], 'no request was refused');
    assert.deepEqual(pageErrors, [], 'no uncaught errors in the page');
  } finally {
    await context.close();
  }
});

test('without a token a read asks for it inline; once entered, reads and the stream work', { timeout: 90000 }, async () => {
  const context = await browser.newContext();
  try {
    const p = await newPage(context);
    await p.goto(`${base()}/#live`, { waitUntil: 'load', timeout: 20000 });
    await p.waitForSelector('#token-bar:not([hidden])', { timeout: 15000 });
    assert.equal(await p.evaluate(() => document.activeElement?.id), 'token-input', 'the token input has the focus');
    assert.equal(await p.locator('[role="dialog"], dialog[open]').count(), 0, 'no modal dialog');
    assert.equal(await p.textContent('#vehicle-name'), 'no vehicle', 'nothing was read yet');
    await p.fill('#token-input', token);
    await p.press('#token-input', 'Enter');
    await p.waitForFunction((vid) => document.getElementById('vehicle-name')?.textContent.startsWith(vid), vehicleId, { timeout: 20000 });
    await p.waitForFunction(() => document.getElementById('link-badge')?.textContent === 'LIVE', null, { timeout: 20000 });
    assert.ok(await p.isHidden('#token-bar'));
    assert.equal(await p.evaluate(() => sessionStorage.getItem('avk-token')), token);
  } finally {
    await context.close();
  }
});

test('a refused token is said to be refused, the bar stays, and another try with the right one works', { timeout: 120000 }, async () => {
  const context = await browser.newContext();
  try {
    const p = await newPage(context);
    const bar = () => p.evaluate(() => {
      const b = document.getElementById('token-bar');
      return { hidden: b.hidden, text: b.textContent.replace(/\s+/g, ' '), focus: document.activeElement?.id };
    });
    const refusedWith = (t) => p.waitForResponse((r) => r.status() === 401 && r.request().headers().authorization === `Bearer ${t}`, { timeout: 20000 });
    // A wrong token in the address (a mistyped link): the first read is refused, and the page
    // says it was this token, not that one is missing.
    const wrong = `${'0'.repeat(31)}1`;
    const firstRefusal = refusedWith(wrong);
    await p.goto(`${base()}/?token=${wrong}#live`, { waitUntil: 'load', timeout: 20000 });
    await firstRefusal;
    const first = await until('the bar saying the token was refused', async () => {
      const b = await bar();
      return !b.hidden && /token refused/i.test(b.text) ? b : null;
    }, 15000, 100);
    assert.equal(first.focus, 'token-input');
    // Another wrong one, entered in the bar: refused again, and the bar is still there for a third
    // try (it used to go away on submit, leaving DISCONNECTED and no mission, nothing said why).
    const secondRefusal = refusedWith('not-the-station-token');
    await p.fill('#token-input', 'not-the-station-token');
    await p.press('#token-input', 'Enter');
    await secondRefusal;
    const second = await until('the bar saying the second token was refused', async () => {
      const b = await bar();
      return !b.hidden && /token refused/i.test(b.text) && (await p.evaluate(() => document.getElementById('token-bar').dataset.refused)) === '2' ? b : null;
    }, 15000, 100);
    assert.equal(second.focus, 'token-input', 'the input keeps the focus for the next try');
    assert.equal(await p.getAttribute('#token-input', 'aria-describedby'), 'token-state token-help', 'the input is described by what the bar says');
    // The right one: taken, the bar goes, the page reads and streams.
    await p.fill('#token-input', token);
    await p.press('#token-input', 'Enter');
    await p.waitForFunction((vid) => document.getElementById('vehicle-name')?.textContent.startsWith(vid), vehicleId, { timeout: 20000 });
    await p.waitForFunction(() => document.getElementById('link-badge')?.textContent === 'LIVE', null, { timeout: 20000 });
    await until('the bar gone once the token is taken', async () => (await bar()).hidden, 10000, 100);
    assert.equal(await p.evaluate(() => sessionStorage.getItem('avk-token')), token);
  } finally {
    await context.close();
  }
});

// A real `avk serve` for the Node tests (browser and interop): started on a free port, its URL
// and control token read from what it prints, stopped with SIGTERM (SIGKILL if it hangs).

import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { createServer } from 'node:net';
import { slow, sleep } from './wait.mjs';

const SERVER_START_MS = slow(20000);

/** Starts `avk <args>`; resolves to {child, port, token, base, log} once it prints its URL. */
export function startAvkServer(avk, args) {
  return new Promise((resolve, reject) => {
    const child = spawn(avk, args, { stdio: ['ignore', 'pipe', 'pipe'] });
    const s = { child, port: null, token: null, base: null, log: '' };
    const timer = setTimeout(() => {
      child.kill('SIGKILL');
      reject(new Error(`avk serve did not print its URL within ${SERVER_START_MS} ms:\n${s.log}`));
    }, SERVER_START_MS);
    const onData = (chunk) => {
      s.log = (s.log + chunk.toString()).slice(-20000); // keep draining: a full pipe would block it
      const url = s.log.match(/AVK Station on http:\/\/127\.0\.0\.1:(\d+)\//);
      const tok = s.log.match(/dashboard with control: \S+\?token=([0-9A-Za-z_-]+)/);
      if (url && tok && !s.base) {
        clearTimeout(timer);
        s.port = Number(url[1]);
        s.token = tok[1];
        s.base = `http://127.0.0.1:${s.port}`;
        resolve(s);
      }
    };
    child.stdout.on('data', onData);
    child.stderr.on('data', onData);
    child.on('error', (e) => {
      clearTimeout(timer);
      reject(e);
    });
    child.on('exit', (code, sig) => {
      s.exited = { code, sig };
      if (!s.base) {
        clearTimeout(timer);
        reject(new Error(`avk serve exited (${code ?? sig}) before printing its URL:\n${s.log}`));
      }
    });
  });
}

export async function stopAvkServer(s) {
  if (!s || s.exited) return;
  const exited = new Promise((r) => s.child.once('exit', r));
  s.child.kill('SIGTERM');
  const killed = await Promise.race([exited.then(() => true), sleep(8000).then(() => false)]);
  if (!killed) {
    s.child.kill('SIGKILL');
    await Promise.race([exited, sleep(3000)]);
  }
}

/** A REST request to server `s` under /api/v1 with its token; resolves to the answer's JSON (null
 *  when empty) and fails naming the request and the status when it is not 2xx. */
export async function apiRequest(s, pathname, { method = 'GET', body } = {}) {
  const res = await fetch(`${s.base}/api/v1${pathname}`, {
    method,
    headers: { Authorization: `Bearer ${s.token}`, ...(body ? { 'Content-Type': 'application/json' } : {}) },
    body: body ? JSON.stringify(body) : undefined,
    signal: AbortSignal.timeout(slow(10000)),
  });
  const text = await res.text();
  assert.ok(res.ok, `${method} ${pathname}: ${res.status} ${text}`);
  return text ? JSON.parse(text) : null;
}

/** A loopback TCP port nobody listens on at the moment of asking (the kernel's pick for port 0). */
export function freeLoopbackPort() {
  return new Promise((resolve, reject) => {
    const s = createServer();
    s.on('error', reject);
    s.listen(0, '127.0.0.1', () => {
      const { port } = s.address();
      s.close(() => resolve(port));
    });
  });
}

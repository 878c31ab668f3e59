// Shared set-up of the browser tests that run their own station (the big e2e file keeps its own):
// where things are, Debian's Chromium through playwright-core (no browser download), pages that
// record console errors, view switching that waits for the view to be shown, and screenshots. A
// missing Chromium or web/node_modules is a failure, not a skip: CI installs both (scripts/setup,
// scripts/web-deps).

import assert from 'node:assert/strict';
import { existsSync, mkdirSync, copyFileSync, rmSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { slow, sleep, until } from './wait.mjs';
import { stopAvkServer } from './avk_server.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
export const webDir = path.resolve(here, '..');
export const repo = path.resolve(webDir, '..');
export const AVK = path.resolve(process.env.AVK_BINARY || path.join(repo, 'build/server/avk'));
export const SHOTS = path.resolve(process.env.AVK_SCREENSHOTS || path.join(repo, 'build/web-screenshots'));
export const DOC_SHOTS = path.join(repo, 'docs/screenshots');
export const CHROMIUM = process.env.AVK_CHROMIUM || '/usr/bin/chromium';

export function checkPrerequisites() {
  assert.ok(existsSync(AVK), `the avk binary is missing: ${AVK} (build it, or set AVK_BINARY)`);
  assert.ok(existsSync(CHROMIUM), `Chromium is missing: ${CHROMIUM} (scripts/setup installs Debian's chromium)`);
  assert.ok(
    existsSync(path.join(webDir, 'node_modules/playwright-core')) && existsSync(path.join(webDir, 'node_modules/plotly.js-dist-min/plotly.min.js')),
    'web/node_modules is missing: run scripts/web-deps (npm ci in web/)',
  );
  mkdirSync(SHOTS, { recursive: true });
}

/** The headless browser itself. */
export async function launchChromium() {
  const { chromium } = await import('playwright-core');
  return chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    timeout: slow(30000),
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
}

/** A page of `context` with the viewport, recording console errors and uncaught exceptions in
 *  `errors` ({console: [], page: []}) tagged with errors.phase. */
export async function openPage(context, viewport, errors) {
  const p = await context.newPage();
  await p.setViewportSize(viewport);
  p.setDefaultTimeout(slow(15000));
  p.on('console', (m) => {
    if (m.type() === 'error') errors.console.push({ text: m.text(), phase: errors.phase, url: m.location()?.url });
  });
  p.on('pageerror', (e) => errors.page.push({ text: `${e.message}\n${e.stack ?? ''}`, phase: errors.phase }));
  return p;
}

/** Checks the prerequisites and launches the browser; resolves to {browser, context,
 *  newPage(viewport), errors}, errors a flat list of every page's console errors and exceptions. */
export async function launchBrowser() {
  checkPrerequisites();
  const browser = await launchChromium();
  const context = await browser.newContext({ acceptDownloads: true });
  const recorded = { console: [], page: [], phase: '' };
  const newPage = (viewport = { width: 1280, height: 800 }) => openPage(context, viewport, recorded);
  return {
    browser,
    context,
    newPage,
    get errors() {
      return [...recorded.console.map((e) => e.text), ...recorded.page.map((e) => e.text)];
    },
  };
}

/** Closes the browser (bounded), stops the server and removes the test's folder, whatever
 *  happened; and never leaves the server behind if the runner is interrupted. */
export async function tearDown({ browser, server, dir }) {
  await Promise.race([browser?.close(), sleep(10000)]).catch(() => {});
  await stopAvkServer(server).catch(() => {});
  if (dir) rmSync(dir, { recursive: true, force: true });
}

export function killServerOnExit(getServer) {
  process.on('exit', () => {
    const s = getServer();
    if (s && !s.exited) s.child.kill('SIGKILL');
  });
}

/** Sets the address's view and checks it is shown, again until it is: under load a selector
 *  wait (which polls on animation frames) saw the view visible and still timed out. */
export async function showView(page, view) {
  await until(
    `the ${view} view`,
    () =>
      page.evaluate((v) => {
        if (window.location.hash !== `#${v}`) window.location.hash = `#${v}`;
        const el = document.getElementById(`view-${v}`);
        return el !== null && !el.hidden;
      }, view),
    5000,
    100,
  );
}
export const goView = showView;

/** A full-page screenshot into SHOTS; copied to docs/screenshots with AVK_UPDATE_DOC_SCREENSHOTS=1
 *  (a test run never leaves the checkout modified otherwise). */
export async function screenshot(page, name) {
  const file = path.join(SHOTS, `${name}.png`);
  await page.screenshot({ path: file, fullPage: true, timeout: slow(20000) });
  if (process.env.AVK_UPDATE_DOC_SCREENSHOTS === '1') {
    mkdirSync(DOC_SHOTS, { recursive: true });
    copyFileSync(file, path.join(DOC_SHOTS, `${name}.png`));
  }
  return file;
}

// Shared set-up of the browser tests: where things are, Debian's Chromium through playwright-core
// (no browser download), a page that records console errors, and view switching that waits for
// the view to be shown. A missing Chromium or web/node_modules is a failure, not a skip.

import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { slow, until } from './wait.mjs';

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
}

export async function launchBrowser() {
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

/** Sets the address's view and checks it is shown, again until it is. */
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

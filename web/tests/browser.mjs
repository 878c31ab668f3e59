// Debian's Chromium driven by playwright-core for the browser tests that run their own station
// (the big e2e file keeps its own set-up). A missing Chromium or web/node_modules is a failure, not
// a skip: CI installs both (scripts/setup, scripts/web-deps).

import assert from 'node:assert/strict';
import { existsSync, mkdirSync, copyFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { slow, until } from './wait.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
export const webDir = path.resolve(here, '..');
export const repo = path.resolve(webDir, '..');
export const AVK = path.resolve(process.env.AVK_BINARY || path.join(repo, 'build/server/avk'));
export const SHOTS = path.resolve(process.env.AVK_SCREENSHOTS || path.join(repo, 'build/web-screenshots'));
export const DOC_SHOTS = path.join(repo, 'docs/screenshots');
const CHROMIUM = process.env.AVK_CHROMIUM || '/usr/bin/chromium';

/** Launches the browser; resolves to {browser, context, newPage(viewport), errors}. errors
 *  collects console errors and page exceptions of every page it made. */
export async function launchBrowser() {
  assert.ok(existsSync(AVK), `the avk binary is missing: ${AVK} (build it, or set AVK_BINARY)`);
  assert.ok(existsSync(CHROMIUM), `Chromium is missing: ${CHROMIUM} (scripts/setup installs Debian's chromium)`);
  assert.ok(existsSync(path.join(webDir, 'node_modules/playwright-core')), 'web/node_modules is missing: run scripts/web-deps');
  mkdirSync(SHOTS, { recursive: true });
  const { chromium } = await import('playwright-core');
  const browser = await chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    timeout: slow(30000),
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  const context = await browser.newContext({ acceptDownloads: true });
  const errors = [];
  const newPage = async (viewport = { width: 1280, height: 800 }) => {
    const p = await context.newPage();
    await p.setViewportSize(viewport);
    p.setDefaultTimeout(slow(15000));
    p.on('console', (m) => {
      if (m.type() === 'error') errors.push(m.text());
    });
    p.on('pageerror', (e) => errors.push(`${e.message}\n${e.stack ?? ''}`));
    return p;
  };
  return { browser, context, newPage, errors };
}

/** Shows a view by its address and waits until it is the one shown. */
export async function goView(page, view) {
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

// Debian's Chromium driven by puppeteer-core (which downloads no browser),
// headless, with WebGL through SwiftShader, and a fresh profile per launch.
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import assert from 'node:assert/strict';
import puppeteer from 'puppeteer-core';

export const CHROMIUM = process.env.CHROMIUM ?? '/usr/bin/chromium';

export function chromiumAvailable() {
  return existsSync(CHROMIUM);
}

export async function launchBrowser() {
  const profile = mkdtempSync(join(tmpdir(), 'tessera-chromium-'));
  const browser = await puppeteer.launch({
    executablePath: CHROMIUM,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run',
      // Tabs behind the first still draw (the 20-tab benchmark; a hidden tab
      // gets no animation frames otherwise).
      '--disable-background-timer-throttling', '--disable-backgrounding-occluded-windows', '--disable-renderer-backgrounding',
      `--user-data-dir=${profile}`],
  });
  const close = browser.close.bind(browser);
  browser.close = async () => {
    await close();
    rmSync(profile, { recursive: true, force: true });
  };
  return browser;
}

// A page that records its errors: uncaught exceptions and console errors.
export async function openPage(browser, url, size = { width: 1000, height: 680 }) {
  const page = await browser.newPage();
  page.problems = [];
  page.on('pageerror', (e) => page.problems.push(`pageerror: ${e.message}`));
  page.on('console', (m) => { if (m.type() === 'error') page.problems.push(`console: ${m.text()}`); });
  await page.setViewport(size);
  await page.goto(url);
  return page;
}

export const state = (page) => page.evaluate(() => window.tesseraViewer.state());

// The page decoded every region it holds in its Web Worker, and its main
// thread neither created a Draco module nor fetched draco_decoder.wasm
// (docs/WEB_VIEWER.md "Decoding in a worker"). Returns the test hook's
// decoding facts.
export async function assertDecodedInWorker(page) {
  const s = await state(page);
  const d = s.decoding;
  assert.equal(d.workers, 1, JSON.stringify(d));
  assert.equal(d.workerDraco, true, `the worker has its Draco module: ${JSON.stringify(d)}`);
  assert.equal(d.mainThreadDraco, false, 'the main thread created a Draco module');
  assert.ok(d.decoded >= s.regions && d.decoded > 0, `every region held came from the worker: ${JSON.stringify(d)}, ${s.regions} regions`);
  assert.equal(d.failed, 0, JSON.stringify(d));
  const fetched = await page.evaluate(() => performance.getEntriesByType('resource').map((e) => new URL(e.name).pathname));
  assert.ok(fetched.includes('/decode_worker.js'), `the page started its worker: ${fetched.join(' ')}`);
  assert.ok(!fetched.includes('/draco_decoder.wasm'), 'the main thread fetched draco_decoder.wasm');
  return d;
}

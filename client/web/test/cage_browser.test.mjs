// The control cage in the page (docs/WEB_VIEWER.md "The control cage"), in
// headless Chromium against a real tessera-server, as browser.test.mjs
// runs it: the page built fresh with its test hook, served by the server's
// own --ws-port. A Catmull-Clark cube of six quads (max level 2): at
// control level 0 its cage is the 6 quads with 12 edges, at level 1 the 24
// quads of one split with 48, each level asked for once; the lines show in
// the cage's colour and go with the toggle; a level above the document's
// max shows the server's refusal and the page goes on. A Loop cube's cage is
// its 12 triangles. Skipped without a server build that has --ws-port, or
// without /usr/bin/chromium.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { copyFileSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { serverHasWebSocket } from './support/server.mjs';
import { createCube, grant } from './support/client.mjs';
import { toBig } from '../src/codec/uint64.js';
import { CAGE_COLOUR } from '../src/scene/cage_layer.js';
import { assertDecodedInWorker, chromiumAvailable, launchBrowser, openPage, state } from './support/browser.mjs';
import { decodePng } from './support/png.mjs';
import { startPageServer } from './support/page_server.mjs';

const skip = !serverHasWebSocket() ? 'no build/release/server/tessera-server with --ws-port'
  : !chromiumAvailable() ? 'no Chromium' : false;
const VIEWER = 'cage-test-viewer-token';
// The unit cube as six quads (deploy/samples/quad_cube.obj's faces, 0-based):
// a mesh that is not all triangles is a Catmull-Clark document.
const QUAD_CUBE_OFF = `OFF
8 6 0
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
4 0 3 2 1
4 4 5 6 7
4 0 1 5 4
4 1 2 6 5
4 2 3 7 6
4 3 0 4 7
`;
let served, admin, browser, quads, triangles, base;

before(async () => {
  if (skip) return;
  served = await startPageServer();
  ({ admin, base } = served);
  const created = await admin.call({
    create_document: { name: 'quad cube', mesh: Buffer.from(QUAD_CUBE_OFF), mesh_format: 2, max_level: 2, file_name: 'quad_cube.off' },
  });
  quads = toBig(created.message.ack.document_id);
  triangles = await createCube(admin, 2);
  await grant(admin, VIEWER, 1);
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  await served?.stop();
});

const ready = (page) => page.waitForSelector('body[data-state=ready]', { timeout: 30000 });
const cageOf = async (page) => (await state(page)).cage;
// The cage of `level` drawn, or given up on; then its facts.
async function cageAt(page, level) {
  await page.waitForFunction((l) => {
    const c = window.tesseraViewer.state().cage;
    return c.level === l && c.status !== 'asking' && c.status !== 'waiting' && (c.status !== 'shown' || c.segments > 0);
  }, { timeout: 20000 }, level).catch(async (e) => { throw new Error(`${e.message}: ${JSON.stringify(await state(page))}`); });
  return cageOf(page);
}
// The panel's cage row once it names `level` with its answer (the panel is
// refreshed four times a second, so it may still say it is asking).
async function cageRow(page, level) {
  await page.waitForFunction((l) => {
    const row = document.querySelector('[data-f="cage"]').textContent;
    return row.startsWith(`cage of level ${l}:`) && !row.includes('asking');
  }, { timeout: 5000 }, level);
  return page.$eval('[data-f="cage"]', (e) => e.textContent);
}

// Pixels within a small distance of the cage's colour (the lines are one
// pixel wide and anti-aliased: the middle of a line keeps most of it).
const CAGE_RGB = [(CAGE_COLOUR >> 16) & 255, (CAGE_COLOUR >> 8) & 255, CAGE_COLOUR & 255];
function cagePixels(png) {
  let n = 0;
  for (let y = 0; y < png.height; ++y) {
    for (let x = 0; x < png.width; ++x) {
      const p = png.pixel(x, y);
      if (Math.abs(p[0] - CAGE_RGB[0]) + Math.abs(p[1] - CAGE_RGB[1]) + Math.abs(p[2] - CAGE_RGB[2]) < 60) ++n;
    }
  }
  return n;
}

// A screenshot through a temporary file, removed once read;
// TESSERA_KEEP_SCREENSHOTS=DIR keeps a copy there as NAME.png.
async function screenshot(page, name) {
  const dir = mkdtempSync(join(tmpdir(), 'tessera-cage-shot-'));
  try {
    const path = join(dir, `${name}.png`);
    await page.screenshot({ type: 'png', path });
    if (process.env.TESSERA_KEEP_SCREENSHOTS) copyFileSync(path, join(process.env.TESSERA_KEEP_SCREENSHOTS, `${name}.png`));
    return decodePng(readFileSync(path));
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

test('a catmull-clark cube\'s cage: 6 quads and 12 edges at level 0, 24 and 48 at level 1, drawn in its colour, each level asked once', { skip }, async () => {
  const page = await openPage(browser, `${base}/?doc=${quads}&cage=1&level=0#token=${VIEWER}`);
  await ready(page);
  const level0 = await cageAt(page, 0);
  console.log(`cage level 0: ${JSON.stringify(level0)}`);
  assert.equal(level0.status, 'shown');
  assert.equal(level0.faces, 6);
  assert.equal(level0.edges, 12);
  assert.deepEqual(level0.faceSizes, { 4: 6 }, 'every face has 4 corners');
  // The page's first camera looks at the corner (1, 1, 1): the three quads
  // around it face it (flat, since their corners are limit points of a
  // cube's corners), and their 9 edges are drawn; the far corner's 3 are not.
  assert.equal(level0.segments, 9);
  assert.equal(level0.requests, 1);
  assert.equal(await cageRow(page, 0), 'cage of level 0: 6 faces · 12 edges · 9 drawn');
  const level0Pixels = cagePixels(await screenshot(page, 'cage-level-0'));

  await page.keyboard.press(']');
  const level1 = await cageAt(page, 1);
  console.log(`cage level 1: ${JSON.stringify(level1)}`);
  assert.equal(level1.status, 'shown');
  assert.equal(level1.faces, 24);
  assert.equal(level1.edges, 48);
  assert.deepEqual(level1.faceSizes, { 4: 24 });
  // More of them face the camera than at level 0, not the far side's.
  assert.ok(level1.segments > level0.segments && level1.segments < 48, `segments drawn: ${level1.segments}`);
  assert.equal(level1.requests, 2);
  assert.match(await cageRow(page, 1), /^cage of level 1: 24 faces · 48 edges · \d+ drawn$/);

  const withCage = await screenshot(page, 'cage-level-1');
  const shown = cagePixels(withCage);
  // O turns it off: the lines go, and with them the colour.
  await page.keyboard.press('o');
  await page.waitForFunction(() => window.tesseraViewer.state().cage.status === 'off', { timeout: 5000 });
  await new Promise((r) => setTimeout(r, 300));
  const withoutCage = await screenshot(page, 'no-cage');
  const hidden = cagePixels(withoutCage);
  console.log(`pixels of the cage's colour: ${level0Pixels} at level 0, ${shown} at level 1, ${hidden} without the cage`);
  assert.ok(level0Pixels > 200, `the cage's lines show at level 0: ${level0Pixels} pixels`);
  assert.ok(shown > level0Pixels, `and more of them at level 1: ${shown} pixels`);
  assert.equal(hidden, 0, 'nothing else has the cage\'s colour');
  // The panel's toggle follows the key, and its cage row goes.
  await page.waitForFunction(() => !document.querySelector('[data-f="cageOn"]').checked &&
    document.querySelector('[data-f="cage"]').hidden, { timeout: 5000 });

  // Back on with the panel's toggle, and back to level 0: the answers
  // kept, nothing asked again.
  await page.click('[data-f="cageOn"]');
  await page.waitForFunction(() => window.tesseraViewer.state().cage.on, { timeout: 5000 });
  // (Keys go to the focused checkbox now: the panel's − button.)
  await page.click('[data-f="down"]');
  const again = await cageAt(page, 0);
  assert.equal(again.status, 'shown');
  assert.equal(again.edges, 12);
  assert.equal(again.requests, 2, 'each level asked for once');
  assert.equal((await state(page)).error, '');
  await assertDecodedInWorker(page); // the quads' lattice ids too
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('a level above the document\'s max level shows the server\'s refusal, and the page goes on', { skip }, async () => {
  // The page's profile allows level 3 (balanced); the document stops at 2.
  const page = await openPage(browser, `${base}/?doc=${quads}&cage=1&level=3#token=${VIEWER}`);
  await ready(page);
  const refused = await cageAt(page, 3);
  const s = await state(page);
  console.log(`level 3: ${JSON.stringify(refused)}; error "${s.error}"`);
  assert.equal(refused.status, 'refused');
  assert.equal(refused.faces, 0);
  assert.match(s.error, /^control cage of level 3: REJECT_REASON_INVALID_ARGUMENT: control cage of document \d+: level 3 is outside 0\.\.2$/);
  await page.waitForFunction((e) => document.querySelector('[data-f="error"]').textContent === e, { timeout: 5000 }, s.error);
  assert.equal(await cageRow(page, 3), 'cage of level 3: refused (below)');
  // Still connected and drawing: level 2's cage comes (96 quads, 192 edges).
  await page.keyboard.press('[');
  const level2 = await cageAt(page, 2);
  assert.equal(level2.status, 'shown');
  assert.deepEqual([level2.faces, level2.edges], [96, 192]);
  assert.deepEqual(level2.faceSizes, { 4: 96 });
  const after = await state(page);
  assert.equal(after.connected, true);
  assert.equal(after.ready, true);
  assert.equal(after.hashMatches, true);
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('a loop cube\'s cage is its 12 triangles with 18 edges', { skip }, async () => {
  const page = await openPage(browser, `${base}/?doc=${triangles}&cage=1&level=0#token=${VIEWER}`);
  await ready(page);
  const level0 = await cageAt(page, 0);
  console.log(`loop cube, cage level 0: ${JSON.stringify(level0)}`);
  assert.equal(level0.status, 'shown');
  assert.deepEqual([level0.faces, level0.edges], [12, 18]);
  assert.deepEqual(level0.faceSizes, { 3: 12 });
  // The three sides towards the camera, two triangles each: their 4 + 4 +
  // 4 outer edges less the 3 they share, and 3 diagonals.
  assert.equal(level0.segments, 12);
  assert.equal(await cageRow(page, 0), 'cage of level 0: 12 faces · 18 edges · 12 drawn');
  assert.ok(cagePixels(await screenshot(page, 'loop-cage-level-0')) > 200, 'the lines show');
  assert.deepEqual(page.problems, []);
  await page.close();
});

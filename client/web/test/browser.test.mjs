// The page itself in headless Chromium against a real tessera-server, served
// by the server's own --ws-port from a fresh build (with the test hook,
// build.mjs --test-hook). What a person would check:
// the cube shows, anti-aliased, with the HUD in its corner, through a view
// unless the address asks for a profile; the hash matches the server's; a
// drag edits and undo takes it back; collaborators' picks show both ways;
// the keys and the LOD selector work; the start panel asks for a token and
// lists documents; a large document shows its preview first, then its
// tiles; a morph document is shown with the profile. Every region is
// decoded in the page's Web Worker, never on its main thread. Skipped
// without a server build that has --ws-port, or without /usr/bin/chromium.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { serverHasWebSocket, testData } from './support/server.mjs';
import { createCube, createMesh, grant, openSession, until } from './support/client.mjs';
import { toLong } from '../src/codec/uint64.js';
import { PREVIEW_ID } from '../src/scene/tile_assembly.js';
import { assertDecodedInWorker, chromiumAvailable, launchBrowser, openPage, state } from './support/browser.mjs';
import { decodePng } from './support/png.mjs';
import { startPageServer } from './support/page_server.mjs';

const skip = !serverHasWebSocket() ? 'no build/release/server/tessera-server with --ws-port'
  : !chromiumAvailable() ? 'no Chromium' : false;
const EDITOR = 'browser-test-editor-token', VIEWER = 'browser-test-viewer-token';
let served, server, admin, browser, documentId, base;

before(async () => {
  if (skip) return;
  served = await startPageServer();
  ({ server, admin, base } = served);
  console.log(served.buildLog);
  documentId = await createCube(admin);
  await grant(admin, EDITOR, 2, documentId);
  await grant(admin, VIEWER, 1, documentId);
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  await served?.stop();
});

const docUrl = (token, extra = '') => `${base}/?doc=${documentId}${extra}#token=${token}`;
const ready = (page) => page.waitForSelector('body[data-state=ready]', { timeout: 30000 });
// Ready and knowing its role on the document: a token granted on one
// document learns it from its own Presence entry, which may come after the
// first picture (the HelloAck's role covers all documents only). Editing
// waits for it, so tests that edit do too.
async function readyWithRole(page) {
  await ready(page);
  await page.waitForFunction(() => window.tesseraViewer.state().role !== 'ROLE_UNSPECIFIED', { timeout: 10000 });
}

// With a view, the first picture (data-state=ready) is the coarsest tiles
// (docs/WEB_VIEWER.md "Views"): the cube's level-0 tile, which holds no
// vertex of level 1, so a pick of level 1 finds none until the camera's
// own tiles come. They came late enough for that after a level-2 edit and
// a phone-sized page on the same document; waiting for them is the test's
// part, not the page's.
async function cameraTilesHere(page) {
  await page.waitForFunction(() => { const s = window.tesseraViewer.state(); return !s.views || s.viewComplete; }, { timeout: 30000 });
}

async function screenshot(page) {
  return decodePng(await page.screenshot({ type: 'png' }));
}

// Pixels of a rectangle that differ from the background at the frame's
// corner by more than a few levels.
function differing(png, x0, y0, x1, y1, reference = png.pixel(png.width - 2, png.height - 2)) {
  let n = 0;
  for (let y = y0; y < y1; ++y) {
    for (let x = x0; x < x1; ++x) {
      const p = png.pixel(x, y);
      if (Math.abs(p[0] - reference[0]) + Math.abs(p[1] - reference[1]) + Math.abs(p[2] - reference[2]) > 24) ++n;
    }
  }
  return n / ((x1 - x0) * (y1 - y0));
}

test('the cube shows through a view by default, anti-aliased, hashed like the server, with the HUD in its corner', { skip }, async () => {
  // No ?views= and no ?lod=: a view-dependent subscription (docs/WEB_VIEWER.md
  // "Views"), which the server says is complete for the page's camera.
  const page = await openPage(browser, docUrl(VIEWER));
  await readyWithRole(page);
  await page.waitForFunction(() => window.tesseraViewer.state().viewComplete, { timeout: 30000 });
  const s = await state(page);
  assert.equal(s.views, true, 'a view by default');
  assert.ok(s.firstPicture.triangles < s.triangles, `the coarsest tiles first: ${JSON.stringify(s.firstPicture)}, then ${s.triangles}`);
  assert.equal(s.firstPicture.shown.includes(String(PREVIEW_ID)), false, 'a small document has no preview');
  // The panel (refreshed four times a second) has the tolerance, not the LOD preset.
  await page.waitForFunction(() => document.querySelector('select[data-f=preset]').disabled &&
    document.querySelector('select[data-f=codec]').disabled &&
    !document.querySelector('[data-f="toleranceRow"]').hidden, { timeout: 5000 });
  assert.equal(s.connected, true);
  assert.equal(s.ready, true);
  assert.equal(s.role, 'ROLE_VIEWER');
  assert.equal(s.documentId, String(documentId));
  assert.match(s.surfaceHash, /^0x[0-9a-f]{16}$/);
  assert.notEqual(s.serverSurfaceHash, '0x0000000000000000');
  assert.equal(s.surfaceHash, s.serverSurfaceHash);
  assert.equal(s.hashMatches, true);
  assert.ok(s.triangles > 100 && s.regions > 0 && s.bytesReceived > 1000 && s.frames > 2, JSON.stringify(s));
  assert.equal(s.error, '');
  const decoding = await assertDecodedInWorker(page);
  console.log(`decoded in the worker: ${decoding.decoded} regions, ${decoding.meanMs.toFixed(2)} ms mean, ${decoding.p99Ms.toFixed(2)} ms p99`);
  const antialias = await page.evaluate(() => document.querySelector('#stage canvas').getContext('webgl2').getContextAttributes().antialias);
  assert.equal(antialias, true);
  const frames = await page.evaluate(() => window.tesseraViewer.renderedFrames());
  assert.ok(frames >= 1);
  await page.keyboard.press('w');
  await page.waitForFunction((n) => window.tesseraViewer.renderedFrames() > n, { timeout: 5000 }, frames);
  await page.keyboard.press('w');

  const hud = await page.$eval('#hud', (e) => e.getBoundingClientRect().toJSON());
  assert.ok(hud.left < 40 && hud.top < 40 && hud.right < 1000 * 0.4 && hud.bottom < 680 * 0.5, JSON.stringify(hud));
  const png = await screenshot(page);
  const covered = differing(png, 450, 290, 550, 390);
  console.log(`centre covered by the surface: ${(100 * covered).toFixed(0)}%; HUD ${Math.round(hud.width)}x${Math.round(hud.height)} px`);
  assert.ok(covered > 0.95, 'the model fills the middle of the frame');
  assert.ok(differing(png, 900, 20, 990, 90, png.pixel(945, 55)) < 0.02, 'the top-right corner is background');
  assert.deepEqual(page.problems, []);
  await page.close();
});

// The box of the pixels the canvas draws (the surface and its markers),
// from a screenshot taken without the page's background: the canvas is
// transparent where nothing is drawn.
async function drawnBox(page, skip) {
  await page.evaluate(() => { document.body.style.background = 'none'; });
  const png = decodePng(await page.screenshot({ type: 'png', omitBackground: true }));
  await page.evaluate(() => { document.body.style.background = ''; });
  let x0 = png.width, y0 = png.height, x1 = -1, y1 = -1;
  for (let y = 0; y < png.height; ++y) {
    for (let x = 0; x < png.width; ++x) {
      if (skip(x, y) || png.alpha(x, y) < 128) continue;
      x0 = Math.min(x0, x), y0 = Math.min(y0, y), x1 = Math.max(x1, x), y1 = Math.max(y1, y);
    }
  }
  return { x0, y0, x1, y1 };
}

test('with ?codec=meshopt the page shows the cube from meshopt regions decoded in its worker, hashed like the server, through an edit', { skip }, async () => {
  const timings = {};
  // A cube of its own: its edits leave the document the other tests pick on
  // as they expect it.
  const cube = await createCube(admin);
  await grant(admin, EDITOR, 2, cube);
  for (const codec of ['draco', 'meshopt']) {
    const page = await openPage(browser, `${base}/?doc=${cube}&lod=balanced&codec=${codec}#token=${EDITOR}`);
    try {
      await readyWithRole(page);
      const s = await state(page);
      assert.equal(s.hashMatches, true);
      const d = await assertDecodedInWorker(page);
      assert.equal(d.decodedMeshopt, codec === 'meshopt' ? d.decoded : 0, JSON.stringify(d));
      // An edit: the delta comes in the same codec, and the hash still holds.
      const version = s.version;
      await admin.call({ open_document: { document_id: toLong(cube) } });
      const moved = await admin.call({ move_vertex: { document_id: toLong(cube), vertex_ids: [toLong(2n << 58n)],
        target: { x: 0.0004, y: -0.0003, z: 0.0005 }, mode: 2 } });
      assert.ok(moved.message?.ack, JSON.stringify(moved.message));
      await page.waitForFunction((v) => window.tesseraViewer.state().version > v && window.tesseraViewer.state().hashMatches,
        { timeout: 20000 }, version);
      const after = (await state(page)).decoding;
      assert.ok(after.decoded > d.decoded, JSON.stringify(after));
      assert.equal(after.decodedMeshopt, codec === 'meshopt' ? after.decoded : 0, JSON.stringify(after));
      timings[codec] = { regions: after.decoded, meanMs: after.meanMs, p99Ms: after.p99Ms };
    } finally {
      await page.close();
    }
  }
  console.log(`[ measured ] page decode per region, in its worker: ${JSON.stringify(timings)}`);
});

test('the panel\'s codec control resubscribes in the chosen codec: the page then holds and draws that codec\'s regions, same triangles and hash', { skip }, async () => {
  // A profile: the server serves meshopt regions to profiles only, and the
  // control is disabled with a view (docs/REGION_ENCODING.md "meshopt regions").
  const page = await openPage(browser, docUrl(VIEWER, '&lod=balanced'));
  try {
    await ready(page);
    // A profile without ?codec= starts in meshopt (docs/PERFORMANCE.md
    // "Region codecs: the page's default").
    const s0 = await state(page);
    assert.equal(s0.codec, 'meshopt');
    assert.deepEqual(s0.regionCodecs, { meshopt: s0.regions });
    await page.waitForFunction(() => !document.querySelector('select[data-f=codec]').disabled &&
      document.querySelector('select[data-f=codec]').value === 'meshopt', { timeout: 5000 });
    let previous = s0;
    for (const codec of ['draco', 'meshopt']) {
      const frames = await page.evaluate(() => window.tesseraViewer.renderedFrames());
      await page.select('select[data-f=codec]', codec);
      await page.waitForFunction((c, n) => {
        const s = window.tesseraViewer.state();
        return s.codec === c && s.regions > 0 && s.regionCodecs[c] === s.regions && s.hashMatches &&
          window.tesseraViewer.renderedFrames() > n;
      }, { timeout: 30000 }, codec, frames);
      const s = await state(page);
      console.log(`codec ${previous.codec} -> ${codec}: ${s.regions} regions, ${s.triangles} triangles, ` +
        `${s.decoding.decodedMeshopt} of ${s.decoding.decoded} decoded as meshopt`);
      assert.equal(s.triangles, s0.triangles, 'the same surface in either codec');
      assert.equal(s.surfaceHash, s0.surfaceHash);
      assert.equal(s.shown, s.tiles, 'every region held is drawn');
      assert.equal(s.error, '');
      previous = s;
    }
    const d = await assertDecodedInWorker(page);
    assert.ok(d.decodedMeshopt >= s0.regions && d.decoded >= 3 * s0.regions, JSON.stringify(d));
    assert.deepEqual(page.problems, []);
  } finally {
    await page.close();
  }
  // ?codec= is the control's first value.
  const draco = await openPage(browser, docUrl(VIEWER, '&lod=balanced&codec=draco'));
  try {
    await ready(draco);
    await draco.waitForFunction(() => document.querySelector('select[data-f=codec]').value === 'draco', { timeout: 5000 });
    const s = await state(draco);
    assert.deepEqual(s.regionCodecs, { draco: s.regions });
  } finally {
    await draco.close();
  }
});

test('on a phone-sized page the panel starts folded, never covers the model, and the fit centres it below the panel', { skip }, async () => {
  const size = { width: 390, height: 844 };
  const page = await openPage(browser, docUrl(VIEWER), size);
  await ready(page);
  if (process.env.TESSERA_KEEP_SCREENSHOTS) (await import('node:fs')).writeFileSync(`${process.env.TESSERA_KEEP_SCREENSHOTS}/phone.png`, await page.screenshot({ type: 'png' }));
  const hud = await page.$eval('#hud', (e) => ({ folded: e.classList.contains('folded'), ...e.getBoundingClientRect().toJSON() }));
  assert.equal(hud.folded, true, 'folded at first');
  assert.ok(hud.bottom < 60, `the folded panel is one row: ${JSON.stringify(hud)}`);
  const inHud = (x, y) => x <= hud.right + 1 && y <= hud.bottom + 1;
  const box = await drawnBox(page, inHud);
  console.log(`phone: HUD ${Math.round(hud.width)}x${Math.round(hud.height)} px, surface rows ${box.y0}..${box.y1}, columns ${box.x0}..${box.x1}`);
  assert.ok(box.y0 > hud.bottom, `the surface starts below the panel: ${JSON.stringify(box)}`);
  const above = box.y0 - hud.bottom, below = size.height - 1 - box.y1;
  assert.ok(Math.abs(above - below) < 0.1 * size.height, `centred in the free area: ${above} px above, ${below} below`);
  assert.ok(box.x1 - box.x0 > 0.6 * size.width, `and fills its width: ${JSON.stringify(box)}`);
  // H unfolds it, and it stays within the top half.
  await page.keyboard.press('h');
  const open = await page.$eval('#hud', (e) => e.getBoundingClientRect().toJSON());
  assert.ok(open.bottom < size.height / 2 && open.right <= size.width, JSON.stringify(open));
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('a drag edits the document as one undo step; undo and redo come back to the hashes', { skip }, async () => {
  const page = await openPage(browser, docUrl(EDITOR, '&name=dragger'));
  await readyWithRole(page);
  await cameraTilesHere(page);
  const s0 = await state(page);
  assert.equal(s0.role, 'ROLE_EDITOR');
  const v = await page.evaluate(() => window.tesseraViewer.someVertexNearCentre());
  assert.match(v.id, /^v\d+:\d+$/);
  assert.equal(BigInt(v.packed) >> 58n, BigInt(v.id.slice(1).split(':')[0]));
  await page.mouse.move(v.x, v.y);
  await page.mouse.down();
  for (let i = 1; i <= 8; ++i) {
    await page.mouse.move(v.x + 3 * i, v.y - 6 * i);
    await new Promise((r) => setTimeout(r, 45));
  }
  await page.mouse.up();
  await page.waitForFunction((n) => {
    const s = window.tesseraViewer.state();
    return s.editsSent > 1 && s.lastEditToDeltaMs !== null && s.version >= n + s.editsSent && s.awaitingAnswers === 0 && s.hashMatches;
  }, { timeout: 20000 }, s0.version);
  const s1 = await state(page);
  console.log(`drag: ${s1.editsSent} edits, ${s1.editsRejected} rejected, edit-to-delta ${s1.lastEditToDeltaMs.toFixed(1)} ms, v${s0.version} -> v${s1.version}`);
  assert.equal(s1.editsRejected, 0);
  assert.deepEqual(s1.picked, [v.id]);
  assert.notEqual(s1.surfaceHash, s0.surfaceHash);
  const moved = await page.evaluate((id) => window.tesseraViewer.screenPointOfVertex(id), v.id);
  assert.ok(Math.hypot(moved.x - (v.x + 24), moved.y - (v.y - 48)) < 3, `the vertex followed the pointer: ${JSON.stringify(moved)}`);

  await page.keyboard.down('Control');
  await page.keyboard.press('z');
  await page.keyboard.up('Control');
  await page.waitForFunction((h) => window.tesseraViewer.state().surfaceHash === h, { timeout: 20000 }, s0.surfaceHash);
  await page.keyboard.down('Control');
  await page.keyboard.press('y');
  await page.keyboard.up('Control');
  await page.waitForFunction((h) => window.tesseraViewer.state().surfaceHash === h, { timeout: 20000 }, s1.surfaceHash);
  const s2 = await state(page);
  assert.equal(s2.hashMatches, true);
  assert.equal(s2.version, s1.version + 2 * s1.editsSent, 'one Undo and one Redo per edit of the step');
  const decoding = await assertDecodedInWorker(page);
  assert.ok(decoding.decoded > s1.decoding.decoded, 'the deltas of undo and redo were decoded in the worker');
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('after a level-2 edit and a phone-sized page, a new page picks near the centre once its camera\'s tiles are here', { skip }, async () => {
  // The order that once left the drag test's pick empty: the pick came
  // before the camera's tiles (cameraTilesHere above), not after a
  // hierarchy it could not pick in.
  const cube = await createCube(admin);
  await grant(admin, EDITOR, 2, cube);
  await grant(admin, VIEWER, 1, cube);
  await admin.call({ open_document: { document_id: toLong(cube) } });
  const moved = await admin.call({ move_vertex: { document_id: toLong(cube), vertex_ids: [toLong(2n << 58n)],
    target: { x: 0.0004, y: -0.0003, z: 0.0005 }, mode: 2 } });
  assert.ok(moved.message?.ack, JSON.stringify(moved.message));
  const phone = await openPage(browser, `${base}/?doc=${cube}#token=${VIEWER}`, { width: 390, height: 844 });
  await ready(phone);
  await phone.close();
  const page = await openPage(browser, `${base}/?doc=${cube}#token=${EDITOR}`);
  try {
    await readyWithRole(page);
    await cameraTilesHere(page);
    const v = await page.evaluate(() => window.tesseraViewer.someVertexNearCentre());
    assert.ok(v, JSON.stringify((await state(page)).tileLevels));
    assert.match(v.id, /^v1:\d+$/);
    assert.equal((await state(page)).hashMatches, true);
    assert.deepEqual(page.problems, []);
  } finally {
    await page.close();
  }
});

test('picks travel both ways through presence', { skip }, async () => {
  const page = await openPage(browser, docUrl(VIEWER, '&name=watcher'));
  await ready(page);
  const bob = await openSession(server.port, EDITOR, documentId, { baseLevel: 1, maxLevel: 3, angle: 15 }, 'bob');
  bob.session.select([(1n << 58n) | 3n]);
  await page.waitForFunction(() => window.tesseraViewer.state().collaborators.some((c) => c.name === 'bob' && c.selection[0] === 'v1:3'),
    { timeout: 10000 });
  const people = (await state(page)).collaborators.map((c) => `${c.name}${c.self ? '*' : ''}:${c.role}`);
  assert.ok(people.includes('bob:ROLE_EDITOR') && people.includes('watcher*:ROLE_VIEWER'), people.join());
  await cameraTilesHere(page);
  const v = await page.evaluate(() => window.tesseraViewer.someVertexNearCentre());
  await page.mouse.click(v.x, v.y);
  await until(() => bob.session.collaborators.list().some((c) => c.name === 'watcher' && c.selection.length === 1 &&
    `v${c.selection[0] >> 58n}:${c.selection[0] & ((1n << 58n) - 1n)}` === v.id), 'the watcher\'s pick at bob');
  assert.equal((await state(page)).editsSent, 0, 'a viewer picks but does not edit');
  bob.connection.stop();
  assert.deepEqual(page.problems, []);
  await page.close();
});

// Picks vertices a and b by clicking where the page draws them, C creases
// the edge they name (one new version, no error), then V makes the last
// pick a corner (another version).
async function creaseThenCorner(page, a, b) {
  const s0 = await state(page);
  for (const id of [a, b]) {
    const p = await page.evaluate((i) => window.tesseraViewer.screenPointOfVertex(i), id);
    await page.mouse.click(p.x, p.y);
  }
  await page.waitForFunction(() => window.tesseraViewer.state().picked.length === 2);
  assert.deepEqual((await state(page)).picked, [a, b]);
  await page.keyboard.press('c');
  await page.waitForFunction((n) => { const s = window.tesseraViewer.state(); return s.version > n || s.error !== ''; }, { timeout: 15000 }, s0.version);
  const afterC = await state(page);
  assert.equal(afterC.error, '');
  assert.equal(afterC.version, s0.version + 1);
  await page.keyboard.press('v');
  await page.waitForFunction((n) => window.tesseraViewer.state().version > n, { timeout: 15000 }, afterC.version);
}

test('C creases the edge of the last two picks, V makes a corner, W and R redraw, the LOD selector resubscribes', { skip }, async () => {
  // A profile: the LOD selector is disabled with a view.
  const page = await openPage(browser, docUrl(EDITOR, '&name=keys&lod=balanced'));
  await readyWithRole(page);
  // Base edge (5, 6) of the cube (the top rim's edge from (1, 0, 1) to
  // (1, 1, 1)) is e6 in the scan of 3.2 (triangles (0 2 1), (0 3 2),
  // (4 5 6): e0..e6), so its midpoint is v1:(8 + 6) and its half at vertex 6
  // joins v1:6 and v1:14 at level 1.
  await creaseThenCorner(page, 'v1:6', 'v1:14');
  assert.equal((await state(page)).hashMatches, true);

  const plain = await screenshot(page);
  await page.keyboard.press('w');
  await new Promise((r) => setTimeout(r, 400));
  const wired = await screenshot(page);
  let changed = 0;
  for (let y = 250; y < 430; y += 2) for (let x = 400; x < 600; x += 2) if (plain.pixel(x, y).join() !== wired.pixel(x, y).join()) ++changed;
  assert.ok(changed > 200, `the wireframe shows (${changed} pixels changed)`);
  await page.keyboard.press('w');
  await page.keyboard.press('r');

  const before = await state(page);
  await page.select('select[data-f=preset]', 'fine');
  await page.waitForFunction((t) => { const s = window.tesseraViewer.state(); return s.triangles !== t && s.hashMatches; }, { timeout: 30000 }, before.triangles);
  const fine = await state(page);
  console.log(`LOD balanced -> fine: ${before.triangles} -> ${fine.triangles} triangles`);
  assert.ok(fine.triangles > before.triangles);
  assert.equal(fine.surfaceHash, fine.serverSurfaceHash);
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('without a token the page asks for one; a refused one is shown and not retried; without ?doc it lists', { skip }, async () => {
  const page = await openPage(browser, `${base}/`);
  await page.waitForSelector('body[data-state=token] input[name=token]', { timeout: 15000 });
  await page.type('input[name=token]', 'a-token-nobody-granted-here');
  await page.keyboard.press('Enter');
  await page.waitForSelector('body[data-state=error]', { timeout: 20000 });
  assert.match(await page.$eval('.start-problem', (e) => e.textContent), /ERROR_CODE_AUTH_FAILED/);
  assert.match((await state(page)).error, /AUTH_FAILED/);
  assert.ok(!page.url().includes('?token'), 'the token never goes into the query');
  await page.close();

  const list = await openPage(browser, `${base}/#token=${VIEWER}`);
  await list.waitForSelector('.start-documents button', { timeout: 15000 });
  await list.click('.start-documents button');
  await ready(list);
  assert.equal(new URL(list.url()).searchParams.get('doc'), String(documentId));
  assert.equal(new URL(list.url()).hash, `#token=${VIEWER}`);
  assert.equal((await state(list)).hashMatches, true);
  await list.close();
});

// The page connects while its worker loads the decoders (docs/WEB_VIEWER.md
// "Decoding in a worker", Start): with the worker's script held back, the
// HelloAck comes before the decoder is ready, and the payloads that came
// meanwhile are decoded once it is. A worker that cannot load is a clear
// error, and the page stops its connection.
//
// The worker's script alone is paused (the DevTools protocol's Fetch domain
// with that one pattern): puppeteer's request interception pauses every
// request, the worker's own fetch of draco_decoder.wasm too, which it then
// does not always hand on.
async function pageWithWorker(url, answer) {
  const page = await browser.newPage();
  page.problems = [];
  page.on('pageerror', (e) => page.problems.push(`pageerror: ${e.message}`));
  const devtools = await page.createCDPSession();
  devtools.on('Fetch.requestPaused', (e) => answer(devtools, e.requestId));
  await devtools.send('Fetch.enable', { patterns: [{ urlPattern: '*/decode_worker.js', requestStage: 'Request' }] });
  await page.setViewport({ width: 1000, height: 680 });
  await page.goto(url);
  return page;
}

test('the page connects while its decoder loads, and shows the cube once it has; a decoder that cannot load is a clear error', { skip }, async () => {
  const HELD_MS = 1500;
  let held = 0;
  const slow = await pageWithWorker(docUrl(VIEWER), (devtools, requestId) => {
    ++held;
    setTimeout(() => devtools.send('Fetch.continueRequest', { requestId }).catch(() => {}), HELD_MS);
  });
  await ready(slow);
  const s = await state(slow);
  assert.equal(held, 1, 'the worker\'s script was asked for once, and held back');
  assert.ok(s.milestones.decoderReady >= HELD_MS && s.milestones.helloAck < s.milestones.decoderReady,
    `connected before the decoder was ready: ${JSON.stringify(s.milestones)}`);
  assert.equal(s.hashMatches, true);
  assert.ok(s.triangles > 0, JSON.stringify(s));
  await assertDecodedInWorker(slow);
  assert.deepEqual(slow.problems, []);
  await slow.close();

  const missing = await pageWithWorker(docUrl(VIEWER), (devtools, requestId) => devtools.send('Fetch.fulfillRequest', {
    requestId, responseCode: 404, responseHeaders: [{ name: 'Content-Type', value: 'text/plain' }], body: Buffer.from('not here').toString('base64'),
  }).catch(() => {}));
  await missing.waitForSelector('body[data-state=error]', { timeout: 20000 });
  assert.match(await missing.$eval('#start', (e) => e.textContent), /region decoder did not load: the decode worker stopped/);
  const after = await state(missing);
  assert.match(after.error, /the decode worker stopped/);
  assert.equal(after.ready, false);
  assert.equal(after.connected, false, 'the connection was stopped');
  assert.equal(after.triangles, 0);
  await missing.close();
});

// A view-dependent subscription (the default, asked for here with
// ?views=1, which still works; docs/WEB_VIEWER.md "Views"): the
// first picture is the coarsest tiles, refined once the page has framed
// them and sent its camera; turning the camera changes which tiles are
// held, turning it back restores them, and every picture's hash is the
// server's.
test('with ?views=1 the page loads coarse first, then the tiles its camera needs; orbiting changes them and back', { skip }, async () => {
  // Six levels: close up the view needs the sixth where it looks, and the
  // fifth elsewhere.
  const deep = await createCube(admin, 6);
  await grant(admin, VIEWER, 1, deep);
  const page = await openPage(browser, `${base}/?doc=${deep}&views=1#token=${VIEWER}`, { width: 390, height: 844 });
  await ready(page);
  const complete = (p) => p.waitForFunction(() => {
    const s = window.tesseraViewer.state();
    return s.viewComplete && s.hashMatches;
  }, { timeout: 60000 });
  await complete(page);
  const whole = await state(page);
  console.log(`views: first picture ${whole.firstPicture.triangles} triangles at ${whole.firstPicture.ms} ms; ` +
    `whole ${whole.triangles} triangles, tiles by level ${JSON.stringify(whole.tileLevels)}`);
  assert.ok(whole.firstPicture.triangles < whole.triangles, 'the first picture is coarser than the last');
  assert.equal(whole.surfaceHash, whole.serverSurfaceHash);
  // A quarter turn brings other faces near: other tiles at the sixth level.
  await page.evaluate(() => window.tesseraViewer.orbitBy(Math.PI / 2));
  await page.waitForFunction((t) => window.tesseraViewer.state().tiles !== t, { timeout: 30000 }, whole.tiles);
  await complete(page);
  const turned = await state(page);
  console.log(`views: turned ${turned.triangles} triangles ${JSON.stringify(turned.tileLevels)}`);
  assert.equal(turned.surfaceHash, turned.serverSurfaceHash);
  // And back: the tiles it started with.
  await page.evaluate(() => window.tesseraViewer.orbitBy(-Math.PI / 2));
  await page.waitForFunction((t) => window.tesseraViewer.state().tiles === t, { timeout: 30000 }, whole.tiles);
  await complete(page);
  assert.equal((await state(page)).surfaceHash, whole.surfaceHash);
  // The panel's tolerance: from 1 to 8 pixels (the slider's log2 is 3),
  // fewer triangles, and the server's hash again; back to 1, the first set.
  const setTolerance = (log2) => page.evaluate((v) => {
    const slider = document.querySelector('[data-f="tolerance"]');
    slider.value = String(v);
    slider.dispatchEvent(new Event('input'));
  }, log2);
  assert.equal(await page.$eval('[data-f="toleranceRow"]', (e) => e.hidden), false, 'the panel has the tolerance');
  await setTolerance(3);
  await page.waitForFunction((t) => window.tesseraViewer.state().tiles !== t, { timeout: 30000 }, whole.tiles);
  await complete(page);
  const coarser = await state(page);
  console.log(`views: at 8 px ${coarser.triangles} triangles ${JSON.stringify(coarser.tileLevels)}`);
  assert.ok(coarser.triangles < whole.triangles, 'a larger tolerance shows fewer triangles');
  // The panel refreshes four times a second.
  await page.waitForFunction(() => document.querySelector('[data-f="toleranceValue"]').textContent === '8 px',
    { timeout: 5000 });
  await setTolerance(0);
  await page.waitForFunction((t) => window.tesseraViewer.state().tiles === t, { timeout: 30000 }, whole.tiles);
  await complete(page);
  assert.equal((await state(page)).surfaceHash, whole.surfaceHash);
  await assertDecodedInWorker(page);
  assert.deepEqual(page.problems, []);
  await page.close();
});

// A document whose level-0 surface has more than 8,192 triangles (CGAL's
// fandisk: 12,946) starts with the surface's preview, simplified to at most
// 2,048 (docs/VIEWS.md "The first picture"). The page draws it alone while it is
// held, whatever tiles arrive meanwhile, and the tiles once the server has
// removed it (docs/WEB_VIEWER.md "Views"). On loopback the delta that
// removes it may arrive before the page's first frame, so what the server
// sent first is checked as it came, and the first frame only for never
// drawing the preview with tiles.
test('a large document\'s first picture is its preview, alone and a few kilobytes; the whole view is tiles without it', { skip }, async () => {
  const fandisk = await createMesh(admin, testData('cgal/fandisk.off'), 3);
  await grant(admin, VIEWER, 1, fandisk);
  const page = await openPage(browser, `${base}/?doc=${fandisk}#token=${VIEWER}`);
  await ready(page);
  const { firstSnapshot: sent, firstPicture: first } = await state(page);
  assert.deepEqual(sent.ids, [String(PREVIEW_ID)], `the preview alone: ${JSON.stringify(sent)}`);
  assert.ok(sent.triangles > 0 && sent.triangles <= 2048 && sent.bytes > 0 && sent.bytes < 16384, JSON.stringify(sent));
  if (first.shown.includes(String(PREVIEW_ID))) {
    assert.deepEqual(first.shown, [String(PREVIEW_ID)], `the preview drawn alone: ${JSON.stringify(first)}`);
  }
  await page.waitForFunction(() => {
    const s = window.tesseraViewer.state();
    return s.viewComplete && s.hashMatches;
  }, { timeout: 60000 });
  const whole = await state(page);
  console.log(`preview: first snapshot ${sent.triangles} triangles, ${sent.bytes} bytes; first frame at ${first.ms} ms ` +
    `(${first.shown.length} region(s)); ` +
    `whole ${whole.triangles} triangles, tiles by level ${JSON.stringify(whole.tileLevels)}`);
  assert.equal(whole.tileLevels.preview, undefined, 'the server removed the preview');
  assert.ok(Object.keys(whole.tileLevels).length >= 2, `tiles of several levels: ${JSON.stringify(whole.tileLevels)}`);
  assert.equal(whole.shown, whole.tiles, 'every tile held is drawn');
  assert.ok(whole.triangles > 12946);
  assert.equal(whole.surfaceHash, whole.serverSurfaceHash);
  await assertDecodedInWorker(page);
  assert.deepEqual(page.problems, []);
  await page.close();
});

// A morph document (PROTOCOL.md section 14) is shown with the profile even
// by default: its time, morph_t, is a profile field. The page finds it out
// before it subscribes (docs/WEB_VIEWER.md "Views").
test('a catmull-clark document is shown with quad lattice ids, hashed like the server; C, V and a drag edit it', { skip }, async () => {
  // The cube as six quads at "fine" (max level 4): one region per base quad,
  // each carrying quad lattice ids (docs/PROTOCOL.md 6.2), which the
  // surface hash covers.
  const quads = await createMesh(admin, new URL('../../../deploy/samples/quad_cube.obj', import.meta.url).pathname, 4);
  await grant(admin, EDITOR, 2, quads);
  const page = await openPage(browser, `${base}/?doc=${quads}&name=quads&lod=fine#token=${EDITOR}`);
  await readyWithRole(page);
  const s0 = await state(page);
  assert.equal(s0.views, false);
  assert.equal(s0.hashMatches, true);
  assert.ok(s0.triangles > 100 && s0.regions === 6, JSON.stringify(s0));
  // Faces (0 3 2 1) then (4 5 6 7) number the base edges (0,3), (3,2),
  // (2,1), (1,0), (4,5), (5,6): e5 joins the top corners 5 and 6, its
  // vertex is v1:(V + F + 5) = v1:19, and its half at vertex 6 joins v1:6
  // and v1:19 (docs/ARCHITECTURE.md "The quad split").
  await creaseThenCorner(page, 'v1:6', 'v1:19');
  await page.waitForFunction(() => window.tesseraViewer.state().hashMatches, { timeout: 15000 });
  const afterV = await state(page);
  assert.notEqual(afterV.surfaceHash, s0.surfaceHash);

  const v = await page.evaluate(() => window.tesseraViewer.someVertexNearCentre());
  await page.mouse.move(v.x, v.y);
  await page.mouse.down();
  for (let i = 1; i <= 6; ++i) {
    await page.mouse.move(v.x + 3 * i, v.y - 5 * i);
    await new Promise((r) => setTimeout(r, 45));
  }
  await page.mouse.up();
  await page.waitForFunction((n) => {
    const s = window.tesseraViewer.state();
    return s.editsSent > 2 && s.version > n && s.awaitingAnswers === 0 && s.hashMatches;
  }, { timeout: 20000 }, afterV.version);
  const dragged = await state(page);
  console.log(`catmull-clark quad cube: ${s0.triangles} triangles, ${s0.regions} regions; ${dragged.editsSent} edits, v${s0.version} -> v${dragged.version}`);
  assert.equal(dragged.editsRejected, 0);
  assert.notEqual(dragged.surfaceHash, afterV.surfaceHash);
  assert.equal(dragged.surfaceHash, dragged.serverSurfaceHash);
  await assertDecodedInWorker(page);
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('a catmull-clark document shows through a view by default, hashed like the server', { skip }, async () => {
  // No ?views= and no ?lod=: the view-dependent subscription every document
  // gets by default, tiles of the quad split (docs/VIEWS.md "Catmull-Clark
  // documents").
  const quads = await createMesh(admin, new URL('../../../deploy/samples/quad_cube.obj', import.meta.url).pathname, 4);
  await grant(admin, VIEWER, 1, quads);
  const page = await openPage(browser, `${base}/?doc=${quads}&name=quads#token=${VIEWER}`);
  await readyWithRole(page);
  await page.waitForFunction(() => window.tesseraViewer.state().viewComplete, { timeout: 30000 });
  const s = await state(page);
  console.log(`catmull-clark quad cube by view: ${s.triangles} triangles, ${s.regions} tiles`);
  assert.equal(s.views, true, 'a view by default');
  assert.ok(s.triangles > 0);
  assert.equal(s.surfaceHash, s.serverSurfaceHash);
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('a morph document opened without ?views= or ?lod= is shown with the profile', { skip }, async () => {
  const morph = await createCube(admin, 4);
  // Key 1: the cube with its corner (1, 1, 1) pulled in.
  const cube = readFileSync(new URL('../../../deploy/samples/cube.obj', import.meta.url), 'utf8');
  const key1 = cube.replace(/^v 1 1 1$/m, 'v 0.8 0.8 0.8');
  assert.notEqual(key1, cube);
  await admin.call({ open_document: { document_id: toLong(morph) } });
  await admin.call({ add_morph_key: { document_id: toLong(morph), mesh: Buffer.from(key1), mesh_format: 1, file_name: 'key1.obj' } });
  await grant(admin, VIEWER, 1, morph);
  const page = await openPage(browser, `${base}/?doc=${morph}#token=${VIEWER}`);
  await ready(page);
  const s = await state(page);
  assert.equal(s.views, false, 'a morph document is not shown with a view');
  assert.equal(s.hashMatches, true);
  // The surface of the page's default profile ("balanced"), as a session
  // subscribed with it assembles it.
  const other = await openSession(server.port, VIEWER, morph, { baseLevel: 1, maxLevel: 3, angle: 15 }, 'balanced');
  assert.equal(BigInt(s.surfaceHash), other.session.lastHash.ours);
  other.connection.stop();
  // The panel offers the LOD preset, not the tolerance.
  await page.waitForFunction(() => document.querySelector('[data-f="toleranceRow"]').hidden &&
    !document.querySelector('select[data-f=preset]').disabled, { timeout: 5000 });
  assert.deepEqual(page.problems, []);
  await page.close();
});

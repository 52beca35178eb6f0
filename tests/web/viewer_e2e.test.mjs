// The browser viewer end to end (docs/WEB_VIEWER.md, "Tests"): the real
// tessera-server of this build serving the built page on its --ws-port,
// Debian's Chromium headless (puppeteer-core), and the C++ tools as the
// other participants: `tessera remote` creates, grants and edits,
// `tessera-replay surface` computes the surface hash the C++ client library
// assembles. Loopback only; every wait is bounded.
//
//   TESSERA_BUILD_DIR=build/release TESSERA_SOURCE_DIR=. node --test tests/web/viewer_e2e.test.mjs
// (ctest runs it as web_viewer_e2e.)
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';

const SOURCE = resolve(process.env.TESSERA_SOURCE_DIR ?? new URL('../..', import.meta.url).pathname);
const BUILD = resolve(process.env.TESSERA_BUILD_DIR ?? join(SOURCE, 'build/release'));
const { launchBrowser, openPage, state } = await import(join(SOURCE, 'client/web/test/support/browser.mjs'));
const { decodePng } = await import(join(SOURCE, 'client/web/test/support/png.mjs'));

const SERVER = join(BUILD, 'server/tessera-server');
const CLI = join(BUILD, 'client/cli/tessera');
const REPLAY = join(BUILD, 'client/replay/tessera-replay');
// The page with its test hook (client/web/CMakeLists.txt, TESSERA_WEB_TEST_HOOK).
const WEB = process.env.TESSERA_WEB_DIR ?? join(BUILD, 'web');
const ADMIN = 'e2e-admin-token-0123456789';
const EDITOR = 'e2e-editor-token-0123456789';
// The LOD profile the page is opened with (?lod=balanced,
// client/web/src/session/lod_profiles.js): tessera-replay assembles the
// same surface. Without ?lod= (or ?views=0) the page would show a view.
const PROFILE = '1,3,15';

let dir, server, ports, browser, documentId;

function sleep(ms) { return new Promise((r) => setTimeout(r, ms)); }

async function until(what, predicate, ms = 30000) {
  const deadline = Date.now() + ms;
  for (;;) {
    const value = await predicate();
    if (value) return value;
    if (Date.now() > deadline) throw new Error(`timed out after ${ms} ms waiting for ${what}`);
    await sleep(50);
  }
}

// Starts the server; with `fixed`, on the ports of the previous run.
async function startServer(fixed) {
  const portFile = join(dir, 'port'), wsPortFile = join(dir, 'ws.port');
  rmSync(portFile, { force: true });
  rmSync(wsPortFile, { force: true });
  const args = ['--data', join(dir, 'data'), '--admin-token-file', join(dir, 'admin.token'),
    '--port', fixed ? String(fixed.tcp) : '0', '--port-file', portFile,
    '--ws-port', fixed ? String(fixed.web) : '0', '--ws-port-file', wsPortFile, '--web-root', WEB];
  const child = spawn(SERVER, args, { stdio: ['ignore', 'ignore', 'pipe'] });
  let log = '';
  child.stderr.on('data', (d) => { log += d; });
  child.log = () => log;
  // The port file is written once every port is bound.
  await until('the server\'s port file', () => existsSync(portFile) && readFileSync(portFile, 'utf8').trim() !== '', 20000);
  return { child, tcp: Number(readFileSync(portFile, 'utf8')), web: Number(readFileSync(wsPortFile, 'utf8')) };
}

async function stopServer() {
  if (!server || server.child.exitCode !== null) return;
  const exited = new Promise((r) => server.child.once('exit', r));
  server.child.kill('SIGTERM');
  await exited;
}

function cli(...args) {
  const r = spawnSync(CLI, ['remote', '--port', String(server.tcp), '--token', ADMIN, ...args], { encoding: 'utf8', timeout: 60000 });
  assert.equal(r.status, 0, `tessera remote ${args.join(' ')}: ${r.stderr}`);
  return r.stdout.trim();
}

// The version and surface hash the C++ client library assembles.
function cppSurface() {
  const r = spawnSync(REPLAY, ['surface', '--port', String(server.tcp), '--token', ADMIN, '--document', String(documentId),
    '--profile', PROFILE], { encoding: 'utf8', timeout: 60000 });
  assert.equal(r.status, 0, r.stderr);
  const version = Number(/version[ =:]+(\d+)/.exec(r.stdout)?.[1]);
  const hash = /surface_hash[ =:]+(?:0x)?([0-9a-f]{16})/.exec(r.stdout)?.[1];
  assert.ok(version > 0 && hash, `tessera-replay surface printed: ${r.stdout}`);
  return { version, hash: `0x${hash}` };
}

function editScript(text) {
  const file = join(dir, `edit-${Date.now()}.txt`);
  writeFileSync(file, text);
  return cli('edit', String(documentId), '--script', file);
}

// Screenshot pixels that differ from the background. The background is a
// vertical gradient, so each row's reference is its pixel at the right
// edge, which the fitted model does not reach.
async function picture(page) {
  return decodePng(await page.screenshot({ type: 'png' }));
}
function coverage(png) {
  let n = 0;
  for (let y = 0; y < png.height; y += 2) {
    const bg = png.pixel(png.width - 2, y);
    for (let x = 0; x < png.width; x += 2) {
      const p = png.pixel(x, y);
      if (Math.abs(p[0] - bg[0]) + Math.abs(p[1] - bg[1]) + Math.abs(p[2] - bg[2]) > 24) ++n;
    }
  }
  return n / (Math.ceil(png.width / 2) * Math.ceil(png.height / 2));
}
function changedPixels(a, b) {
  let n = 0;
  for (let y = 0; y < a.height; y += 2) {
    for (let x = 0; x < a.width; x += 2) {
      const p = a.pixel(x, y), q = b.pixel(x, y);
      if (Math.abs(p[0] - q[0]) + Math.abs(p[1] - q[1]) + Math.abs(p[2] - q[2]) > 24) ++n;
    }
  }
  return n;
}

const pageUrl = (token, doc = documentId) => `http://127.0.0.1:${server.web}/?doc=${doc}&lod=balanced#token=${token}`;
const ready = (page) => page.waitForSelector('body[data-state=ready]', { timeout: 60000 });

before(async () => {
  // The page must be a test build: the checks below read window.tesseraViewer.
  assert.ok(readFileSync(join(WEB, 'viewer.js'), 'utf8').includes('tesseraViewer'),
    `${WEB}/viewer.js has no test hook: configure with -DTESSERA_WEB_TEST_HOOK=ON (build.mjs --test-hook)`);
  dir = mkdtempSync(join(tmpdir(), 'tessera-web-e2e-'));
  writeFileSync(join(dir, 'admin.token'), `${ADMIN}\n`);
  server = await startServer();
  ports = { tcp: server.tcp, web: server.web };
  documentId = Number(cli('create', join(SOURCE, 'tests/data/cube.obj'), '--tags', join(SOURCE, 'tests/data/cube.tags'),
    '--max-level', '4'));
  assert.ok(documentId > 0);
  cli('grant', String(documentId), 'editor', EDITOR);
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  await stopServer();
  if (dir) rmSync(dir, { recursive: true, force: true });
});

test('the page shows the document and its surface hash equals the C++ client\'s', async () => {
  const page = await openPage(browser, pageUrl(EDITOR));
  await ready(page);
  const s = await state(page);
  assert.equal(s.error, '');
  assert.ok(s.hashMatches, `page ${s.surfaceHash}, server ${s.serverSurfaceHash}`);
  const cpp = cppSurface();
  assert.equal(s.version, cpp.version);
  assert.equal(s.surfaceHash, cpp.hash, 'the page and the C++ client assembled different surfaces');
  const png = await picture(page);
  const covered = coverage(png);
  // The cube fills a sensible part of a 1000x680 frame: not a speck, not a
  // wall (HUD and panel are small).
  assert.ok(covered > 0.08 && covered < 0.7, `the silhouette covers ${(covered * 100).toFixed(1)} % of the frame`);
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('another client\'s edit changes the picture and the version', async () => {
  const page = await openPage(browser, pageUrl(EDITOR));
  await ready(page);
  const before = await state(page);
  await sleep(300);  // let the first frames settle
  const shotBefore = await picture(page);
  editScript('move v1:20 to 0.5 0.5 1.6\n');
  const after = await until('the edit in the page', async () => {
    const s = await state(page);
    return s.version > before.version && s.hashMatches ? s : null;
  });
  await sleep(300);
  const changed = changedPixels(shotBefore, await picture(page));
  assert.ok(changed > 200, `only ${changed} sampled pixels changed after the edit`);
  assert.equal(after.surfaceHash, cppSurface().hash);
  await page.close();
});

test('a drag in the page edits the document, and undo restores the surface hash', async () => {
  const page = await openPage(browser, pageUrl(EDITOR));
  await ready(page);
  const start = await state(page);
  const hashBefore = cppSurface();
  assert.equal(hashBefore.hash, start.surfaceHash);
  const vertex = await page.evaluate(() => window.tesseraViewer.someVertexNearCentre());
  assert.ok(vertex, 'no vertex near the centre to drag');
  await page.mouse.move(vertex.x, vertex.y);
  await page.mouse.down();
  for (let i = 1; i <= 8; ++i) {
    await page.mouse.move(vertex.x + 5 * i, vertex.y - 4 * i);
    await sleep(40);
  }
  await page.mouse.up();
  // Undo waits until every edit of the step is answered (acks follow the
  // journal's fsync, which a loaded machine can delay).
  const dragged = await until('the drag\'s edits acknowledged', async () => {
    const s = await state(page);
    return s.version > start.version && s.editsSent > 0 && s.awaitingAnswers === 0 && s.hashMatches ? s : null;
  });
  // The C++ client sees the edited surface.
  await until('the C++ client to see the drag', () => cppSurface().version >= dragged.version);
  const edited = cppSurface();
  assert.notEqual(edited.hash, hashBefore.hash, 'the drag did not change the surface');
  assert.equal(dragged.editsRejected, 0);
  // One undo step takes the whole drag back.
  await sleep(200);
  await page.keyboard.down('Control');
  await page.keyboard.press('z');
  await page.keyboard.up('Control');
  await until('the undo', async () => cppSurface().hash === hashBefore.hash, 30000);
  const undone = await until('the page to show the undo', async () => {
    const s = await state(page);
    return s.surfaceHash === hashBefore.hash && s.hashMatches ? s : null;
  });
  assert.ok(undone.version > dragged.version);
  assert.deepEqual(page.problems, []);
  await page.close();
});

test('a wrong token is shown as a clear message', async () => {
  const page = await openPage(browser, pageUrl('this-token-is-wrong-0123456789'));
  const s = await until('the refusal', async () => {
    const t = await state(page);
    return t.error ? t : null;
  });
  assert.match(s.error, /not known/);
  const text = await page.evaluate(() => document.body.innerText);
  assert.match(text, /access token is not known/);
  await page.close();
});

test('a server restart is survived by reconnecting', async () => {
  const page = await openPage(browser, pageUrl(EDITOR));
  await ready(page);
  const before = await state(page);
  await stopServer();
  await until('the page to notice', async () => !(await state(page)).connected, 15000);
  server = await startServer(ports);
  editScript('offset v2:3 by 0 0 0.05\n');
  const after = await until('the page to reconnect and show the new version', async () => {
    const s = await state(page);
    return s.connected && s.version > before.version && s.hashMatches ? s : null;
  }, 60000);
  assert.equal(after.surfaceHash, cppSurface().hash);
  await page.close();
});

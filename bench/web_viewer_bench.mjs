// The browser viewer's figures (docs/PERFORMANCE.md "Browser
// viewer"), in Debian's Chromium, headless, with SwiftShader's software WebGL
// (no GPU here), against this build's tessera-server on loopback:
//   1. page load to the first full picture: from navigation (a fresh browser
//      context: nothing cached) to the first frame drawn once the snapshot is
//      applied and its hash checked, for the creased cube (profile
//      "balanced") and for knot1 from CGAL's data at profile "fine" (98,124
//      triangles);
//   2. edit to pixels: tessera_timed_editor (C++) sends offset edits and
//      prints each one's send time; every tab records when it first drew
//      each version (window.tesseraViewer.versionsShown()); both clocks are
//      this machine's wall clock. With 1 tab and with 20 tabs of the cube,
//      each tab in a window of its own (all visible);
//   3. bytes transferred for one page load (CDP's encodedDataLength), and
//      the JavaScript + WebAssembly among them.
//
//   node bench/web_viewer_bench.mjs [--build build/release] [--loads 5] [--edits 60] [--interval-ms 150]
// Bounded: every wait has a deadline, the edits are counted.
import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { parseArgs } from 'node:util';

const { values: opts } = parseArgs({
  options: {
    build: { type: 'string', default: 'build/release' },
    loads: { type: 'string', default: '5' },
    edits: { type: 'string', default: '60' },
    'interval-ms': { type: 'string', default: '150' },
    tabs: { type: 'string', default: '1,20' },
  },
});
const SOURCE = resolve(new URL('..', import.meta.url).pathname);
const BUILD = resolve(opts.build);
const { launchBrowser } = await import(join(SOURCE, 'client/web/test/support/browser.mjs'));
const { until } = await import(join(SOURCE, 'client/web/test/support/client.mjs'));
const ADMIN = 'bench-admin-token-0123456789';

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const quantile = (xs, q) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? s[Math.min(s.length - 1, Math.floor(q * (s.length - 1) + 0.5))] : NaN;
};

const dir = mkdtempSync(join(tmpdir(), 'tessera-web-bench-'));
writeFileSync(join(dir, 'admin.token'), `${ADMIN}\n`);
const portFile = join(dir, 'port'), wsPortFile = join(dir, 'ws.port');
const server = spawn(join(BUILD, 'server/tessera-server'), ['--data', join(dir, 'data'), '--admin-token-file', join(dir, 'admin.token'),
  '--port', '0', '--port-file', portFile, '--ws-port', '0', '--ws-port-file', wsPortFile], { stdio: 'ignore' });
let browser;
try {
  await until(() => existsSync(portFile) && readFileSync(portFile, 'utf8').trim(), 'the server', 60000);
  const tcp = Number(readFileSync(portFile, 'utf8')), web = Number(readFileSync(wsPortFile, 'utf8'));
  const cli = (...args) => {
    const r = spawnSync(join(BUILD, 'client/cli/tessera'), ['remote', '--port', String(tcp), '--token', ADMIN, ...args], { encoding: 'utf8' });
    if (r.status !== 0) throw new Error(r.stderr);
    return r.stdout.trim();
  };
  const cube = cli('create', join(SOURCE, 'tests/data/cube.obj'), '--tags', join(SOURCE, 'tests/data/cube.tags'), '--max-level', '4');
  const knot = cli('create', join(BUILD, 'testdata/cgal/knot1.off'), '--max-level', '4');
  const url = (doc, lod) => `http://127.0.0.1:${web}/?doc=${doc}&lod=${lod}#token=${ADMIN}`;
  browser = await launchBrowser();
  console.log(`chromium ${await browser.version()}, SwiftShader WebGL, ${new Date().toISOString()}`);

  // 1 and 3: loads in fresh contexts.
  for (const [name, doc, lod] of [['creased cube, balanced', cube, 'balanced'], ['knot1, fine', knot, 'fine']]) {
    const times = [];
    let bytes = 0, codeBytes = 0, triangles = 0;
    for (let i = 0; i < Number(opts.loads); ++i) {
      const context = await browser.createBrowserContext();
      const page = await context.newPage();
      await page.setViewport({ width: 1280, height: 800 });
      const cdp = await page.createCDPSession();
      await cdp.send('Network.enable');
      const types = new Map();
      let loadBytes = 0, loadCode = 0;
      cdp.on('Network.responseReceived', (e) => types.set(e.requestId, e.response.url));
      cdp.on('Network.loadingFinished', (e) => {
        loadBytes += e.encodedDataLength;
        const u = types.get(e.requestId) ?? '';
        if (u.endsWith('.js') || u.endsWith('.wasm')) loadCode += e.encodedDataLength;
      });
      const t0 = Date.now();
      await page.goto(url(doc, lod));
      await page.waitForSelector('body[data-state=ready]', { timeout: 120000 });
      const shown = await until(() => page.evaluate(() => window.tesseraViewer.versionsShown()[0]?.[1]), 'the first picture', 60000);
      times.push(shown - t0);
      const s = await page.evaluate(() => window.tesseraViewer.state());
      if (!s.hashMatches) throw new Error(`${name}: the page's hash differs from the server's`);
      triangles = s.triangles;
      bytes = loadBytes;
      codeBytes = loadCode;
      await context.close();
    }
    console.log(`load ${name}: ${triangles} triangles; first full picture p50 ${quantile(times, 0.5)} ms, ` +
      `min ${Math.min(...times)} ms, max ${Math.max(...times)} ms over ${times.length} cold loads; ` +
      `transferred ${(bytes / 1024).toFixed(1)} KiB, of which JavaScript + WebAssembly ${(codeBytes / 1024).toFixed(1)} KiB`);
  }

  // 2: edit to pixels.
  for (const tabs of opts.tabs.split(',').map(Number)) {
    // A context per tab: each is a window of its own, visible, so every
    // tab draws (Chromium gives a hidden tab no animation frames, by design).
    const contexts = [];
    const pages = [];
    for (let i = 0; i < tabs; ++i) {
      const context = await browser.createBrowserContext();
      contexts.push(context);
      const page = await context.newPage();
      await page.setViewport({ width: 800, height: 600 });
      await page.goto(url(cube, 'balanced'));
      pages.push(page);
    }
    for (const page of pages) await page.waitForSelector('body[data-state=ready]', { timeout: 120000 });
    await sleep(500);
    const editor = spawnSync(join(BUILD, 'bench/tessera_timed_editor'), ['--port', String(tcp), '--token', ADMIN, '--document', cube,
      '--edits', opts.edits, '--interval-ms', opts['interval-ms']], { encoding: 'utf8', timeout: 600000 });
    if (editor.status !== 0) throw new Error(editor.stderr);
    const sent = new Map(editor.stdout.trim().split('\n').map((l) => l.split(' ').map(Number)));
    const last = Math.max(...sent.keys());
    const latencies = [];
    for (const page of pages) {
      await until(() => page.evaluate((v) => window.tesseraViewer.state().version >= v, last), 'the last edit in every tab', 60000);
    }
    await sleep(300);
    for (const page of pages) {
      // An edit is on screen at the first frame drawn at its version or a
      // later one (edits that arrive together share a frame).
      const shown = (await page.evaluate(() => window.tesseraViewer.versionsShown())).sort((a, b) => a[0] - b[0]);
      for (const [version, at] of sent) {
        const frame = shown.find(([v]) => v >= version);
        if (!frame) throw new Error(`version ${version} was never drawn`);
        latencies.push(frame[1] - at);
      }
    }
    console.log(`edit to pixels, ${tabs} tab(s), ${sent.size} edits every ${opts['interval-ms']} ms: p50 ${quantile(latencies, 0.5).toFixed(1)} ms, ` +
      `p99 ${quantile(latencies, 0.99).toFixed(1)} ms, max ${Math.max(...latencies).toFixed(1)} ms over ${latencies.length} ` +
      `(edit, tab) samples`);
    for (const context of contexts) await context.close();
  }
} finally {
  await browser?.close();
  server.kill('SIGTERM');
  await sleep(500);
  rmSync(dir, { recursive: true, force: true });
}

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
//      the JavaScript + WebAssembly among them;
//   4. with --fandisk-edits N: CGAL's fandisk (12,946 regions) at profile
//      "balanced" in one tab, its snapshot's bytes and decode time in the
//      page's worker, then N timed edits: each delta's regions, bytes and
//      decode time in the worker (the test hook's decodeBatches()), and
//      edit to pixels.
// --codec draco,meshopt measures every case in each region codec
// (docs/REGION_ENCODING.md "meshopt regions"; the page's ?codec=), codecs
// alternating, --repeat times; every line carries the load average (1 min)
// before and after it, as the machine's cores are shared.
//
//   node bench/web_viewer_bench.mjs [--build build/release] [--loads 5] [--edits 60] [--interval-ms 150]
//     [--tabs 1,20] [--codec draco] [--repeat 1] [--fandisk-edits 0] [--web-root DIR]
// --web-root serves a page built elsewhere (client/web/build.mjs --out DIR
// --test-hook) instead of the build's.
// Bounded: every wait has a deadline, the edits are counted.
import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { loadavg, tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { parseArgs } from 'node:util';

const { values: opts } = parseArgs({
  options: {
    build: { type: 'string', default: 'build/release' },
    loads: { type: 'string', default: '5' },
    edits: { type: 'string', default: '60' },
    'interval-ms': { type: 'string', default: '150' },
    tabs: { type: 'string', default: '1,20' },
    codec: { type: 'string', default: 'draco' },
    repeat: { type: 'string', default: '1' },
    'fandisk-edits': { type: 'string', default: '0' },
    'web-root': { type: 'string' },
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

const CODECS = opts.codec.split(',');
// Every case once per codec and repetition, the codecs' order reversed
// every other repetition: neither always runs first on a machine whose
// load moves.
const rounds = [];
for (let r = 0; r < Number(opts.repeat); ++r) rounds.push(r % 2 === 0 ? CODECS : [...CODECS].reverse());
const load = () => loadavg()[0].toFixed(2);
const sum = (xs) => xs.reduce((a, b) => a + b, 0);

const dir = mkdtempSync(join(tmpdir(), 'tessera-web-bench-'));
writeFileSync(join(dir, 'admin.token'), `${ADMIN}\n`);
const portFile = join(dir, 'port'), wsPortFile = join(dir, 'ws.port');
const server = spawn(join(BUILD, 'server/tessera-server'), ['--data', join(dir, 'data'), '--admin-token-file', join(dir, 'admin.token'),
  '--port', '0', '--port-file', portFile, '--ws-port', '0', '--ws-port-file', wsPortFile,
  ...(opts['web-root'] ? ['--web-root', resolve(opts['web-root'])] : [])], { stdio: 'ignore' });
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
  const fandisk = Number(opts['fandisk-edits']) > 0 ? cli('create', join(BUILD, 'testdata/cgal/fandisk.off'), '--max-level', '4') : null;
  const url = (doc, lod, codec) => `http://127.0.0.1:${web}/?doc=${doc}&lod=${lod}&codec=${codec}#token=${ADMIN}`;
  // Runs the timed editor on `doc`; returns [[version, sent Unix ms]].
  const timedEdits = (doc, edits) => {
    const editor = spawnSync(join(BUILD, 'bench/tessera_timed_editor'), ['--port', String(tcp), '--token', ADMIN, '--document', doc,
      '--edits', String(edits), '--interval-ms', opts['interval-ms']], { encoding: 'utf8', timeout: 600000 });
    if (editor.status !== 0) throw new Error(editor.stderr);
    return new Map(editor.stdout.trim().split('\n').map((l) => l.split(' ').map(Number)));
  };
  // Edit to pixels of every (edit, tab): the first frame a tab drew at the
  // edit's version or a later one (edits that arrive together share a frame).
  const editToPixels = async (pages, sent) => {
    const last = Math.max(...sent.keys());
    for (const page of pages) {
      await until(() => page.evaluate((v) => window.tesseraViewer.state().version >= v, last), 'the last edit in every tab', 120000);
    }
    await sleep(300);
    const latencies = [];
    for (const page of pages) {
      const shown = (await page.evaluate(() => window.tesseraViewer.versionsShown())).sort((a, b) => a[0] - b[0]);
      for (const [version, at] of sent) {
        const frame = shown.find(([v]) => v >= version);
        if (!frame) throw new Error(`version ${version} was never drawn`);
        latencies.push(frame[1] - at);
      }
    }
    return latencies;
  };
  browser = await launchBrowser();
  console.log(`chromium ${await browser.version()}, SwiftShader WebGL, ${new Date().toISOString()}`);

  // 1 and 3: loads in fresh contexts.
  for (const codec of Number(opts.loads) > 0 ? rounds.flat() : [])
  for (const [name, doc, lod] of [['creased cube, balanced', cube, 'balanced'], ['knot1, fine', knot, 'fine']]) {
    const loadBefore = load();
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
      await page.goto(url(doc, lod, codec));
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
    console.log(`[${codec}] load ${name}: ${triangles} triangles; first full picture p50 ${quantile(times, 0.5)} ms, ` +
      `min ${Math.min(...times)} ms, max ${Math.max(...times)} ms over ${times.length} cold loads; ` +
      `transferred ${(bytes / 1024).toFixed(1)} KiB, of which JavaScript + WebAssembly ${(codeBytes / 1024).toFixed(1)} KiB` +
      `; load average ${loadBefore} -> ${load()}`);
  }

  // 4: fandisk's snapshot and deltas, one tab.
  for (const codec of fandisk ? rounds.flat() : []) {
    const loadBefore = load();
    const context = await browser.createBrowserContext();
    const page = await context.newPage();
    await page.setViewport({ width: 800, height: 600 });
    const t0 = Date.now();
    await page.goto(url(fandisk, 'balanced', codec));
    await page.waitForSelector('body[data-state=ready]', { timeout: 300000 });
    const readyMs = Date.now() - t0;
    const s = await page.evaluate(() => window.tesseraViewer.state());
    if (!s.hashMatches || s.regionCodecs[codec] !== s.regions) throw new Error(`fandisk, ${codec}: ${JSON.stringify(s.regionCodecs)}, hash ${s.hashMatches}`);
    const snapshot = await page.evaluate(() => window.tesseraViewer.decodeBatches());
    await sleep(500);
    const sent = timedEdits(fandisk, Number(opts['fandisk-edits']));
    const latencies = await editToPixels([page], sent);
    const deltas = (await page.evaluate(() => window.tesseraViewer.decodeBatches())).slice(snapshot.length);
    const after = await page.evaluate(() => window.tesseraViewer.state());
    if (!after.hashMatches || deltas.some((d) => (d.meshopt === d.regions) !== (codec === 'meshopt'))) throw new Error(`fandisk deltas, ${codec}`);
    const ms = deltas.map((d) => d.ms);
    console.log(`[${codec}] fandisk, balanced: ${s.triangles} triangles in ${s.regions} regions; ready ${readyMs} ms; snapshot ` +
      `${sum(snapshot.map((b) => b.bytes))} bytes, decode ${sum(snapshot.map((b) => b.ms)).toFixed(0)} ms in the worker ` +
      `(${snapshot.length} messages); ${deltas.length} deltas of ${sent.size} edits every ${opts['interval-ms']} ms: ` +
      `${(sum(deltas.map((d) => d.regions)) / deltas.length).toFixed(1)} regions and ` +
      `${(sum(deltas.map((d) => d.bytes)) / deltas.length).toFixed(0)} bytes a delta on average, decode a delta p50 ` +
      `${quantile(ms, 0.5).toFixed(2)} ms, p99 ${quantile(ms, 0.99).toFixed(2)} ms, mean ${(sum(ms) / ms.length).toFixed(2)} ms; ` +
      `edit to pixels p50 ${quantile(latencies, 0.5).toFixed(1)} ms, p99 ${quantile(latencies, 0.99).toFixed(1)} ms; ` +
      `load average ${loadBefore} -> ${load()}`);
    await context.close();
  }

  // 2: edit to pixels.
  for (const codec of rounds.flat())
  for (const tabs of opts.tabs.split(',').map(Number)) {
    const loadBefore = load();
    // A context per tab: each is a window of its own, visible, so every
    // tab draws (Chromium gives a hidden tab no animation frames, by design).
    const contexts = [];
    const pages = [];
    for (let i = 0; i < tabs; ++i) {
      const context = await browser.createBrowserContext();
      contexts.push(context);
      const page = await context.newPage();
      await page.setViewport({ width: 800, height: 600 });
      await page.goto(url(cube, 'balanced', codec));
      pages.push(page);
    }
    for (const page of pages) await page.waitForSelector('body[data-state=ready]', { timeout: 120000 });
    await sleep(500);
    const sent = timedEdits(cube, Number(opts.edits));
    const latencies = await editToPixels(pages, sent);
    console.log(`[${codec}] edit to pixels, cube, ${tabs} tab(s), ${sent.size} edits every ${opts['interval-ms']} ms: p50 ${quantile(latencies, 0.5).toFixed(1)} ms, ` +
      `p99 ${quantile(latencies, 0.99).toFixed(1)} ms, max ${Math.max(...latencies).toFixed(1)} ms over ${latencies.length} ` +
      `(edit, tab) samples; load average ${loadBefore} -> ${load()}`);
    for (const context of contexts) await context.close();
  }
} finally {
  await browser?.close();
  server.kill('SIGTERM');
  await sleep(500);
  rmSync(dir, { recursive: true, force: true });
}

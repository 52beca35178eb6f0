// The page's main thread while it decodes (docs/PERFORMANCE.md "Browser
// viewer: decoding in a worker"), in Debian's Chromium, headless, with
// SwiftShader's software WebGL, against a tessera-server on loopback: this
// tree's page and, with --baseline REV, the page of revision REV built the
// same way, one after the other with a fresh server each.
//   1. load: a fresh browser context opens a large document (CGAL's knot1
//      at profile "fine", one snapshot of about 98,000 triangles): time to
//      the page's ready state, and the main thread's long tasks (over 50 ms,
//      the browser's PerformanceObserver "longtask") from navigation to
//      ready;
//   2. edits: TABS tabs, each a window of its own, show the creased cube at
//      "balanced" while a Node client sends EDITS offset edits, one every
//      INTERVAL ms: edit to pixels (the edit's send time to the first frame
//      a tab drew at its version or later, both Date.now() of this machine)
//      and every tab's long tasks during the edits.
// The page of this tree also reports its decode worker's times (the test
// hook's state().decoding).
//   node client/web/bench/main_thread_bench.mjs --server build/release/server/tessera-server \
//     [--baseline HEAD~1] [--tabs 1,8] [--edits 60] [--interval-ms 150]
// Bounded: every wait has a deadline.
import { spawnSync } from 'node:child_process';
import { cpSync, mkdtempSync, rmSync, symlinkSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { parseArgs } from 'node:util';

const { values: opts } = parseArgs({
  options: {
    server: { type: 'string', default: 'build/release/server/tessera-server' },
    baseline: { type: 'string' },
    tabs: { type: 'string', default: '1,8' },
    edits: { type: 'string', default: '60' },
    'interval-ms': { type: 'string', default: '150' },
  },
});
process.env.TESSERA_SERVER = resolve(opts.server);
const WEB = resolve(new URL('..', import.meta.url).pathname);
const SOURCE = resolve(WEB, '../..');
const { startServer, testData } = await import('../test/support/server.mjs');
const { connect, createCube, createMesh, until } = await import('../test/support/client.mjs');
const { launchBrowser } = await import('../test/support/browser.mjs');
const { toLong } = await import('../src/codec/uint64.js');

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const quantile = (xs, q) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? s[Math.min(s.length - 1, Math.floor(q * (s.length - 1) + 0.5))] : NaN;
};
const dir = mkdtempSync(join(tmpdir(), 'tessera-main-thread-bench-'));

function buildPage(webDir, out) {
  const r = spawnSync(process.execPath, [join(webDir, 'build.mjs'), '--out', out, '--test-hook'], { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(r.stderr);
}

// The page of `rev`, built with this tree's node_modules. The server serves
// this tree's five files, so the page that predates the worker gets this
// tree's decode_worker.js beside it, which it never asks for.
function buildBaseline(rev) {
  const src = join(dir, 'baseline-src');
  spawnSync('mkdir', ['-p', src]);
  const archive = spawnSync('sh', ['-c', `git -C "${SOURCE}" archive "${rev}" client/web protocol/tessera.proto | tar -x -C "${src}"`], { encoding: 'utf8' });
  if (archive.status !== 0) throw new Error(archive.stderr);
  symlinkSync(join(WEB, 'node_modules'), join(src, 'client/web/node_modules'));
  const out = join(dir, 'baseline');
  buildPage(join(src, 'client/web'), out);
  cpSync(join(dir, 'current', 'decode_worker.js'), join(out, 'decode_worker.js'));
  return out;
}

// Long tasks of the main thread, from the first script on.
const OBSERVE_LONG_TASKS = () => {
  window.benchLongTasks = [];
  new PerformanceObserver((list) => {
    for (const e of list.getEntries()) window.benchLongTasks.push([e.startTime, e.duration]);
  }).observe({ type: 'longtask', buffered: true });
};
const longTasksSince = (page, since) => page.evaluate((t) => window.benchLongTasks.filter(([at]) => at >= t).map(([, d]) => d), since);
const describeTasks = (durations, pages) => `${durations.length} long tasks (${(durations.length / pages).toFixed(1)} a tab), ` +
  `${durations.reduce((a, b) => a + b, 0).toFixed(0)} ms in all, longest ${durations.length ? Math.max(...durations).toFixed(0) : 0} ms`;
const decodingOf = (s) => s.decoding?.workers
  ? `worker decodes: ${s.decoding.decoded} regions, ${s.decoding.meanMs.toFixed(2)} ms mean, ${s.decoding.p99Ms.toFixed(2)} ms p99 a region; ` +
    `${(s.decoding.meanMs * s.decoding.decoded / Math.max(1, s.decoding.messagesApplied)).toFixed(2)} ms a snapshot or delta`
  : 'decodes on the main thread';

async function run(name, web) {
  const portFile = `${web}.ws-port`;
  const server = await startServer({ extraArgs: ['--ws-port', '0', '--ws-port-file', portFile, '--web-root', web] });
  let browser, admin;
  try {
    const base = `http://127.0.0.1:${await server.waitForFile(portFile, 'its web port')}`;
    admin = await connect(server.port, server.token, 'bench admin');
    const knot = await createMesh(admin, testData('cgal/knot1.off'), 4);
    const cube = await createCube(admin, 4);
    browser = await launchBrowser();
    const url = (doc, lod) => `${base}/?doc=${doc}&lod=${lod}#token=${server.token}`;

    // 1: the large snapshot.
    {
      const context = await browser.createBrowserContext();
      const page = await context.newPage();
      await page.evaluateOnNewDocument(OBSERVE_LONG_TASKS);
      await page.setViewport({ width: 1280, height: 800 });
      const t0 = Date.now();
      await page.goto(url(knot, 'fine'));
      await page.waitForSelector('body[data-state=ready]', { timeout: 180000 });
      const ms = Date.now() - t0;
      const s = await page.evaluate(() => window.tesseraViewer.state());
      if (!s.hashMatches) throw new Error(`${name}: the page's hash differs from the server's`);
      console.log(`${name}: load knot1 fine, ${s.triangles} triangles in ${s.regions} regions: ready in ${ms} ms; ` +
        `main thread ${describeTasks(await longTasksSince(page, 0), 1)}; ${decodingOf(s)}`);
      await context.close();
    }

    // 2: edits while TABS tabs watch.
    for (const tabs of opts.tabs.split(',').map(Number)) {
      const contexts = [], pages = [];
      for (let i = 0; i < tabs; ++i) {
        const context = await browser.createBrowserContext();
        contexts.push(context);
        const page = await context.newPage();
        await page.evaluateOnNewDocument(OBSERVE_LONG_TASKS);
        await page.setViewport({ width: 800, height: 600 });
        await page.goto(url(cube, 'balanced'));
        pages.push(page);
      }
      for (const page of pages) await page.waitForSelector('body[data-state=ready]', { timeout: 180000 });
      await sleep(500);
      const starts = await Promise.all(pages.map((p) => p.evaluate(() => performance.now())));
      await admin.call({ open_document: { document_id: toLong(cube) } });
      const sent = new Map(); // version -> Date.now() at send
      for (let i = 0; i < Number(opts.edits); ++i) {
        const at = Date.now();
        const reply = await admin.call({
          move_vertex: {
            document_id: toLong(cube), vertex_ids: [toLong(6n)], mode: 2, // MOVE_MODE_OFFSET
            target: { x: 0, y: i % 2 ? -0.01 : 0.01, z: 0 },
          },
        });
        sent.set(Number(reply.message.ack.version), at);
        await sleep(Math.max(0, Number(opts['interval-ms']) - (Date.now() - at)));
      }
      const last = Math.max(...sent.keys());
      for (const page of pages) {
        await until(() => page.evaluate((v) => window.tesseraViewer.state().version >= v, last), 'the last edit in every tab', 120000);
      }
      await sleep(300);
      const latencies = [], tasks = [];
      for (const [i, page] of pages.entries()) {
        const shown = (await page.evaluate(() => window.tesseraViewer.versionsShown())).sort((a, b) => a[0] - b[0]);
        for (const [version, at] of sent) {
          const frame = shown.find(([v]) => v >= version);
          if (!frame) throw new Error(`version ${version} was never drawn`);
          latencies.push(frame[1] - at);
        }
        tasks.push(...await longTasksSince(page, starts[i]));
      }
      const s = await pages[0].evaluate(() => window.tesseraViewer.state());
      if (!s.hashMatches) throw new Error(`${name}: the page's hash differs from the server's after the edits`);
      console.log(`${name}: ${tabs} tab(s), ${sent.size} edits every ${opts['interval-ms']} ms: edit to pixels p50 ${quantile(latencies, 0.5).toFixed(1)} ms, ` +
        `p99 ${quantile(latencies, 0.99).toFixed(1)} ms, max ${Math.max(...latencies).toFixed(1)} ms over ${latencies.length} samples; ` +
        `main thread ${describeTasks(tasks, tabs)}; first tab's ${decodingOf(s)}`);
      for (const context of contexts) await context.close();
    }
  } finally {
    await browser?.close();
    admin?.stop();
    await server.stop();
  }
}

try {
  const current = join(dir, 'current');
  buildPage(WEB, current);
  const baseline = opts.baseline ? buildBaseline(opts.baseline) : null;
  const browser = await launchBrowser();
  console.log(`chromium ${await browser.version()}, SwiftShader WebGL, ${new Date().toISOString()}, load ${(await import('node:os')).loadavg().map((l) => l.toFixed(2)).join(' ')}`);
  await browser.close();
  if (baseline) await run(`baseline ${opts.baseline}`, baseline);
  await run('this tree', current);
} finally {
  rmSync(dir, { recursive: true, force: true });
}

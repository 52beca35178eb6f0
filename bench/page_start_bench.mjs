// The browser page's first second (docs/PERFORMANCE.md "The page's first
// second"): Debian's Chromium, headless, SwiftShader's software WebGL, a
// phone-sized page (390x844) on the sample cube, served by this build's
// tessera-server from each given page build in turn (client/web/build.mjs
// --out DIR --test-hook), a fresh server and browser per run. Per run: the
// page's milestones (its decoder ready, its HelloAck), its first picture,
// and the main thread's long tasks (start and duration, ms from navigation);
// then each build's first pictures and their median.
//   node bench/page_start_bench.mjs [--rounds 6] [--latency MS --kbps N] DIR [DIR...]
// --latency and --kbps emulate a slower network (Chromium's DevTools
// network conditions: added round-trip latency, download and upload rate).
// Bounded: every wait has a deadline.
import { rmSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { parseArgs } from 'node:util';

const { values: opts, positionals: roots } = parseArgs({
  options: { rounds: { type: 'string', default: '6' }, latency: { type: 'string' }, kbps: { type: 'string' } },
  allowPositionals: true,
});
if (roots.length === 0) {
  console.error('usage: node bench/page_start_bench.mjs [--rounds N] WEB_ROOT [WEB_ROOT...]');
  process.exit(2);
}
const SUPPORT = join(resolve(new URL('..', import.meta.url).pathname), 'client/web/test/support');
const { startServer } = await import(join(SUPPORT, 'server.mjs'));
const { connect, createCube, grant } = await import(join(SUPPORT, 'client.mjs'));
const { launchBrowser } = await import(join(SUPPORT, 'browser.mjs'));
const TOKEN = 'page-start-bench-viewer-token';

async function oneRun(root) {
  const portFile = `/tmp/tessera-page-start-${process.pid}.port`;
  const server = await startServer({ extraArgs: ['--ws-port', '0', '--ws-port-file', portFile, '--web-root', resolve(root)] });
  let admin, browser;
  try {
    const base = `http://127.0.0.1:${await server.waitForFile(portFile, 'its web port')}`;
    admin = await connect(server.port, server.token, 'admin');
    const doc = await createCube(admin);
    await grant(admin, TOKEN, 1, doc);
    browser = await launchBrowser();
    const page = await browser.newPage();
    await page.evaluateOnNewDocument(() => {
      window.longTasks = [];
      new PerformanceObserver((list) => {
        for (const e of list.getEntries()) window.longTasks.push([Math.round(e.startTime), Math.round(e.duration)]);
      }).observe({ type: 'longtask', buffered: true });
    });
    await page.setViewport({ width: 390, height: 844 });
    if (opts.latency || opts.kbps) {
      const bytesPerSecond = opts.kbps ? (Number(opts.kbps) * 1000) / 8 : -1;
      await page.emulateNetworkConditions({ download: bytesPerSecond, upload: bytesPerSecond, latency: Number(opts.latency ?? 0) });
    }
    await page.goto(`${base}/?doc=${doc}#token=${TOKEN}`);
    await page.waitForSelector('body[data-state=ready]', { timeout: 30000 });
    return await page.evaluate(() => {
      const s = window.tesseraViewer.state();
      return { milestones: s.milestones, firstPicture: s.firstPicture.ms, longTasks: window.longTasks };
    });
  } finally {
    await browser?.close();
    admin?.stop();
    await server.stop();
    rmSync(portFile, { force: true });
  }
}

const firstPictures = new Map(roots.map((r) => [r, []]));
for (let round = 0; round < Number(opts.rounds); ++round) {
  for (const root of roots) {
    const r = await oneRun(root);
    firstPictures.get(root).push(r.firstPicture);
    console.log(`${root}: decoder ready ${r.milestones.decoderReady} ms, hello ${r.milestones.helloAck} ms, ` +
      `first picture ${r.firstPicture} ms, long tasks [start, ms] ${JSON.stringify(r.longTasks)}`);
  }
}
for (const [root, ms] of firstPictures) {
  const sorted = [...ms].sort((a, b) => a - b);
  console.log(`${root}: first picture ${ms.join(' ')} ms, median ${sorted[Math.floor(sorted.length / 2)]}`);
}

// The browser page with views against its whole-document LOD presets
// (docs/PERFORMANCE.md "Views"), in Debian's Chromium, headless, with
// SwiftShader's software WebGL, against this build's tessera-server on
// loopback: CGAL's armadillo (52,000 faces) held to level 4, a fresh browser
// context per row, phone (390x844) and desktop (1920x1080) pages. Per row:
// navigation to the first picture drawn, navigation to the whole picture
// (the preset's snapshot, or the view's tiles complete), the bytes the
// server sent the page over its WebSocket, the triangles shown and
// triangles per pixel. The server is fresh per run: the first views row
// includes building the tiles it needs.
//   node bench/views_page_bench.mjs [--build build/release] [--screenshots DIR] [--only TEXT]
//       [--web-root DIR] [--no-close-up]
// --only runs the rows whose name contains TEXT ("phone, views");
// --no-close-up leaves out the close-up row.
// --web-root serves a page built elsewhere (client/web/build.mjs --out DIR
// --test-hook), to compare two revisions of the page on one server.
// Bounded: every wait has a deadline.
import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { parseArgs } from 'node:util';

const { values: opts } = parseArgs({
  options: {
    build: { type: 'string', default: 'build/release' }, screenshots: { type: 'string' }, only: { type: 'string' },
    'web-root': { type: 'string' }, 'no-close-up': { type: 'boolean', default: false },
  },
});
const SOURCE = resolve(new URL('..', import.meta.url).pathname);
const BUILD = resolve(opts.build);
const { launchBrowser } = await import(join(SOURCE, 'client/web/test/support/browser.mjs'));
const { until } = await import(join(SOURCE, 'client/web/test/support/client.mjs'));
const ADMIN = 'bench-admin-token-0123456789';


const dir = mkdtempSync(join(tmpdir(), 'tessera-views-page-'));
writeFileSync(join(dir, 'admin.token'), `${ADMIN}\n`);
spawnSync('tar', ['xzf', '/usr/share/doc/libcgal-dev/data.tar.gz', '-C', dir, 'data/meshes/armadillo.off']);
const portFile = join(dir, 'port'), wsPortFile = join(dir, 'ws.port');
const server = spawn(join(BUILD, 'server/tessera-server'), ['--data', join(dir, 'data'), '--admin-token-file', join(dir, 'admin.token'),
  '--port', '0', '--port-file', portFile, '--ws-port', '0', '--ws-port-file', wsPortFile, '--max-level', '4',
  ...(opts['web-root'] ? ['--web-root', resolve(opts['web-root'])] : [])], { stdio: 'ignore' });
let browser;
try {
  await until(() => existsSync(wsPortFile) && readFileSync(wsPortFile, 'utf8').trim(), 'the server', 300000);
  const tcp = Number(readFileSync(portFile, 'utf8')), web = Number(readFileSync(wsPortFile, 'utf8'));
  const created = spawnSync(join(BUILD, 'client/cli/tessera'), ['remote', '--port', String(tcp), '--token', ADMIN, 'create',
    join(dir, 'data/meshes/armadillo.off'), '--max-level', '4'], { encoding: 'utf8' });
  if (created.status !== 0) throw new Error(created.stderr);
  const doc = created.stdout.trim();
  browser = await launchBrowser();
  console.log(`chromium ${await browser.version()}, SwiftShader WebGL, ${new Date().toISOString()}`);
  const rows = [
    ['phone, views 1 px', 390, 844, '&views=1'], ['phone, coarse', 390, 844, '&lod=coarse'],
    ['phone, balanced', 390, 844, '&lod=balanced'],
    ['desktop, views 1 px', 1920, 1080, '&views=1'], ['desktop, balanced', 1920, 1080, '&lod=balanced'],
    // Where a view saves most: close up, where the finest tiles are needed
    // in a small part. The camera moves to a fifth of its distance.
    ['phone, views 1 px, then close up', 390, 844, '&views=1', 0.2],
  ];
  // The page's state once its picture is whole (a view: every tile it
  // needs) and its surface hash matches the server's.
  const complete = (page, views, what) => until(() => page.evaluate((v) => {
    const st = window.tesseraViewer.state();
    return (v ? st.viewComplete : st.ready) && st.hashMatches ? st : null;
  }, views), what, 300000);
  const shoot = async (page, name) => {
    if (opts.screenshots) await page.screenshot({ path: join(opts.screenshots, `${name.replace(/[^a-z0-9]+/g, '-')}.png`) });
  };
  for (const [name, width, height, query, closeUp] of rows) {
    if (opts.only && !name.includes(opts.only)) continue;
    if (closeUp && opts['no-close-up']) continue;
    const context = await browser.createBrowserContext();
    const page = await context.newPage();
    await page.setViewport({ width, height });
    const t0 = Date.now();
    await page.goto(`http://127.0.0.1:${web}/?doc=${doc}${query}#token=${ADMIN}`);
    await page.waitForSelector('body[data-state=ready]', { timeout: 300000 });
    const views = query.includes('views');
    const s = await complete(page, views, 'the whole picture');
    const whole = Date.now() - t0;
    if (closeUp) {
      console.log(`${name}: before moving: ${(s.bytesReceived / 1048576).toFixed(2)} MiB received, ` +
        `${s.triangles} triangles, tiles by level ${JSON.stringify(s.tileLevels)}`);
      const t1 = Date.now();
      await page.evaluate((f) => window.tesseraViewer.dolly(f), closeUp);
      await page.waitForFunction((t) => window.tesseraViewer.state().tiles !== t, { timeout: 300000 }, s.tiles);
      const c = await complete(page, true, 'the close-up picture');
      await shoot(page, name);
      console.log(`${name}: close up complete ${Date.now() - t1} ms after moving, ` +
        `${(c.bytesReceived / 1048576).toFixed(2)} MiB received in all, ${c.triangles} triangles, ` +
        `${(c.triangles / (width * height)).toFixed(2)} per pixel, tiles by level ${JSON.stringify(c.tileLevels)}`);
      await context.close();
      continue;
    }
    await shoot(page, name);
    console.log(`${name}: decoder ready ${s.milestones.decoderReady} ms, hello ${s.milestones.helloAck} ms, ` +
      `first picture ${s.firstPicture.ms} ms (${s.firstPicture.triangles} triangles), ` +
      `whole ${whole} ms, ${(s.bytesReceived / 1048576).toFixed(2)} MiB received, ${s.triangles} triangles, ` +
      `${(s.triangles / (width * height)).toFixed(2)} per pixel${views ? `, tiles by level ${JSON.stringify(s.tileLevels)}` : ''}`);
    await context.close();
  }
} finally {
  await browser?.close();
  server.kill('SIGTERM');
  await new Promise((r) => server.once('exit', r));
  rmSync(dir, { recursive: true, force: true });
}

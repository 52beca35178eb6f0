// Builds the page into one directory of exactly five files, the ones
// tessera-server --ws-port serves (server/net/static_files.h): index.html,
// viewer.css, viewer.js (the page's modules and libraries in one minified
// bundle, protocol/tessera.proto inside as text), decode_worker.js (the Web
// Worker that decodes region payloads with Draco, a bundle of its own: the
// page's main thread never loads Draco, docs/WEB_VIEWER.md "Decoding in a
// worker") and draco_decoder.wasm (copied from the draco3d package, never
// kept in the repository; the worker fetches it). Offline once `npm ci` has
// run.
//
//   node client/web/build.mjs --out DIR [--test-hook]
//
// --test-hook builds the page for the headless-browser tests and the
// benchmark: with window.tesseraViewer (src/test_hook.js, README.md "Test
// hook"). Without it the hook's code is not in viewer.js at all: main.js
// calls it under `if (TESSERA_TEST_HOOK)`, which esbuild's define turns
// into `if (false)` and drops with the module it alone imports.
//
// Prints one line: each file's size, raw and gzip-compressed (node's zlib),
// and the JavaScript + WebAssembly one page load transfers compressed.
import { build } from 'esbuild';
import { copyFileSync, mkdirSync, readFileSync, statSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { gzipSync } from 'node:zlib';

const here = dirname(fileURLToPath(import.meta.url));
const require = createRequire(import.meta.url);
const OUTPUTS = ['index.html', 'viewer.css', 'viewer.js', 'decode_worker.js', 'draco_decoder.wasm'];

function outDirectory(argv) {
  const at = argv.indexOf('--out');
  const value = at >= 0 ? argv[at + 1] : argv.find((a) => a.startsWith('--out='))?.slice(6);
  if (!value) {
    console.error('usage: node client/web/build.mjs --out DIR [--test-hook]');
    process.exit(2);
  }
  return resolve(value);
}

const argv = process.argv.slice(2);
const out = outDirectory(argv);
const testHook = argv.includes('--test-hook');
mkdirSync(out, { recursive: true });

const common = {
  bundle: true,
  minify: true,
  format: 'iife',
  platform: 'browser',
  target: 'es2020',
  define: { TESSERA_TEST_HOOK: String(testHook) },
  legalComments: 'none',
  logLevel: 'warning',
};
await build({
  ...common,
  entryPoints: [join(here, 'src/main.js')],
  outfile: join(out, 'viewer.js'),
  loader: { '.proto': 'text' },
});
// A classic worker script (format iife), which every browser runs.
await build({
  ...common,
  entryPoints: [join(here, 'src/codec/decode_worker.js')],
  outfile: join(out, 'decode_worker.js'),
  // draco3d's wrapper reads its .wasm with node:fs only under Node; the
  // worker hands it the bytes instead, so the branch never runs in a browser.
  external: ['node:fs'],
});
copyFileSync(join(here, 'index.html'), join(out, 'index.html'));
copyFileSync(join(here, 'viewer.css'), join(out, 'viewer.css'));
copyFileSync(require.resolve('draco3d/draco_decoder.wasm'), join(out, 'draco_decoder.wasm'));

const sizes = OUTPUTS.map((name) => {
  const bytes = readFileSync(join(out, name));
  return { name, raw: statSync(join(out, name)).size, gzip: gzipSync(bytes, { level: 9 }).length };
});
const kb = (n) => `${(n / 1024).toFixed(1)} KiB`;
const code = sizes.filter((s) => s.name.endsWith('.js') || s.name.endsWith('.wasm'));
console.log(`${out}${testHook ? ' (with the test hook)' : ''}: ` + sizes.map((s) => `${s.name} ${kb(s.raw)} (gzip ${kb(s.gzip)})`).join(', ') +
  `; JavaScript + WebAssembly per page load: ${kb(code.reduce((a, s) => a + s.raw, 0))} raw, ` +
  `${kb(code.reduce((a, s) => a + s.gzip, 0))} gzip`);

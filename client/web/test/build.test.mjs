// build.mjs: the page as served has no test hook; a build with --test-hook
// has window.tesseraViewer (src/test_hook.js), which the headless-browser
// tests and the benchmark read. Draco is in the decode worker's bundle
// only.
import { test, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

const dir = mkdtempSync(join(tmpdir(), 'tessera-web-build-test-'));
after(() => rmSync(dir, { recursive: true, force: true }));

function build(name, ...flags) {
  const out = join(dir, name);
  const r = spawnSync(process.execPath, [new URL('../build.mjs', import.meta.url).pathname, '--out', out, ...flags], { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  assert.deepEqual(readdirSync(out).sort(), ['decode_worker.js', 'draco_decoder.wasm', 'index.html', 'viewer.css', 'viewer.js']);
  return readFileSync(join(out, 'viewer.js'), 'utf8');
}

// A name of draco3d's decoder interface, which the Emscripten wrapper
// spells out as text.
const DRACO_NAME = 'DecodeArrayToMesh';

test('the page\'s bundle holds no Draco decoder; the decode worker\'s does (docs/WEB_VIEWER.md "Decoding in a worker")', () => {
  const js = build('split');
  assert.ok(!js.includes(DRACO_NAME), 'viewer.js bundles the Draco decoder: the main thread could load it');
  assert.ok(!js.includes('draco_decoder.wasm'), 'viewer.js names the .wasm: the main thread could fetch it');
  assert.ok(js.includes('decode_worker.js'), 'viewer.js does not start the worker');
  const worker = readFileSync(join(dir, 'split', 'decode_worker.js'), 'utf8');
  assert.ok(worker.includes(DRACO_NAME) && worker.includes('draco_decoder.wasm'), 'decode_worker.js lacks the Draco decoder');
});

// Names only the hook has; property names survive minification.
const HOOK_NAMES = ['tesseraViewer', 'someVertexNearCentre', 'screenPointOfVertex', 'renderedFrames', 'versionsShown'];

test('the production bundle leaves the test hook out', () => {
  const js = build('production');
  for (const name of HOOK_NAMES) assert.ok(!js.includes(name), `${name} is in the production viewer.js`);
  assert.ok(!js.includes('TESSERA_TEST_HOOK'), 'the define was not applied');
});

test('--test-hook builds the page with window.tesseraViewer', () => {
  const js = build('test', '--test-hook');
  for (const name of HOOK_NAMES) assert.ok(js.includes(name), `${name} is missing from the test build's viewer.js`);
});

// build.mjs: the page as served has no test hook; a build with --test-hook
// has window.tesseraViewer (src/test_hook.js), which the headless-browser
// tests and the benchmark read.
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
  assert.deepEqual(readdirSync(out).sort(), ['draco_decoder.wasm', 'index.html', 'viewer.css', 'viewer.js']);
  return readFileSync(join(out, 'viewer.js'), 'utf8');
}

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

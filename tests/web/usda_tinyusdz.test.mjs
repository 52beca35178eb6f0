// A .usda written by Tessera, read by an independent USD reader: TinyUSDZ
// (npm's tinyusdz 0.9.0-rc10, its C++ reader compiled to WebAssembly;
// docs/FORMATS.md "USD"). A hand-written quad cube with OpenSubdiv's tags
// goes through `tessera refine --scheme catmull-clark` to .usda; what
// TinyUSDZ reads must be the hand-written points, faces, creases and
// corners (level 0), and at level 1 what Tessera writes to OBJ for the same
// level (another writer, read here by a few lines of JavaScript).
//
// tinyusdz 0.9.0-rc10 is built for browsers only (emscripten's
// -sENVIRONMENT=web): under Node it aborts at start ("node environment
// detected but not enabled at build time"). The test lets it see a browser
// (a `window`, process.type "renderer") and hands it its wasm bytes; its
// reader then runs unchanged.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

const CLI = process.env.TESSERA_CLI;
const WEB = process.env.TESSERA_WEB_SOURCE_DIR;

async function loadTinyUsdz() {
  const require = createRequire(join(WEB, 'package.json'));
  globalThis.window = globalThis;
  process.type = 'renderer';
  const { default: init } = await import(pathToFileURL(require.resolve('tinyusdz/tinyusdz.js')).href);
  return init({ wasmBinary: readFileSync(require.resolve('tinyusdz/tinyusdz.wasm')) });
}

// The layer as TinyUSDZ read it, printed back by TinyUSDZ.
function tinyLayer(native, path) {
  const usd = new native.TinyUSDZLoaderNative();
  const ok = usd.loadAsLayerFromBinary(new Uint8Array(readFileSync(path)), path);
  assert.ok(ok, `TinyUSDZ refused ${path}: ${usd.error()}`);
  return usd.layerToString();
}

// `NAME = [...]` of a printed layer: numbers, or (x, y, z) tuples.
function arrayOf(text, name) {
  const start = text.indexOf(` ${name} = [`);
  if (start < 0) return null;
  const open = text.indexOf('[', start);
  const close = text.indexOf(']', open);
  const body = text.slice(open + 1, close);
  if (body.includes('(')) {
    return [...body.matchAll(/\(([^)]*)\)/g)].map((m) => m[1].split(',').map(Number));
  }
  return body.trim() === '' ? [] : body.split(',').map(Number);
}

function tokenOf(text, name) {
  const m = text.match(new RegExp(` ${name.replace(':', '\\:')} = "([^"]*)"`));
  return m ? m[1] : null;
}

// Creases as "min-max:sharpness", sorted: edges in either direction.
function creaseSet(pairs, sharpness) {
  return pairs.map(([a, b], k) => `${Math.min(a, b)}-${Math.max(a, b)}:${sharpness[k]}`).sort();
}

function layerCage(text) {
  const indices = arrayOf(text, 'creaseIndices') ?? [];
  const lengths = arrayOf(text, 'creaseLengths') ?? [];
  const sharp = arrayOf(text, 'creaseSharpnesses') ?? [];
  assert.ok(lengths.every((n) => n === 2), 'Tessera writes one crease per edge');
  const pairs = lengths.map((_, k) => [indices[2 * k], indices[2 * k + 1]]);
  return {
    scheme: tokenOf(text, 'subdivisionScheme'),
    boundary: tokenOf(text, 'interpolateBoundary'),
    points: arrayOf(text, 'points'),
    counts: arrayOf(text, 'faceVertexCounts'),
    indices: arrayOf(text, 'faceVertexIndices'),
    creases: creaseSet(pairs, sharp),
    corners: (arrayOf(text, 'cornerIndices') ?? []).map((v, k) => `${v}:${arrayOf(text, 'cornerSharpnesses')[k]}`).sort(),
  };
}

// An OBJ as Tessera writes it: v, f and OpenSubdiv's t lines.
function objCage(text) {
  const points = [], counts = [], indices = [], pairs = [], sharp = [], corners = [];
  for (const line of text.split('\n')) {
    const t = line.trim().split(/\s+/);
    if (t[0] === 'v') points.push(t.slice(1, 4).map(Number));
    if (t[0] === 'f') {
      counts.push(t.length - 1);
      indices.push(...t.slice(1).map((c) => Number(c.split('/')[0]) - 1));
    }
    if (t[0] === 't' && t[1] === 'crease') {
      pairs.push([Number(t[3]), Number(t[4])]);
      sharp.push(Number(t[5]));
    }
    if (t[0] === 't' && t[1] === 'corner') corners.push(`${t[3]}:${Number(t[4])}`);
  }
  return { points, counts, indices, creases: creaseSet(pairs, sharp), corners: corners.sort() };
}

// A unit quad cube, tagged by hand: the top rim infinitely sharp, the
// vertical edges 2.5, one corner.
const CUBE_POINTS = [
  [-0.5, -0.5, -0.5], [0.5, -0.5, -0.5], [0.5, 0.5, -0.5], [-0.5, 0.5, -0.5],
  [-0.5, -0.5, 0.5], [0.5, -0.5, 0.5], [0.5, 0.5, 0.5], [-0.5, 0.5, 0.5],
];
const CUBE_FACES = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];
const CUBE_OBJ = [
  ...CUBE_POINTS.map((p) => `v ${p.join(' ')}`),
  ...CUBE_FACES.map((f) => `f ${f.map((v) => v + 1).join(' ')}`),
  't crease 2/1/0 4 5 10', 't crease 2/1/0 5 6 10', 't crease 2/1/0 6 7 10', 't crease 2/1/0 7 4 10',
  't crease 2/1/0 0 4 2.5', 't crease 2/1/0 1 5 2.5', 't crease 2/1/0 2 6 2.5', 't crease 2/1/0 3 7 2.5',
  't corner 1/1/0 0 10', 't interpolateboundary 1/0/0 1',
].join('\n') + '\n';

function tessera(...args) {
  const run = spawnSync(CLI, args, { encoding: 'utf8' });
  assert.equal(run.status, 0, `tessera ${args.join(' ')}: ${run.stderr}`);
}

test('TinyUSDZ reads the points, faces, creases and corners of a cage Tessera wrote', async () => {
  assert.ok(CLI && WEB, 'TESSERA_CLI and TESSERA_WEB_SOURCE_DIR must be set (tests/CMakeLists.txt)');
  const native = await loadTinyUsdz();
  const dir = mkdtempSync(join(tmpdir(), 'usda-tinyusdz-'));
  try {
    const input = join(dir, 'cube.obj');
    writeFileSync(input, CUBE_OBJ);
    for (const level of [0, 1]) {
      tessera('refine', input, '--scheme', 'catmull-clark', '--level', String(level), '-o', join(dir, `cage${level}.usda`));
      tessera('refine', input, '--scheme', 'catmull-clark', '--level', String(level), '-o', join(dir, `cage${level}.obj`));
    }
    const level0 = layerCage(tinyLayer(native, join(dir, 'cage0.usda')));
    assert.equal(level0.scheme, 'catmullClark');
    assert.equal(level0.boundary, 'edgeAndCorner');
    assert.deepEqual(level0.points, CUBE_POINTS);
    assert.deepEqual(level0.counts, CUBE_FACES.map((f) => f.length));
    assert.deepEqual(level0.indices, CUBE_FACES.flat());
    assert.deepEqual(level0.creases, creaseSet(
      [[4, 5], [5, 6], [6, 7], [7, 4], [0, 4], [1, 5], [2, 6], [3, 7]], [10, 10, 10, 10, 2.5, 2.5, 2.5, 2.5]));
    assert.deepEqual(level0.corners, ['0:10']);

    // Level 1: decayed values (2.5 -> 1.5) and 26 points, as TinyUSDZ reads
    // them; the points as float, which is how USD holds point3f.
    const level1 = layerCage(tinyLayer(native, join(dir, 'cage1.usda')));
    const obj = objCage(readFileSync(join(dir, 'cage1.obj'), 'utf8'));
    assert.equal(level1.points.length, 26);
    const asFloat = (points) => points.map((p) => p.map(Math.fround));
    assert.deepEqual(asFloat(level1.points), asFloat(obj.points));
    assert.deepEqual(level1.counts, obj.counts);
    assert.deepEqual(level1.indices, obj.indices);
    assert.deepEqual(level1.creases, obj.creases);
    assert.ok(level1.creases.some((c) => c.endsWith(':1.5')), 'a vertical edge decayed to 1.5');
    assert.deepEqual(level1.corners, obj.corners);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

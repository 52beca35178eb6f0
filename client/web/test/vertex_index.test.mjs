// VertexIndex: kept per region, so that a delta costs its own regions; after
// any sequence of changes it must hold exactly what the definition says:
// every id of every region in the view, at the position the region gives.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { VertexIndex } from '../src/scene/vertex_index.js';

const TWO_32 = 4294967296;

// A region holding vertices `indices` (born at level 0 if index < 8, else 1),
// each at (index, 0, 0), or (index + 0.5, 0, 0) once in `moved`: one surface,
// so a vertex held by several regions is at the same place in each.
function region(indices, moved = new Set()) {
  const n = indices.length;
  const r = { idHi: new Uint32Array(n), idLo: new Uint32Array(n), positions: new Float32Array(3 * n), normals: new Float32Array(3 * n) };
  indices.forEach((index, p) => {
    r.idHi[p] = ((index < 8 ? 0 : 1) << 26) | Math.floor(index / TWO_32);
    r.idLo[p] = index % TWO_32;
    r.positions[3 * p] = index + (moved.has(index) ? 0.5 : 0);
    r.normals[3 * p + 2] = 1;
  });
  return r;
}

// What the index must hold for `regions`, straight from the definition.
function expected(regions) {
  const out = new Map();
  for (const r of regions.values()) {
    for (let p = 0; p < r.idHi.length; ++p) out.set((r.idHi[p] & 0x03ffffff) * TWO_32 + r.idLo[p], r.positions[3 * p]);
  }
  return out;
}

function assertHolds(index, regions, what) {
  const want = expected(regions);
  assert.equal(index.byIndex.size, want.size, `${what}: vertex count`);
  for (const [i, x] of want) {
    const v = index.lookup(BigInt(i));
    assert.ok(v, `${what}: vertex ${i} missing`);
    assert.equal(v.position[0], x, `${what}: vertex ${i}'s position`);
  }
  const level0 = [...want.keys()].filter((i) => i < 8).sort((a, b) => a - b);
  assert.deepEqual(index.atLevel(0).map((v) => v.index).sort((a, b) => a - b), level0, `${what}: level 0`);
  assert.equal(index.atLevel(1).length, want.size, `${what}: level 1`);
}

test('a delta updates only its regions, and shared vertices stay while a region holds them', () => {
  const regions = new Map([[1n, region([0, 1, 8, 9])], [2n, region([1, 2, 9, 10])], [3n, region([2, 3, 11])]]);
  const index = new VertexIndex();
  index.apply({ kind: 'snapshot', regions }, regions);
  assertHolds(index, regions, 'snapshot');

  // Region 1's vertices move; vertices 1 and 9 are shared with region 2,
  // which the delta also carries, as an edit's delta does.
  const moved = new Set([0, 1, 8, 9]);
  regions.set(1n, region([0, 1, 8, 9], moved));
  regions.set(2n, region([1, 2, 9, 10], moved));
  const touched = [];
  const add = index.add.bind(index);
  index.add = (id, r) => { touched.push(id); add(id, r); };
  index.apply({ kind: 'delta', changed: [1n, 2n], removed: [] }, regions);
  assert.deepEqual(touched, [1n, 2n], 'only the changed regions were read');
  assertHolds(index, regions, 'after a delta');

  // Region 2 is removed: vertex 2 is still held by region 3, vertex 10 goes.
  regions.delete(2n);
  index.apply({ kind: 'delta', changed: [], removed: [2n] }, regions);
  assertHolds(index, regions, 'after a removal');
  assert.equal(index.lookup(10n), null);
  assert.ok(index.lookup(2n));

  // A region split in two (a delta that removes one id and adds two).
  regions.delete(3n);
  regions.set(4n, region([2, 3]));
  regions.set(5n, region([3, 11, 12]));
  index.apply({ kind: 'delta', changed: [4n, 5n], removed: [3n] }, regions);
  assertHolds(index, regions, 'after a split');

  // A resync snapshot replaces everything.
  const fresh = new Map([[9n, region([5, 6, 13])]]);
  index.apply({ kind: 'snapshot', regions: fresh }, fresh);
  assertHolds(index, fresh, 'after a resync');
});

test('ids at any level name the same vertex; levels hold the vertices born at or above them', () => {
  const regions = new Map([[1n, region([3, 9])]]);
  const index = new VertexIndex();
  index.apply({ kind: 'snapshot', regions }, regions);
  const atLevel2 = (2n << 58n) | 9n; // "v2:9"
  assert.equal(index.lookup(atLevel2).index, 9);
  assert.deepEqual(index.atLevel(0).map((v) => v.index), [3]);
  assert.equal(index.atLevel(3).length, 2);
});

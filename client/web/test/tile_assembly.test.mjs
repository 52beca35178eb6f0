// The page's crack closing (src/scene/tile_assembly.js), as core/view/
// tile_assembly.h does it: a finer tile's vertex on the edge of a coarser
// neighbour goes onto that edge; shared vertices and tiles without a
// coarser neighbour stay.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { closeCracks, isPreview, PREVIEW_ID, shownTiles } from '../src/scene/tile_assembly.js';

function tile(vertices, triangles) {
  return {
    positions: Float32Array.from(vertices.flatMap((v) => v.p)),
    normals: new Float32Array(vertices.length * 3),
    indices: Uint32Array.from(triangles.flat()),
    idHi: new Uint32Array(vertices.length),
    idLo: Uint32Array.from(vertices.map((v) => v.id)),
  };
}

test('a finer tile\'s vertex on a coarser neighbour\'s edge goes onto it', () => {
  // Coarse: one triangle a b c. Fine: a m b d, m a little off the line
  // a-b. A third tile a d b shares the fine one's other sides, as the rest
  // of a closed surface would.
  const coarse = tile([{ id: 1, p: [0, 0, 0] }, { id: 2, p: [2, 0, 0] }, { id: 3, p: [1, -1, 0] }], [[0, 1, 2]]);
  const fine = tile([{ id: 1, p: [0, 0, 0] }, { id: 4, p: [1, 0.1, 0] }, { id: 2, p: [2, 0, 0] }, { id: 5, p: [1, 1, 0] }],
    [[0, 1, 3], [1, 2, 3]]);
  const rest = tile([{ id: 1, p: [0, 0, 0] }, { id: 5, p: [1, 1, 0] }, { id: 2, p: [2, 0, 0] }], [[0, 1, 2]]);
  const { positions, moved } = closeCracks(new Map([[1n, coarse], [2n, fine], [3n, rest]]));
  assert.equal(moved, 1);
  assert.equal(positions.get(1n), coarse.positions, 'the coarse tile keeps its own positions');
  assert.deepEqual([...positions.get(2n)], [0, 0, 0, 1, 0, 0, 2, 0, 0, 1, 1, 0]);
});

// Each tile's boundary is summarised once per region object; a tile a
// delta changed arrives as a new object, and the coarse tile's ends moving
// move the fine tile's vertex with them.
test('after a delta replaces the coarse tile, the fine one closes onto where it is now', () => {
  const coarse = tile([{ id: 1, p: [0, 0, 0] }, { id: 2, p: [2, 0, 0] }, { id: 3, p: [1, -1, 0] }], [[0, 1, 2]]);
  const fine = tile([{ id: 1, p: [0, 0, 0] }, { id: 4, p: [1, 0.1, 0] }, { id: 2, p: [2, 0, 0] }, { id: 5, p: [1, 1, 0] }],
    [[0, 1, 3], [1, 2, 3]]);
  const rest = tile([{ id: 1, p: [0, 0, 0] }, { id: 5, p: [1, 1, 0] }, { id: 2, p: [2, 0, 0] }], [[0, 1, 2]]);
  const held = new Map([[1n, coarse], [2n, fine], [3n, rest]]);
  assert.deepEqual([...closeCracks(held).positions.get(2n)], [0, 0, 0, 1, 0, 0, 2, 0, 0, 1, 1, 0]);
  // The edit raised vertex 2 to z = 2 in every tile that has it.
  const raise = (t) => ({ ...t, positions: Float32Array.from(t.positions, (x, i) => (i === 3 * [...t.idLo].indexOf(2) + 2 ? 2 : x)) });
  held.set(1n, raise(coarse)).set(2n, raise(fine)).set(3n, raise(rest));
  const { positions, moved } = closeCracks(held);
  assert.equal(moved, 1);
  assert.deepEqual([...positions.get(2n)], [0, 0, 0, 1, 0, 1, 2, 0, 2, 1, 1, 0]);
});

test('tiles at one level, and tiles without ids, are left as they are', () => {
  const left = tile([{ id: 1, p: [0, 0, 0] }, { id: 2, p: [1, 0, 0] }, { id: 3, p: [0, 1, 0] }], [[0, 1, 2]]);
  const right = tile([{ id: 2, p: [1, 0, 0] }, { id: 4, p: [1, 1, 0] }, { id: 3, p: [0, 1, 0] }], [[0, 1, 2]]);
  const bare = { ...right, idHi: null, idLo: null };
  const { positions, moved } = closeCracks(new Map([[1n, left], [2n, right], [3n, bare]]));
  assert.equal(moved, 0);
  assert.equal(positions.get(1n), left.positions);
  assert.equal(positions.get(3n), bare.positions);
});

test('the surface\'s preview is no tile: crack closing leaves it, and the tiles, as they are', () => {
  // A fine tile alone has nothing to close. The preview holds its end ids 1
  // and 2 and joins them by an edge: taken for a coarser tile, it would pull
  // id 4 onto that edge.
  const fine = tile([{ id: 1, p: [0, 0, 0] }, { id: 4, p: [1, 0.1, 0] }, { id: 2, p: [2, 0, 0] }, { id: 5, p: [1, 1, 0] }],
    [[0, 1, 3], [1, 2, 3]]);
  const preview = tile([{ id: 1, p: [0, 0, 0] }, { id: 2, p: [2, 0, 0] }, { id: 3, p: [1, -1, 0] }], [[0, 1, 2]]);
  assert.equal(PREVIEW_ID, 0xfc00000000000000n, 'bit 63, level bits 31, index 0');
  const { positions, moved } = closeCracks(new Map([[2n, fine], [PREVIEW_ID, preview]]));
  assert.equal(moved, 0);
  assert.equal(positions.get(2n), fine.positions);
  assert.equal(positions.get(PREVIEW_ID), preview.positions, 'the preview is drawn as it came');
});

test('while the preview is held the page draws it alone; once removed, the tiles', () => {
  const a = tile([{ id: 1, p: [0, 0, 0] }, { id: 2, p: [1, 0, 0] }, { id: 3, p: [0, 1, 0] }], [[0, 1, 2]]);
  const preview = tile([{ id: 1, p: [0, 0, 0] }, { id: 2, p: [1, 0, 0] }, { id: 3, p: [0, 1, 0] }], [[0, 1, 2]]);
  const held = new Map([[PREVIEW_ID, preview], [1n, a], [2n, a]]);
  assert.deepEqual([...shownTiles(held)], [[PREVIEW_ID, preview]]);
  held.delete(PREVIEW_ID);
  assert.equal(shownTiles(held), held);
  assert.equal(isPreview(PREVIEW_ID), true);
  assert.equal(isPreview(PREVIEW_ID - 1n), false);
});

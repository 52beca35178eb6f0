// The page's crack closing (src/scene/tile_assembly.js), as core/view/
// tile_assembly.h does it: a finer tile's vertex on the edge of a coarser
// neighbour goes onto that edge; shared vertices and tiles without a
// coarser neighbour stay.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { closeCracks } from '../src/scene/tile_assembly.js';

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

test('tiles at one level, and tiles without ids, are left as they are', () => {
  const left = tile([{ id: 1, p: [0, 0, 0] }, { id: 2, p: [1, 0, 0] }, { id: 3, p: [0, 1, 0] }], [[0, 1, 2]]);
  const right = tile([{ id: 2, p: [1, 0, 0] }, { id: 4, p: [1, 1, 0] }, { id: 3, p: [0, 1, 0] }], [[0, 1, 2]]);
  const bare = { ...right, idHi: null, idLo: null };
  const { positions, moved } = closeCracks(new Map([[1n, left], [2n, right], [3n, bare]]));
  assert.equal(moved, 0);
  assert.equal(positions.get(1n), left.positions);
  assert.equal(positions.get(3n), bare.positions);
});

// The control cage's edges and segments (src/scene/control_cage.js), against
// counts and ids worked by hand: the cube's 6 quads have the cube's 12
// edges, a shared edge is drawn once, an index above 2^32 packs below the
// level bits, and a segment needs both of its ends shown and a face of its
// turned to the eye.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { cageEdges, cageSegments, facesTowards } from '../src/scene/control_cage.js';
import { toLong } from '../src/codec/uint64.js';
import { idName, packId } from '../src/codec/ids.js';

// deploy/samples/quad_cube.obj's faces, 0-based.
const CUBE_FACES = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];

const cageOf = (level, faces) => ({ level, face_sizes: faces.map((f) => f.length), vertices: faces.flat() });
const names = (edges) => edges.map(([a, b]) => `${idName(a)}-${idName(b)}`);

test('the cube\'s six quads give its twelve edges, each once, as level-0 ids', () => {
  const cage = cageEdges(cageOf(0, CUBE_FACES));
  assert.equal(cage.level, 0);
  assert.equal(cage.faces, 6);
  assert.deepEqual(cage.faceSizes, { 4: 6 });
  // The bottom ring, the top ring and the four uprights.
  assert.deepEqual(names(cage.edges).sort(), [
    'v0:0-v0:1', 'v0:0-v0:3', 'v0:0-v0:4', 'v0:1-v0:2', 'v0:1-v0:5', 'v0:2-v0:3',
    'v0:2-v0:6', 'v0:3-v0:7', 'v0:4-v0:5', 'v0:4-v0:7', 'v0:5-v0:6', 'v0:6-v0:7',
  ]);
  for (const [a, b] of cage.edges) assert.ok(a < b, 'the smaller id first');
});

test('a quad and a triangle sharing an edge give six edges', () => {
  const cage = cageEdges(cageOf(3, [[0, 1, 2, 3], [2, 1, 4]]));
  assert.equal(cage.faces, 2);
  assert.deepEqual(cage.faceSizes, { 3: 1, 4: 1 });
  assert.deepEqual(names(cage.edges), ['v3:0-v3:1', 'v3:1-v3:2', 'v3:2-v3:3', 'v3:0-v3:3', 'v3:1-v3:4', 'v3:2-v3:4']);
  // The shared edge 1-2 belongs to both faces, the others to one.
  assert.deepEqual(cage.edgeFaces, [[0], [0, 1], [0], [0], [1], [1]]);
  assert.deepEqual(cage.starts, [0, 4, 7]);
  assert.deepEqual(cage.corners.map((id) => idName(id)), ['v3:0', 'v3:1', 'v3:2', 'v3:3', 'v3:2', 'v3:1', 'v3:4']);
});

test('one level finer, the cube is 24 quads with 48 edges (V - E + F = 26 - 48 + 24 = 2)', () => {
  // The quad split of each face by hand: its face point, the points of its
  // edges, and a child quad per corner. Indices as the level numbers them
  // (docs/ARCHITECTURE.md "The quad split"): the 8 corners, a point per face
  // (8 + f), then a point per edge (14 + e) in order of first naming.
  const edgeIndex = new Map();
  const edgePoint = (a, b) => {
    const key = a < b ? `${a} ${b}` : `${b} ${a}`;
    if (!edgeIndex.has(key)) edgeIndex.set(key, 14 + edgeIndex.size);
    return edgeIndex.get(key);
  };
  const children = CUBE_FACES.flatMap((f, k) => f.map((c, i) => {
    const prev = f[(i + 3) % 4], next = f[(i + 1) % 4];
    return [c, edgePoint(c, next), 8 + k, edgePoint(prev, c)];
  }));
  assert.equal(edgeIndex.size, 12);
  const cage = cageEdges(cageOf(1, children));
  assert.equal(cage.faces, 24);
  assert.deepEqual(cage.faceSizes, { 4: 24 });
  assert.equal(cage.edges.length, 48);
  assert.equal(new Set(cage.edges.map(([a, b]) => `${a} ${b}`)).size, 48);
});

test('an index above 2^32 packs below the level bits, from the wire\'s Longs and from text', () => {
  const big = 2n ** 32n + 5n;
  for (const corners of [[toLong(0), toLong(big), toLong(7)], ['0', String(big), '7']]) {
    const cage = cageEdges({ level: 2, face_sizes: [3], vertices: corners });
    // (2 << 58) | index, worked out: 576460752303423488 + 4294967301.
    assert.deepEqual(cage.edges, [
      [576460752303423488n, 576460756598390789n],
      [576460752303423495n, 576460756598390789n],
      [576460752303423488n, 576460752303423495n],
    ]);
    assert.deepEqual(names(cage.edges), ['v2:0-v2:4294967301', 'v2:7-v2:4294967301', 'v2:0-v2:7']);
  }
});

test('a reply whose corners do not add up, or with a face of two corners, is refused by name', () => {
  assert.throws(() => cageEdges({ level: 0, face_sizes: [4, 4], vertices: [0, 1, 2, 3, 4, 5, 6] }), /8 corners, but it names 7 vertices/);
  assert.throws(() => cageEdges({ level: 0, face_sizes: [3, 2], vertices: [0, 1, 2, 3, 4] }), /face 1 has 2 corners/);
  assert.throws(() => cageEdges({ level: 0, face_sizes: [3], vertices: [0, 1, 2n ** 58n] }), /does not fit/);
  const empty = cageEdges({ level: 0, face_sizes: [], vertices: [] });
  assert.deepEqual([empty.faces, empty.edges, empty.faceSizes], [0, [], {}]);
});

// The cube's corners at their places (index i at x = i's corner of
// quad_cube.obj), by packed id at `level`, leaving out `hidden`.
const CUBE_POINTS = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]];
function cubePoints(level, hidden = []) {
  const points = new Map();
  CUBE_POINTS.forEach((position, i) => { if (!hidden.includes(i)) points.set(packId(level, i), { position }); });
  return (id) => points.get(id) ?? null;
}

test('a segment joins the positions of its two ends; an edge with an end not shown is skipped', () => {
  const square = cageEdges(cageOf(1, [[0, 1, 2, 3]]));
  const all = cageSegments(square, cubePoints(1));
  assert.equal(all.segments, 4);
  assert.deepEqual([...all.positions], [0, 0, 0, 1, 0, 0, /**/ 1, 0, 0, 1, 1, 0, /**/ 1, 1, 0, 0, 1, 0, /**/ 0, 0, 0, 0, 1, 0]);
  // Without v1:3: only the edges 0-1 and 1-2 have both ends.
  const some = cageSegments(square, cubePoints(1, [3]));
  assert.equal(some.segments, 2);
  assert.deepEqual([...some.positions.subarray(0, 12)], [0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 1, 0]);
  // The ids name the level: the same indices at level 2 are other ids.
  assert.equal(cageSegments(square, cubePoints(2)).segments, 0);
});

// The cube's edges drawn from an eye, as names.
const seenFrom = (eye, hidden = []) => {
  const cube = cageEdges(cageOf(0, CUBE_FACES));
  const { positions, segments } = cageSegments(cube, cubePoints(0, hidden), eye);
  const at = (p) => CUBE_POINTS.findIndex((q) => q.every((x, k) => x === p[k]));
  const out = [];
  for (let s = 0; s < segments; ++s) out.push(`${at(positions.subarray(6 * s, 6 * s + 3))}-${at(positions.subarray(6 * s + 3, 6 * s + 6))}`);
  return out.sort();
};

test('from an eye, an edge is drawn when one of its faces faces the eye: the cube\'s 9 edges one sees', () => {
  // From (3, 2.5, 4) the faces x = 1 (1 2 6 5), y = 1 (2 3 7 6) and z = 1
  // (4 5 6 7) face the eye; their edges are all but the three at corner 0.
  assert.deepEqual(seenFrom([3, 2.5, 4]), ['1-2', '1-5', '2-3', '2-6', '3-7', '4-5', '4-7', '5-6', '6-7']);
  // Straight above: the top face alone.
  assert.deepEqual(seenFrom([0.5, 0.5, 5]), ['4-5', '4-7', '5-6', '6-7']);
  // From below and behind, the other 9.
  assert.deepEqual(seenFrom([-2, -1.5, -3]), ['0-1', '0-3', '0-4', '1-2', '1-5', '2-3', '3-7', '4-5', '4-7']);
  // Without corner 3, its edges go; the face y = 1 still faces the eye by
  // its other three corners, so 2-6 and 6-7 stay.
  assert.deepEqual(seenFrom([3, 2.5, 4], [3]), ['1-2', '1-5', '2-6', '4-5', '4-7', '5-6', '6-7']);
});

test('a face needs three corners shown to face anything, and its front is the counter-clockwise side', () => {
  const square = cageEdges(cageOf(0, [[0, 1, 2, 3]])); // counter-clockwise seen from +z
  const points = cubePoints(0);
  assert.deepEqual([...facesTowards(square, points, [0.5, 0.5, 3])], [1]);
  assert.deepEqual([...facesTowards(square, points, [0.5, 0.5, -3])], [0]);
  assert.equal(cageSegments(square, points, [0.5, 0.5, -3]).segments, 0, 'from behind, nothing');
  assert.equal(cageSegments(square, points, null).segments, 4, 'no eye: every edge');
  assert.deepEqual([...facesTowards(square, cubePoints(0, [2, 3]), [0.5, 0.5, 3])], [0], 'two corners are no polygon');
  // The edge 0-1 with both ends shown, but its one face unknown: not drawn.
  assert.equal(cageSegments(square, cubePoints(0, [2, 3]), [0.5, 0.5, 3]).segments, 0);
});

test('segments are written into a given buffer, which is returned', () => {
  const cage = cageEdges(cageOf(0, CUBE_FACES));
  const out = new Float32Array(6 * 12);
  const drawn = cageSegments(cage, cubePoints(0), null, out);
  assert.equal(drawn.positions, out);
  assert.equal(drawn.segments, 12);
});

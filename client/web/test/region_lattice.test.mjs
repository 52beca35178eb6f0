// Level counts and lattice ids (docs/PROTOCOL.md 3.2, 6.2): the cube's
// counts from the text, a refinement of one triangle worked by hand, and the
// descent against a port of the reference's full table
// (core/tessellation/region_lattice.cc) on every point of deeper lattices.
// Then the same for quads of the quad split (6.2 "Quad lattice ids"): counts
// and small lattices worked by hand, and the descent and the child rules
// against a refinement of the whole square that finds each edge by the two
// vertices it joins (docs/ARCHITECTURE.md "The quad split").
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { LevelCounts, idName, packId } from '../src/codec/ids.js';
import { RegionLattice, quadChildren } from '../src/codec/region_lattice.js';

test('the cube has 8/18/12, then 26/72/48, then 98/288/192', () => {
  const c = new LevelCounts(8, 18, 12, 2);
  assert.deepEqual([c.vertices(0), c.edges(0), c.faces(0)], [8, 18, 12]);
  assert.deepEqual([c.vertices(1), c.edges(1), c.faces(1)], [26, 72, 48]);
  assert.deepEqual([c.vertices(2), c.edges(2), c.faces(2)], [98, 288, 192]);
  assert.equal(c.birthLevel(7), 0);
  assert.equal(c.birthLevel(8), 1);
  assert.equal(c.birthLevel(25), 1);
  assert.equal(c.birthLevel(26), 2);
  assert.equal(c.birthLevel(98), -1);
});

// One triangle (0, 1, 2) whose edges e0 = (0, 1), e1 = (1, 2), e2 = (2, 0)
// all run forward, as the scan of 3.2 numbers them.
const single = { level: 0, index: 0, corners: [0, 1, 2], edges: [0, 1, 2], forward: 7, baseCounts: [3, 3, 1] };

test('one level down: corners keep their ids, midpoints are V0 + e at level 1', () => {
  const lattice = new RegionLattice(single, 1);
  const at = (u, v) => idName(lattice.idAt(u, v));
  assert.equal(at(0, 0), 'v0:0');
  assert.equal(at(2, 0), 'v0:1');
  assert.equal(at(0, 2), 'v0:2');
  assert.equal(at(1, 0), 'v1:3'); // m0, on e0
  assert.equal(at(1, 1), 'v1:4'); // m1, on e1
  assert.equal(at(0, 1), 'v1:5'); // m2, on e2
  assert.throws(() => lattice.idAt(2, 1), /outside/);
});

test('two levels down, worked by hand from the children of 3.2', () => {
  // Level 1: V1 = 6, E1 = 9. Child 0 = (v0, m0, m2) has edges 0 (half of e0
  // at v0), i0 = 2*3 + 0 = 6, and 5 (half of e2 at v0); child 1 = (m0, v1,
  // m1) has edges 1 (half of e0 at v1), 2, and i1 = 7.
  const lattice = new RegionLattice(single, 2);
  const at = (u, v) => idName(lattice.idAt(u, v));
  assert.equal(at(0, 0), 'v0:0');
  assert.equal(at(2, 0), 'v1:3');
  assert.equal(at(1, 0), 'v2:6'); // on e1:0
  assert.equal(at(0, 1), 'v2:11'); // on e1:5
  assert.equal(at(1, 1), 'v2:12'); // on i0 = e1:6
  assert.equal(at(3, 0), 'v2:7'); // on e1:1
  assert.equal(at(2, 1), 'v2:13'); // on i1 = e1:7, shared by children 1 and 3
});

// The reference's construction: refine the whole face, record each point.
function referenceTable(frame, depth) {
  const n = 1 << depth;
  const deepest = frame.level + depth;
  const counts = new LevelCounts(...frame.baseCounts, deepest);
  const table = new Map();
  const record = (p, index) => {
    const key = `${p[0]},${p[1]}`;
    if (!table.has(key)) table.set(key, packId(counts.birthLevel(index), index));
  };
  let nodes = [{ face: frame.index, at: [[0, 0], [n, 0], [0, n]], vertex: frame.corners, edge: frame.edges,
    forward: [frame.forward & 1, frame.forward & 2, frame.forward & 4].map(Boolean) }];
  nodes[0].at.forEach((p, j) => record(p, nodes[0].vertex[j]));
  for (let l = frame.level; l < deepest; ++l) {
    const V = counts.vertices(l), E = counts.edges(l);
    const next = [];
    for (const p of nodes) {
      const m = [], mv = [], half = [];
      for (let j = 0; j < 3; ++j) {
        const a = p.at[j], b = p.at[(j + 1) % 3];
        m.push([(a[0] + b[0]) / 2, (a[1] + b[1]) / 2]);
        mv.push(V + p.edge[j]);
        record(m[j], mv[j]);
        half.push(p.forward[j] ? [[2 * p.edge[j], true], [2 * p.edge[j] + 1, false]]
          : [[2 * p.edge[j] + 1, false], [2 * p.edge[j], true]]);
      }
      const i0 = 2 * E + 3 * p.face;
      next.push({ face: 4 * p.face, at: [p.at[0], m[0], m[2]], vertex: [p.vertex[0], mv[0], mv[2]],
        edge: [half[0][0][0], i0, half[2][1][0]], forward: [half[0][0][1], true, !half[2][1][1]] });
      next.push({ face: 4 * p.face + 1, at: [m[0], p.at[1], m[1]], vertex: [mv[0], p.vertex[1], mv[1]],
        edge: [half[0][1][0], half[1][0][0], i0 + 1], forward: [!half[0][1][1], half[1][0][1], true] });
      next.push({ face: 4 * p.face + 2, at: [m[2], m[1], p.at[2]], vertex: [mv[2], mv[1], p.vertex[2]],
        edge: [i0 + 2, half[1][1][0], half[2][0][0]], forward: [true, !half[1][1][1], half[2][0][1]] });
      next.push({ face: 4 * p.face + 3, at: [m[1], m[2], m[0]], vertex: [mv[1], mv[2], mv[0]],
        edge: [i0 + 2, i0, i0 + 1], forward: [false, false, false] });
    }
    nodes = next;
  }
  return table;
}

test('the descent equals the full table on every point, for every edge direction', () => {
  // A face of the cube's level 1 (26/72/48), with edges that exist there.
  for (let forward = 0; forward < 8; ++forward) {
    const frame = { level: 1, index: 17, corners: [3, 20, 11], edges: [40, 5, 63], forward, baseCounts: [8, 18, 12] };
    for (const depth of [0, 1, 3, 5]) {
      const lattice = new RegionLattice(frame, depth);
      const table = referenceTable(frame, depth);
      const n = 1 << depth;
      assert.equal(table.size, ((n + 1) * (n + 2)) / 2);
      for (let u = 0; u <= n; ++u) {
        for (let v = 0; u + v <= n; ++v) {
          assert.equal(lattice.idAt(u, v), table.get(`${u},${v}`), `forward ${forward}, depth ${depth}, (${u}, ${v})`);
        }
      }
    }
  }
});

test('frames naming elements their level does not have are refused', () => {
  assert.throws(() => new RegionLattice({ ...single, corners: [0, 1, 3] }, 1), /corner or edge 2/);
  assert.throws(() => new RegionLattice({ ...single, index: 1 }, 1), /does not exist/);
  assert.throws(() => new RegionLattice(single, 8), /depth 8/);
});

// ---- Quads (flag 8) ----

test('the quad split counts one quad: 4/4/1/4, then 9/12/4/16, then 25/40/16/64', () => {
  // V1 = V0 + F0 + E0 = 4 + 1 + 4 = 9, E1 = C0 + 2 E0 = 4 + 8 = 12, F1 = C0 = 4,
  // C1 = 4 F1 = 16; V2 = 9 + 4 + 12 = 25, E2 = 16 + 24 = 40, F2 = 16, C2 = 64:
  // the 5 x 5 points, 40 segments and 16 squares of a 4 x 4 grid.
  const c = LevelCounts.quads(4, 4, 1, 4, 2);
  assert.deepEqual([c.vertices(0), c.edges(0), c.faces(0), c.corners(0)], [4, 4, 1, 4]);
  assert.deepEqual([c.vertices(1), c.edges(1), c.faces(1), c.corners(1)], [9, 12, 4, 16]);
  assert.deepEqual([c.vertices(2), c.edges(2), c.faces(2), c.corners(2)], [25, 40, 16, 64]);
  assert.equal(c.birthLevel(3), 0);
  assert.equal(c.birthLevel(4), 1);
  assert.equal(c.birthLevel(24), 2);
  assert.equal(c.birthLevel(25), -1);
});

test('the quad cube has 8/12/6/24, then 26/48/24/96, then 98/192/96/384', () => {
  // V1 = 8 + 6 + 12 = 26, E1 = 24 + 2*12 = 48, F1 = 24, C1 = 96;
  // V2 = 26 + 24 + 48 = 98, E2 = 96 + 2*48 = 192, F2 = 96, C2 = 384.
  const c = LevelCounts.quads(8, 12, 6, 24, 2);
  assert.deepEqual([c.vertices(1), c.edges(1), c.faces(1), c.corners(1)], [26, 48, 24, 96]);
  assert.deepEqual([c.vertices(2), c.edges(2), c.faces(2), c.corners(2)], [98, 192, 96, 384]);
  assert.equal(c.birthLevel(25), 1);
  assert.equal(c.birthLevel(26), 2);
  // Loop's counts of the same numbers differ: the split is the counts' own.
  assert.equal(new LevelCounts(8, 12, 6, 1).vertices(1), 20);
  assert.equal(new LevelCounts(8, 12, 6, 1).corners(0), 18);
  assert.throws(() => LevelCounts.quads(2 ** 50, 2 ** 50, 2 ** 50, 2 ** 52, 3), /exceed 2\^53 at level 1/);
});

test('a triangle beside a quad counts its 7 corners, not 4 per face: 5/6/2/7, then 13/19/7/28, then 39/66/28', () => {
  // V1 = 5 + 2 + 6 = 13, E1 = C0 + 2 E0 = 7 + 12 = 19, F1 = C0 = 7, C1 = 28;
  // V2 = 13 + 7 + 19 = 39, E2 = 28 + 38 = 66, F2 = 28. A disc throughout:
  // V - E + F = 5 - 6 + 2 = 13 - 19 + 7 = 39 - 66 + 28 = 1.
  const c = LevelCounts.quads(5, 6, 2, 7, 2);
  assert.deepEqual([c.vertices(1), c.edges(1), c.faces(1), c.corners(1)], [13, 19, 7, 28]);
  assert.deepEqual([c.vertices(2), c.edges(2), c.faces(2), c.corners(2)], [39, 66, 28, 112]);
});

// One quad (0, 1, 2, 3) whose edges e0 = (0, 1), e1 = (1, 2), e2 = (2, 3),
// e3 = (3, 0) all run forward.
const quad = { sides: 4, level: 0, index: 0, firstChild: 0, corners: [0, 1, 2, 3], edges: [0, 1, 2, 3], forward: 15,
  baseCounts: [4, 4, 1, 4] };

test('a quad one level down: the face vertex is V0 + f, the edge vertices V0 + F0 + e', () => {
  const lattice = new RegionLattice(quad, 1);
  const at = (u, v) => idName(lattice.idAt(u, v));
  assert.deepEqual([at(0, 0), at(2, 0), at(2, 2), at(0, 2)], ['v0:0', 'v0:1', 'v0:2', 'v0:3']);
  assert.equal(at(1, 1), 'v1:4'); // 4 + 0
  assert.equal(at(1, 0), 'v1:5'); // m0: 4 + 1 + e0
  assert.equal(at(2, 1), 'v1:6'); // m1: 4 + 1 + 1
  assert.equal(at(1, 2), 'v1:7'); // m2
  assert.equal(at(0, 1), 'v1:8'); // m3
  assert.throws(() => lattice.idAt(3, 0), /lattice point \(3, 0\) outside/);
  assert.throws(() => lattice.idAt(2, -1), /lattice point \(2, -1\) outside/);
});

test('a quad two levels down, worked by hand from the quad split', () => {
  // n = 4: corners at (0,0) (4,0) (4,4) (0,4); level 1 puts v4 at (2,2), m0 =
  // v5 at (2,0), m1 = v6 at (4,2), m2 = v7 at (2,4), m3 = v8 at (0,2).
  // Level-1 edges (E1 = 12): interior edge c + j = j joins v4 to mj; the
  // halves of e are C0 + 2e + end = 4 + 2e + end, end 0 being the edge's
  // first corner: e0 -> 4 at v0, 5 at v1; e1 -> 6 at v1, 7 at v2; e2 -> 8 at
  // v2, 9 at v3; e3 -> 10 at v3, 11 at v0.
  // Level-1 faces: child j = face j, the square between corner j and (2,2).
  // Level 2 adds V1 + f = 9 + f at each child's centre and V1 + F1 + e =
  // 13 + e at the middle of each level-1 edge.
  const lattice = new RegionLattice(quad, 2);
  const at = (u, v) => idName(lattice.idAt(u, v));
  const expected = {
    '0,0': 'v0:0', '4,0': 'v0:1', '4,4': 'v0:2', '0,4': 'v0:3',
    '2,2': 'v1:4', '2,0': 'v1:5', '4,2': 'v1:6', '2,4': 'v1:7', '0,2': 'v1:8',
    '1,1': 'v2:9', '3,1': 'v2:10', '3,3': 'v2:11', '1,3': 'v2:12', // 9 + f, f = 0..3
    '2,1': 'v2:13', // interior edge 0, v4 to m0: 13 + 0
    '3,2': 'v2:14', // interior edge 1, v4 to m1: 13 + 1
    '2,3': 'v2:15', // interior edge 2: 13 + 2
    '1,2': 'v2:16', // interior edge 3, shared by children 3 and 0: 13 + 3
    '1,0': 'v2:17', // half 4 of e0 at v0: 13 + 4
    '3,0': 'v2:18', // half 5 of e0 at v1: 13 + 5
    '4,1': 'v2:19', // half 6 of e1 at v1
    '4,3': 'v2:20', // half 7 of e1 at v2
    '3,4': 'v2:21', // half 8 of e2 at v2
    '1,4': 'v2:22', // half 9 of e2 at v3
    '0,3': 'v2:23', // half 10 of e3 at v3
    '0,1': 'v2:24', // half 11 of e3 at v0: 13 + 11 = 24 = V2 - 1
  };
  assert.equal(Object.keys(expected).length, 25);
  for (const [key, name] of Object.entries(expected)) {
    const [u, v] = key.split(',').map(Number);
    assert.equal(at(u, v), name, `(${key})`);
  }
  assert.throws(() => lattice.idAt(5, 4), /outside/);
});

// The second face of a mesh whose first face is the triangle (0, 1, 2): the
// quad (1, 3, 4, 2), edges e0 = (0, 1), e1 = (1, 2), e2 = (2, 0), e3 = (3, 1),
// e4 = (4, 3), e5 = (2, 4), each given as (first end, second end). The quad's
// edges (1,3) (3,4) (4,2) (2,1) are e3, e4, e5, e1, every one running from
// corner j+1 to corner j, so no forward bit is set. V0 = 5, E0 = 6, F0 = 2,
// C0 = 3 + 4 = 7, and the quad's children start after the triangle's three.
const second = { sides: 4, level: 0, index: 1, firstChild: 3, corners: [1, 3, 4, 2], edges: [3, 4, 5, 1], forward: 0,
  baseCounts: [5, 6, 2, 7] };

test('a base quad after a triangle, its edges running backwards, worked by hand', () => {
  // Level 1: V1 = 5 + 2 + 6 = 13, F1 = 7, E1 = 7 + 12 = 19. The face vertex is
  // V0 + 1 = 6; the edge vertices V0 + F0 + e = 7 + e.
  const one = new RegionLattice(second, 1);
  const at1 = (u, v) => idName(one.idAt(u, v));
  assert.deepEqual([at1(0, 0), at1(2, 0), at1(2, 2), at1(0, 2)], ['v0:1', 'v0:3', 'v0:4', 'v0:2']);
  assert.equal(at1(1, 1), 'v1:6');
  assert.equal(at1(1, 0), 'v1:10'); // on e3: 7 + 3
  assert.equal(at1(2, 1), 'v1:11'); // on e4
  assert.equal(at1(1, 2), 'v1:12'); // on e5
  assert.equal(at1(0, 1), 'v1:8'); // on e1

  // Level 2 (n = 4): children 3..6 (faces c + j), interior edges 3..6, and
  // halves 7 + 2e + end, end 0 at the edge's first end:
  //   e3 = (3, 1): 13 at v3, 14 at v1;  e4 = (4, 3): 15 at v4, 16 at v3;
  //   e5 = (2, 4): 17 at v2, 18 at v4;  e1 = (1, 2): 9 at v1, 10 at v2.
  // Level 2 adds V1 + f = 13 + f at each child's centre and V1 + F1 + e =
  // 20 + e on each level-1 edge (V2 = 13 + 7 + 19 = 39).
  const two = new RegionLattice(second, 2);
  const at = (u, v) => idName(two.idAt(u, v));
  assert.equal(at(2, 2), 'v1:6');
  assert.equal(at(1, 1), 'v2:16'); // centre of child 0 = face 3: 13 + 3
  assert.equal(at(3, 1), 'v2:17'); // face 4
  assert.equal(at(3, 3), 'v2:18'); // face 5
  assert.equal(at(1, 3), 'v2:19'); // face 6
  assert.equal(at(2, 1), 'v2:23'); // interior edge 3 (v6 to m0): 20 + 3
  assert.equal(at(3, 2), 'v2:24'); // interior edge 4 (v6 to m1)
  assert.equal(at(2, 3), 'v2:25'); // interior edge 5
  assert.equal(at(1, 2), 'v2:26'); // interior edge 6 (v6 to m3), between children 3 and 0
  assert.equal(at(1, 0), 'v2:34'); // half 14 of e3, at v1: 20 + 14
  assert.equal(at(3, 0), 'v2:33'); // half 13 of e3, at v3
  assert.equal(at(4, 1), 'v2:36'); // half 16 of e4, at v3
  assert.equal(at(4, 3), 'v2:35'); // half 15 of e4, at v4
  assert.equal(at(3, 4), 'v2:38'); // half 18 of e5, at v4: 20 + 18 = 38 = V2 - 1
  assert.equal(at(1, 4), 'v2:37'); // half 17 of e5, at v2
  assert.equal(at(0, 3), 'v2:30'); // half 10 of e1, at v2
  assert.equal(at(0, 1), 'v2:29'); // half 9 of e1, at v1
});

// The quad split of docs/ARCHITECTURE.md on the root square alone, refined
// whole: each face's edges are looked up by the vertices they join, never
// by the child rules of 6.2. Interior edge c + j runs from the face vertex
// to the vertex on edge j; parent edge e's halves C + 2e + end run from its
// vertex to its end `end`; child j has the corner j, the vertex on edge j,
// the face vertex and the vertex on edge j-1, rotated so that the corner
// keeps position j. Returns the point -> id table (refusing a point given
// two ids) and the faces and edges of every level.
function quadReference(frame, depth) {
  const n = 1 << depth;
  const deepest = frame.level + depth;
  const counts = LevelCounts.quads(...frame.baseCounts, deepest);
  const table = new Map();
  const record = (p, index) => {
    const key = `${p[0]},${p[1]}`, id = packId(counts.birthLevel(index), index);
    if (table.has(key) && table.get(key) !== id) throw new Error(`(${key}) is ${idName(table.get(key))} and ${idName(id)}`);
    table.set(key, id);
  };
  const pair = (a, b) => (a < b ? `${a} ${b}` : `${b} ${a}`);
  const mid = (a, b) => [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
  let edges = new Map();
  frame.corners.forEach((a, j) => {
    const b = frame.corners[(j + 1) % 4];
    edges.set(pair(a, b), { index: frame.edges[j], ends: frame.forward & (1 << j) ? [a, b] : [b, a] });
  });
  let faces = [{ face: frame.index, first: frame.firstChild, at: [[0, 0], [n, 0], [n, n], [0, n]], vertex: frame.corners }];
  faces[0].at.forEach((p, j) => record(p, frame.corners[j]));
  const levels = [];
  for (let l = frame.level; l < deepest; ++l) {
    levels.push({ faces, edges });
    const V = counts.vertices(l), F = counts.faces(l), C = counts.corners(l);
    const nextEdges = new Map(), nextFaces = [];
    for (const { index, ends } of edges.values()) {
      ends.forEach((end, k) => nextEdges.set(pair(V + F + index, end), { index: C + 2 * index + k, ends: [V + F + index, end] }));
    }
    for (const f of faces) {
      const fv = V + f.face, centre = mid(f.at[0], f.at[2]);
      record(centre, fv);
      const ev = [], eat = [];
      for (let j = 0; j < 4; ++j) {
        const e = edges.get(pair(f.vertex[j], f.vertex[(j + 1) % 4]));
        ev.push(V + F + e.index);
        eat.push(mid(f.at[j], f.at[(j + 1) % 4]));
        record(eat[j], ev[j]);
        nextEdges.set(pair(fv, ev[j]), { index: f.first + j, ends: [fv, ev[j]] });
      }
      for (let j = 0; j < 4; ++j) {
        const i = (j + 3) % 4;
        const ring = [f.vertex[j], ev[j], fv, ev[i]], ringAt = [f.at[j], eat[j], centre, eat[i]];
        const rotated = (a) => [0, 1, 2, 3].map((k) => a[(k - j + 4) % 4]);
        nextFaces.push({ face: f.first + j, first: 4 * (f.first + j), vertex: rotated(ring), at: rotated(ringAt) });
      }
    }
    faces = nextFaces;
    edges = nextEdges;
  }
  levels.push({ faces, edges });
  return { counts, table, levels };
}

// A reference face as the lattice's node: its edges and their directions.
function quadNode(f, edges) {
  const found = f.vertex.map((a, k) => edges.get(`${Math.min(a, f.vertex[(k + 1) % 4])} ${Math.max(a, f.vertex[(k + 1) % 4])}`));
  assert.ok(found.every(Boolean), `face ${f.face} has its four edges`);
  return { ...f, edge: found.map((e) => e.index), forward: found.map((e, k) => e.ends[0] === f.vertex[k]) };
}

// A single quad, the backwards quad after a triangle, and faces of the quad
// cube's levels 1 (26/48/24, C1 = 96) and 2 (98/192/96): indices within
// their levels, first children 4 x index below the base.
const quadFrames = [
  quad,
  second,
  { sides: 4, level: 1, index: 17, firstChild: 68, corners: [3, 20, 11, 25], edges: [40, 5, 47, 30], forward: 0,
    baseCounts: [8, 12, 6, 24] },
  { sides: 4, level: 2, index: 95, firstChild: 380, corners: [97, 0, 50, 26], edges: [191, 100, 7, 64], forward: 0,
    baseCounts: [8, 12, 6, 24] },
];

test('the quad descent equals the whole refinement on every point, for every edge direction', () => {
  for (const base of quadFrames) {
    for (let forward = 0; forward < 16; ++forward) {
      const frame = { ...base, forward };
      for (let depth = 0; depth <= 4; ++depth) {
        const lattice = new RegionLattice(frame, depth);
        const { table } = quadReference(frame, depth);
        const n = 1 << depth;
        assert.equal(table.size, (n + 1) * (n + 1));
        for (let u = 0; u <= n; ++u) {
          for (let v = 0; v <= n; ++v) {
            assert.equal(lattice.idAt(u, v), table.get(`${u},${v}`),
              `f${frame.level}:${frame.index}, forward ${forward}, depth ${depth}, (${u}, ${v})`);
          }
        }
      }
    }
  }
});

test('the child rules of 6.2 give every child the faces, corners and edges of the whole refinement', () => {
  // The descent enters only the first child holding a point, so a wrong
  // edge of a later child could hide; here every child of every face is
  // compared, edge indices and directions included.
  for (const base of quadFrames) {
    for (const forward of [0, 5, 10, 15]) {
      const { counts, levels } = quadReference({ ...base, forward }, 3);
      for (let k = 0; k + 1 < levels.length; ++k) {
        const level = base.level + k;
        levels[k].faces.forEach((f, i) => {
          const children = quadChildren(quadNode(f, levels[k].edges), counts, level);
          for (let j = 0; j < 4; ++j) {
            const { at, ...want } = quadNode(levels[k + 1].faces[4 * i + j], levels[k + 1].edges);
            const { at: gotAt, ...got } = children[j];
            assert.deepEqual(got, want, `child ${j} of f${level}:${f.face}, forward ${forward}`);
            assert.deepEqual(gotAt, at);
          }
        });
      }
    }
  }
});

test('quad frames naming elements or children their level does not have are refused', () => {
  assert.throws(() => new RegionLattice({ ...quad, corners: [0, 1, 2, 4] }, 1), /corner or edge 3/);
  assert.throws(() => new RegionLattice({ ...quad, edges: [0, 1, 2, 4] }, 1), /corner or edge 3/);
  assert.throws(() => new RegionLattice({ ...quad, index: 1 }, 1), /does not exist/);
  assert.throws(() => new RegionLattice({ ...quad, forward: 16 }, 1), /edge directions 16/);
  assert.throws(() => new RegionLattice({ ...quad, firstChild: 1 }, 1), /first child 1 leaves no room/); // 1..4, F1 = C0 = 4
  assert.throws(() => new RegionLattice({ ...second, firstChild: 4 }, 1), /first child 4 leaves no room/); // 4..7, F1 = 7
  assert.throws(() => new RegionLattice({ ...second, firstChild: undefined }, 1), /first child undefined/);
  assert.throws(() => new RegionLattice({ ...quadFrames[2], firstChild: 72 }, 1), /first child 72 is not 4 x 17/);
  assert.throws(() => new RegionLattice({ ...quad, sides: 5 }, 1), /5 sides/);
  assert.throws(() => new RegionLattice(quad, 8), /depth 8/);
  // A triangle's frame keeps its three bits.
  assert.throws(() => new RegionLattice({ ...single, forward: 8 }, 1), /edge directions 8/);
});

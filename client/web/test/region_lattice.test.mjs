// Level counts and lattice ids (docs/PROTOCOL.md 3.2, 6.2): the cube's
// counts from the text, a refinement of one triangle worked by hand, and the
// descent against a port of the reference's full table
// (core/tessellation/region_lattice.cc) on every point of deeper lattices.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { LevelCounts, idName, packId } from '../src/codec/ids.js';
import { RegionLattice } from '../src/codec/region_lattice.js';

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

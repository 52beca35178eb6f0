// Lattice ids (docs/PROTOCOL.md 6.2 "Lattice ids" and "Quad lattice ids",
// core/tessellation/region_lattice.h): every vertex of a region is a point
// (u, v) of its root face's lattice `depth` levels down, n = 2^depth. A
// triangle of Loop's split has corner 0 at (0, 0), corner 1 at (n, 0) and
// corner 2 at (0, n); a quad of Catmull-Clark's quad split has its corners 0
// to 3 at (0, 0), (n, 0), (n, n) and (0, n). The point's vertex index follows
// from the frame by the refinement rules alone (3.2 for triangles, 6.2 "Quad
// lattice ids" for quads).
//
// Why a descent instead of the reference's full table: an adaptive
// tessellation shows few of a deep lattice's points, and a document of many
// base faces sends as many regions; descending from the root face to the
// level where the point first appears costs `depth` steps per vertex and
// allocates nothing per region. Both splits keep each child's corners in the
// counter-clockwise order of the root's, so one containment test serves.
import { LevelCounts } from './ids.js';

export const MAX_LATTICE_DEPTH = 7; // u and v fit a byte
const TWO_32 = 4294967296;

function cross(a, b, p) {
  return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}

// p inside or on the convex counter-clockwise polygon `at`.
function contains(at, p) {
  return at.every((a, k) => cross(a, at[(k + 1) % at.length], p) >= 0);
}

function same(a, b) {
  return a[0] === b[0] && a[1] === b[1];
}

function mid(a, b) {
  return [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
}

// The four children of triangle `node` at `level` (the table of 3.2). Child
// edge k joins child corners k and k+1, and `forward` says whether it runs
// that way.
function triangleChildren(node, counts, level) {
  const V = counts.vertices(level), E = counts.edges(level);
  const m = [], mv = [], half = [];
  for (let j = 0; j < 3; ++j) {
    m.push(mid(node.at[j], node.at[(j + 1) % 3]));
    mv.push(V + node.edge[j]);
    // half[j][0]: the half of edge j at corner j, half[j][1] at corner j+1,
    // each with whether it runs from that corner to the midpoint.
    half.push(node.forward[j]
      ? [[2 * node.edge[j], true], [2 * node.edge[j] + 1, false]]
      : [[2 * node.edge[j] + 1, false], [2 * node.edge[j], true]]);
  }
  const i0 = 2 * E + 3 * node.face, i1 = i0 + 1, i2 = i0 + 2;
  return [
    { face: 4 * node.face, at: [node.at[0], m[0], m[2]], vertex: [node.vertex[0], mv[0], mv[2]],
      edge: [half[0][0][0], i0, half[2][1][0]], forward: [half[0][0][1], true, !half[2][1][1]] },
    { face: 4 * node.face + 1, at: [m[0], node.at[1], m[1]], vertex: [mv[0], node.vertex[1], mv[1]],
      edge: [half[0][1][0], half[1][0][0], i1], forward: [!half[0][1][1], half[1][0][1], true] },
    { face: 4 * node.face + 2, at: [m[2], m[1], node.at[2]], vertex: [mv[2], mv[1], node.vertex[2]],
      edge: [i2, half[1][1][0], half[2][0][0]], forward: [true, !half[1][1][1], half[2][0][1]] },
    { face: 4 * node.face + 3, at: [m[1], m[2], m[0]], vertex: [mv[1], mv[2], mv[0]],
      edge: [i2, i0, i1], forward: [false, false, false] },
  ];
}

// The four children of quad `node` at `level` (docs/PROTOCOL.md 6.2 "Quad
// lattice ids"): child j, face c + j with c = node.first, keeps corner j at
// position j and is followed round by the vertex on edge j, the face vertex
// and the vertex on edge j-1. Its edge at position k is of kind (k - j) mod
// 4: the half of edge j at corner j, interior edge c + j, interior edge
// c + j-1, the half of edge j-1 at corner j. Edge e's halves are C + 2e at
// its first end and C + 2e + 1 at its second, each running from the edge
// vertex to that end; interior edges run from the face vertex out. Exported
// for its test against a refinement by vertex pairs.
export function quadChildren(node, counts, level) {
  const V = counts.vertices(level), F = counts.faces(level), C = counts.corners(level);
  const centre = mid(node.at[0], node.at[2]);
  return [0, 1, 2, 3].map((j) => {
    const i = (j + 3) % 4; // edge j-1, arriving at corner j
    const byKind = {
      at: [node.at[j], mid(node.at[j], node.at[(j + 1) % 4]), centre, mid(node.at[i], node.at[j])],
      vertex: [node.vertex[j], V + F + node.edge[j], V + node.face, V + F + node.edge[i]],
      edge: [C + 2 * node.edge[j] + (node.forward[j] ? 0 : 1), node.first + j,
        node.first + i, C + 2 * node.edge[i] + (node.forward[i] ? 1 : 0)],
      forward: [false, false, true, true],
    };
    const atPositions = (kinds) => [0, 1, 2, 3].map((k) => kinds[(k - j + 4) % 4]);
    return {
      face: node.first + j,
      first: 4 * (node.first + j),
      at: atPositions(byKind.at),
      vertex: atPositions(byKind.vertex),
      edge: atPositions(byKind.edge),
      forward: atPositions(byKind.forward),
    };
  });
}

export class RegionLattice {
  // frame: {sides, level, index, firstChild (quads), corners, edges, forward,
  // baseCounts} (region_header.js; sides 3 when absent); depth: the
  // profile's max level - frame.level.
  constructor(frame, depth) {
    const face = `f${frame.level}:${frame.index}`;
    const sides = frame.sides ?? 3;
    if (sides !== 3 && sides !== 4) throw new RangeError(`region lattice of ${face}: ${sides} sides`);
    if (!(depth >= 0 && depth <= MAX_LATTICE_DEPTH) || frame.level + depth > 63) {
      throw new RangeError(`region lattice of ${face}: depth ${depth} outside [0, ${MAX_LATTICE_DEPTH}]`);
    }
    this.frame = frame;
    this.sides = sides;
    this.depth = depth;
    this.side = 1 << depth;
    this.rootLevel = frame.level;
    const [V0, E0, F0, C0] = frame.baseCounts;
    this.counts = sides === 4
      ? LevelCounts.quads(V0, E0, F0, C0, frame.level + depth)
      : new LevelCounts(V0, E0, F0, frame.level + depth);
    const r = frame.level;
    for (let j = 0; j < sides; ++j) {
      if (frame.corners[j] >= this.counts.vertices(r) || frame.edges[j] >= this.counts.edges(r)) {
        throw new RangeError(`region lattice of ${face}: corner or edge ${j} is not an element of level ${r}`);
      }
    }
    if (frame.index >= this.counts.faces(r)) throw new RangeError(`region lattice: face ${face} does not exist`);
    if (frame.forward >> sides) {
      throw new RangeError(`region lattice of ${face}: edge directions ${frame.forward} beyond ${sides} edges`);
    }
    if (sides === 4) {
      // A quad's children c..c+3 are faces of level r+1, which has one face
      // per corner of level r; below the base level, where every face is a
      // quad, they are 4f..4f+3.
      const c = frame.firstChild, faces = this.counts.corners(r);
      if (!(Number.isSafeInteger(c) && c + 4 <= faces)) {
        throw new RangeError(`region lattice of ${face}: first child ${c} leaves no room for 4 children ` +
          `among level ${r + 1}'s ${faces} faces`);
      }
      if (r > 0 && c !== 4 * frame.index) {
        throw new RangeError(`region lattice of ${face}: first child ${c} is not 4 x ${frame.index}`);
      }
    }
  }

  // The vertex index of lattice point (u, v); throws outside the face.
  indexAt(u, v) {
    const n = this.side;
    const quad = this.sides === 4;
    if (!(u >= 0 && v >= 0 && (quad ? u <= n && v <= n : u + v <= n))) {
      throw new RangeError(`lattice point (${u}, ${v}) outside the root face's lattice of side ${n}`);
    }
    const p = [u, v];
    const f = this.frame;
    let node = {
      face: f.index,
      first: f.firstChild,
      at: quad ? [[0, 0], [n, 0], [n, n], [0, n]] : [[0, 0], [n, 0], [0, n]],
      vertex: f.corners.slice(),
      edge: f.edges.slice(),
      forward: f.corners.map((_, j) => (f.forward & (1 << j)) !== 0),
    };
    // Every point of the lattice is a corner of the face that holds it at
    // the level where it appears.
    for (let level = this.rootLevel; ; ++level) {
      for (let j = 0; j < this.sides; ++j) if (same(node.at[j], p)) return node.vertex[j];
      if (level >= this.rootLevel + this.depth) break;
      const children = quad ? quadChildren(node, this.counts, level) : triangleChildren(node, this.counts, level);
      node = children.find((c) => contains(c.at, p));
    }
    throw new RangeError(`lattice point (${u}, ${v}) is not a vertex of the lattice of side ${n}`);
  }

  // The packed id at the vertex's birth level, as [hi, lo] uint32 halves:
  // level in the top 6 bits of hi.
  idHalvesAt(u, v) {
    const index = this.indexAt(u, v);
    const birth = this.counts.birthLevel(index);
    return [(Math.floor(index / TWO_32) + birth * 2 ** 26) >>> 0, index % TWO_32];
  }

  // The same as a BigInt.
  idAt(u, v) {
    const [hi, lo] = this.idHalvesAt(u, v);
    return (BigInt(hi) << 32n) | BigInt(lo);
  }
}

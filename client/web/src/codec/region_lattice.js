// Lattice ids (docs/PROTOCOL.md 6.2 "Lattice ids", core/tessellation/
// region_lattice.h): every vertex of a region is a point (u, v) of its root
// face's triangular lattice `depth` levels down, corner 0 at (0, 0), corner 1
// at (n, 0), corner 2 at (0, n), n = 2^depth. The point's vertex index
// follows from the frame by the refinement rules of 3.2 alone.
//
// Why a descent instead of the reference's full table: an adaptive
// tessellation shows few of a deep lattice's points, and a document of many
// base faces sends as many regions; descending from the root face to the
// level where the point first appears costs `depth` steps per vertex and
// allocates nothing per region.
import { LevelCounts } from './ids.js';

export const MAX_LATTICE_DEPTH = 7; // u and v fit a byte
const TWO_32 = 4294967296;

function cross(a, b, p) {
  return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}

// p inside or on the counter-clockwise triangle (a, b, c).
function contains(at, p) {
  return cross(at[0], at[1], p) >= 0 && cross(at[1], at[2], p) >= 0 && cross(at[2], at[0], p) >= 0;
}

function same(a, b) {
  return a[0] === b[0] && a[1] === b[1];
}

export class RegionLattice {
  // frame: {level, index, corners[3], edges[3], forward, baseCounts[3]}
  // (region_header.js); depth: the profile's max level - frame.level.
  constructor(frame, depth) {
    const face = `f${frame.level}:${frame.index}`;
    if (!(depth >= 0 && depth <= MAX_LATTICE_DEPTH) || frame.level + depth > 63) {
      throw new RangeError(`region lattice of ${face}: depth ${depth} outside [0, ${MAX_LATTICE_DEPTH}]`);
    }
    this.frame = frame;
    this.depth = depth;
    this.side = 1 << depth;
    this.rootLevel = frame.level;
    this.counts = new LevelCounts(frame.baseCounts[0], frame.baseCounts[1], frame.baseCounts[2], frame.level + depth);
    const r = frame.level;
    for (let j = 0; j < 3; ++j) {
      if (frame.corners[j] >= this.counts.vertices(r) || frame.edges[j] >= this.counts.edges(r)) {
        throw new RangeError(`region lattice of ${face}: corner or edge ${j} is not an element of level ${r}`);
      }
    }
    if (frame.index >= this.counts.faces(r)) throw new RangeError(`region lattice: face ${face} does not exist`);
  }

  // The vertex index of lattice point (u, v); throws outside the triangle.
  indexAt(u, v) {
    const n = this.side;
    if (!(u >= 0 && v >= 0 && u + v <= n)) {
      throw new RangeError(`lattice point (${u}, ${v}) outside the root face's lattice of side ${n}`);
    }
    const p = [u, v];
    const f = this.frame;
    let node = {
      face: f.index,
      at: [[0, 0], [n, 0], [0, n]],
      vertex: f.corners.slice(),
      edge: f.edges.slice(),
      forward: [(f.forward & 1) !== 0, (f.forward & 2) !== 0, (f.forward & 4) !== 0],
    };
    for (let level = this.rootLevel; ; ++level) {
      for (let j = 0; j < 3; ++j) if (same(node.at[j], p)) return node.vertex[j];
      if (level >= this.rootLevel + this.depth) break;
      const V = this.counts.vertices(level), E = this.counts.edges(level);
      const m = [], mv = [], half = [];
      for (let j = 0; j < 3; ++j) {
        const a = node.at[j], b = node.at[(j + 1) % 3];
        m.push([(a[0] + b[0]) / 2, (a[1] + b[1]) / 2]);
        mv.push(V + node.edge[j]);
        if (same(m[j], p)) return mv[j];
        // half[j][0]: the half of edge j at corner j, half[j][1] at corner
        // j+1, each with whether it runs from that corner to the midpoint.
        half.push(node.forward[j]
          ? [[2 * node.edge[j], true], [2 * node.edge[j] + 1, false]]
          : [[2 * node.edge[j] + 1, false], [2 * node.edge[j], true]]);
      }
      const i0 = 2 * E + 3 * node.face, i1 = i0 + 1, i2 = i0 + 2;
      // The children of 3.2's table; child edge k joins child corners k and
      // k+1, and `forward` says whether it runs that way.
      const children = [
        { face: 4 * node.face, at: [node.at[0], m[0], m[2]], vertex: [node.vertex[0], mv[0], mv[2]],
          edge: [half[0][0][0], i0, half[2][1][0]], forward: [half[0][0][1], true, !half[2][1][1]] },
        { face: 4 * node.face + 1, at: [m[0], node.at[1], m[1]], vertex: [mv[0], node.vertex[1], mv[1]],
          edge: [half[0][1][0], half[1][0][0], i1], forward: [!half[0][1][1], half[1][0][1], true] },
        { face: 4 * node.face + 2, at: [m[2], m[1], node.at[2]], vertex: [mv[2], mv[1], node.vertex[2]],
          edge: [i2, half[1][1][0], half[2][0][0]], forward: [true, !half[1][1][1], half[2][0][1]] },
        { face: 4 * node.face + 3, at: [m[1], m[2], m[0]], vertex: [mv[1], mv[2], mv[0]],
          edge: [i2, i0, i1], forward: [false, false, false] },
      ];
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

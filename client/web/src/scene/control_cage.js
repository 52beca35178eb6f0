// The control cage as lines (docs/WEB_VIEWER.md "The control cage"): a Cage
// reply's polygons turned into the unique undirected edges between packed
// vertex ids, and the segments drawn for them between the control points the
// page shows. A corner of the reply is a vertex index at the cage's level,
// so its id is (level, index): the id the page's dots of that level carry
// (docs/PROTOCOL.md 6.2, "The level of a decoded id"). No three.js here, so
// that node tests run it.
import { INDEX_MASK, MAX_ID_LEVEL, packId } from '../codec/ids.js';
import { toBig } from '../codec/uint64.js';

// A Cage reply's fields ({level, face_sizes, vertices}; the uint64s as the
// wire's Longs, BigInts, numbers or decimal strings) as
//   {level, faces, faceSizes: {"4": 6, ...}, corners, starts, edges, edgeFaces}
// corners: every face's corners as packed ids (BigInt), face after face;
// face k's are corners[starts[k]] up to corners[starts[k + 1]].
// edges: [[a, b], ...], two packed ids with a < b, each edge once however
// many faces share it, in the order the faces first name it; edgeFaces[i]:
// the faces that have edge i. Throws a RangeError on a reply that does not
// describe polygons.
export function cageEdges(cage) {
  const level = Number(cage.level ?? 0);
  if (!Number.isInteger(level) || level < 0 || level > MAX_ID_LEVEL) throw new RangeError(`cage level ${cage.level} is not a level`);
  const sizes = (cage.face_sizes ?? []).map(Number);
  const total = sizes.reduce((n, s) => n + s, 0);
  if (total !== (cage.vertices ?? []).length) {
    throw new RangeError(`the cage's ${sizes.length} faces have ${total} corners, but it names ${(cage.vertices ?? []).length} vertices`);
  }
  const corners = cage.vertices.map((corner) => {
    const index = toBig(corner);
    if (index < 0n || index > INDEX_MASK) throw new RangeError(`cage vertex index ${index} does not fit in a vertex id`);
    return packId(level, index);
  });
  const faceSizes = {};
  const starts = [0];
  const edgeOf = new Map(); // "a b" -> its position in edges
  const edges = [];
  const edgeFaces = [];
  sizes.forEach((size, face) => {
    if (!Number.isInteger(size) || size < 3) throw new RangeError(`cage face ${face} has ${size} corners`);
    faceSizes[size] = (faceSizes[size] ?? 0) + 1;
    const first = starts[face];
    for (let c = 0; c < size; ++c) {
      const a = corners[first + c], b = corners[first + ((c + 1) % size)];
      if (a === b) continue; // a repeated corner spans no edge
      const edge = a < b ? [a, b] : [b, a];
      const key = `${edge[0]} ${edge[1]}`;
      let at = edgeOf.get(key);
      if (at === undefined) {
        at = edges.length;
        edgeOf.set(key, at);
        edges.push(edge);
        edgeFaces.push([]);
      }
      if (!edgeFaces[at].includes(face)) edgeFaces[at].push(face);
    }
    starts.push(first + size);
  });
  return { level, faces: sizes.length, faceSizes, corners, starts, edges, edgeFaces };
}

// Which faces of `cage` (cageEdges' result) face an eye at `eye` ([x, y, z]):
// a face does when the polygon of its corners that lookup(id) finds
// ({position}), at least three, turns its front to the eye. The front is the
// counter-clockwise side (the Cage reply's order) by Newell's normal, which
// takes a quad that is not flat. Returns a Uint8Array, 1 for such a face.
export function facesTowards(cage, lookup, eye) {
  const front = new Uint8Array(cage.faces);
  for (let f = 0; f < cage.faces; ++f) {
    const points = [];
    for (let c = cage.starts[f]; c < cage.starts[f + 1]; ++c) {
      const v = lookup(cage.corners[c]);
      if (v) points.push(v.position);
    }
    if (points.length < 3) continue;
    let nx = 0, ny = 0, nz = 0, cx = 0, cy = 0, cz = 0;
    for (let i = 0; i < points.length; ++i) {
      const [x0, y0, z0] = points[i], [x1, y1, z1] = points[(i + 1) % points.length];
      nx += (y0 - y1) * (z0 + z1);
      ny += (z0 - z1) * (x0 + x1);
      nz += (x0 - x1) * (y0 + y1);
      cx += x0, cy += y0, cz += z0;
    }
    const k = points.length;
    if ((eye[0] - cx / k) * nx + (eye[1] - cy / k) * ny + (eye[2] - cz / k) * nz > 0) front[f] = 1;
  }
  return front;
}

// The segments to draw for `cage` (cageEdges' result): an edge is drawn when
// lookup(id) finds both of its ends ({position}: the page's control points)
// and, given an eye, one of its faces faces it (facesTowards): on a closed
// convex surface, the edges one sees. Writes x, y, z of both ends, segment
// after segment, into `out` (at least 6 floats per edge) and returns
// {positions: out, segments}: the first 6 * segments floats are used.
export function cageSegments(cage, lookup, eye = null, out = new Float32Array(6 * cage.edges.length)) {
  const front = eye ? facesTowards(cage, lookup, eye) : null;
  let segments = 0;
  cage.edges.forEach(([a, b], i) => {
    if (front && !cage.edgeFaces[i].some((f) => front[f])) return;
    const va = lookup(a);
    if (!va) return;
    const vb = lookup(b);
    if (!vb) return;
    out.set(va.position, 6 * segments);
    out.set(vb.position, 6 * segments + 3);
    ++segments;
  });
  return { positions: out, segments };
}

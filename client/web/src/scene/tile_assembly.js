// Closing the cracks between tiles shown at different levels, as
// core/view/tile_assembly.h does for the C++ viewers (docs/VIEWS.md
// "Assembling tiles"; Pulli & Lounsbery, "Hierarchical Editing and
// Rendering of Subdivision Surfaces" §3.2.2): along each boundary of a tile,
// a run of vertices no other shown tile has, between two that another tile
// has and joins by an edge, is put on that edge at its dyadic places.
// Vertices are matched across tiles by id (the same id is the same limit
// point in every tile).
//
// The surface's preview (docs/VIEWS.md "The first picture") is no tile: while it
// is held the page draws it alone, and it never takes part in crack
// closing.

// The preview's region id: the cluster form (bit 63) at level 31, index 0.
export const PREVIEW_ID = (1n << 63n) | (31n << 58n);

export function isPreview(regionId) {
  return BigInt(regionId) === PREVIEW_ID;
}

// What a view's page draws out of the regions it holds: the preview alone
// while it is held (the tiles keep arriving and are kept meanwhile), the
// tiles once the server has removed it.
export function shownTiles(regions) {
  const preview = regions.get(PREVIEW_ID);
  return preview ? new Map([[PREVIEW_ID, preview]]) : regions;
}

function idOf(region, v) {
  return `${region.idHi[v]}:${region.idLo[v]}`;
}

function edgeKey(a, b) {
  return a < b ? `${a}|${b}` : `${b}|${a}`;
}

// A tile's boundary, summarised once per decoded region object (a changed
// tile arrives as a new one), as core/view/tile_assembly.h's TileBoundary:
// only boundaries take part in closing cracks (an edge two tiles share is
// on both, and so is a vertex both have), so a delta costs the boundaries
// of the tiles shown, not their triangles.
//   next:     boundary edges (used by one triangle; crease sides split a
//             vertex into copies with one id) as a graph over ids;
//   chords:   the tile's edges, boundary or not, between boundary vertices;
//   position: a boundary vertex's position; copies: its vertex indices.
const boundaries = new WeakMap();

function boundaryOf(region) {
  const known = boundaries.get(region);
  if (known) return known;
  const count = region.positions.length / 3;
  const vid = new Array(count);
  for (let v = 0; v < count; ++v) vid[v] = idOf(region, v);
  const uses = new Map(); // edge key -> triangles using it
  const ends = new Map(); // edge key -> its two ids
  const ix = region.indices;
  for (let t = 0; t < ix.length; t += 3) {
    for (let k = 0; k < 3; ++k) {
      const a = vid[ix[t + k]], b = vid[ix[t + ((k + 1) % 3)]];
      const key = edgeKey(a, b);
      const n = uses.get(key);
      uses.set(key, (n ?? 0) + 1);
      if (n === undefined) ends.set(key, [a, b]);
    }
  }
  const next = new Map();
  for (const [key, n] of uses) {
    if (n !== 1) continue;
    const [a, b] = ends.get(key);
    if (!next.has(a)) next.set(a, []);
    if (!next.has(b)) next.set(b, []);
    next.get(a).push(b);
    next.get(b).push(a);
  }
  const chords = new Set();
  for (const [key, [a, b]] of ends) if (next.has(a) && next.has(b)) chords.add(key);
  const position = new Map(), copies = new Map();
  for (let v = 0; v < count; ++v) {
    if (!next.has(vid[v])) continue;
    if (!position.has(vid[v])) {
      position.set(vid[v], [region.positions[3 * v], region.positions[3 * v + 1], region.positions[3 * v + 2]]);
      copies.set(vid[v], []);
    }
    copies.get(vid[v]).push(v);
  }
  const summary = { next, chords, position, copies };
  boundaries.set(region, summary);
  return summary;
}

// regions: Map id -> decoded region (positions, indices, idHi, idLo).
// Returns Map id -> positions (a new Float32Array for the tiles with moved
// vertices, the region's own array otherwise; the preview's own, always)
// and the count moved. The cracks are closed over the tiles only: the
// preview covers the whole surface with level-0 vertex ids, and taken for a
// tile its simplified edges would pull the tiles' vertices onto them.
export function closeCracks(regions) {
  const ids = [...regions.keys()].filter((id) => !isPreview(id));
  const summaries = new Map();
  const owners = new Map(); // boundary vertex id -> tile ids having it
  for (const id of ids) {
    const r = regions.get(id);
    if (!r.idHi) continue; // no vertex ids: nothing to match
    const b = boundaryOf(r);
    summaries.set(id, b);
    for (const vid of b.next.keys()) {
      let list = owners.get(vid);
      if (!list) owners.set(vid, (list = []));
      list.push(id);
    }
  }
  const shared = (vid) => (owners.get(vid)?.length ?? 0) > 1;
  const out = new Map();
  if (regions.has(PREVIEW_ID)) out.set(PREVIEW_ID, regions.get(PREVIEW_ID).positions);
  let moved = 0;
  for (const id of ids) {
    const r = regions.get(id);
    out.set(id, r.positions);
    const b = summaries.get(id);
    if (!b) continue;
    const { next } = b;
    const target = new Map();
    for (const [start, around] of next) {
      if (!shared(start)) continue;
      for (const first of around) {
        if (shared(first)) continue;
        const run = [start];
        let prev = start, at = first;
        while (!shared(at) && next.get(at).length === 2 && run.length < 1 << 20) {
          run.push(at);
          const n = next.get(at);
          const after = n[0] === prev ? n[1] : n[0];
          prev = at;
          at = after;
        }
        if (!shared(at)) continue;
        run.push(at);
        const a = run[0], z = run[run.length - 1];
        if (a > z) continue; // each run once, from its lower end
        // A tile shows one level: if it has the edge a-z itself, the run
        // went the other way round it, not along a finer copy of a-z.
        if (b.chords.has(edgeKey(a, z))) continue;
        let coarser = false;
        for (const j of owners.get(a)) {
          if (j === id || !owners.get(z).includes(j)) continue;
          if (summaries.get(j).chords.has(edgeKey(a, z))) coarser = true;
        }
        if (!coarser) continue;
        const pa = b.position.get(a), pb = b.position.get(z);
        const segments = run.length - 1;
        for (let k = 1; k + 1 < run.length; ++k) {
          const t = k / segments;
          target.set(run[k], [0, 1, 2].map((c) => (1 - t) * pa[c] + t * pb[c]));
        }
      }
    }
    if (target.size === 0) continue;
    const closed = Float32Array.from(r.positions);
    for (const [vid, p] of target) {
      for (const v of b.copies.get(vid)) {
        closed.set(p, 3 * v);
        ++moved;
      }
    }
    out.set(id, closed);
  }
  return { positions: out, moved };
}

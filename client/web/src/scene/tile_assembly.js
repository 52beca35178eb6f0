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

// Edge key -> how many triangles use it (crease sides split a vertex into
// copies with one id).
function edgesOf(region) {
  const out = new Map();
  const ix = region.indices;
  for (let t = 0; t < ix.length; t += 3) {
    for (let k = 0; k < 3; ++k) {
      const key = edgeKey(idOf(region, ix[t + k]), idOf(region, ix[t + ((k + 1) % 3)]));
      out.set(key, (out.get(key) ?? 0) + 1);
    }
  }
  return out;
}

// regions: Map id -> decoded region (positions, indices, idHi, idLo).
// Returns Map id -> positions (a new Float32Array for the tiles with moved
// vertices, the region's own array otherwise; the preview's own, always)
// and the count moved. The cracks are closed over the tiles only: the
// preview covers the whole surface with level-0 vertex ids, and taken for a
// tile its simplified edges would pull the tiles' vertices onto them.
export function closeCracks(regions) {
  const ids = [...regions.keys()].filter((id) => !isPreview(id));
  const edges = new Map();
  const owners = new Map(); // vertex id -> tile ids having it
  for (const id of ids) {
    const r = regions.get(id);
    if (!r.idHi) continue; // no vertex ids: nothing to match
    edges.set(id, edgesOf(r));
    const seen = new Set();
    for (let v = 0; v < r.positions.length / 3; ++v) {
      const vid = idOf(r, v);
      if (seen.has(vid)) continue;
      seen.add(vid);
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
    if (!r.idHi) continue;
    const next = new Map(); // boundary graph over ids
    for (const [key, uses] of edges.get(id)) {
      if (uses !== 1) continue;
      const [a, b] = key.split('|');
      if (!next.has(a)) next.set(a, []);
      if (!next.has(b)) next.set(b, []);
      next.get(a).push(b);
      next.get(b).push(a);
    }
    const position = new Map();
    for (let v = 0; v < r.positions.length / 3; ++v) {
      position.set(idOf(r, v), [r.positions[3 * v], r.positions[3 * v + 1], r.positions[3 * v + 2]]);
    }
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
        const a = run[0], b = run[run.length - 1];
        if (a > b) continue; // each run once, from its lower end
        // A tile shows one level: if it has the edge a-b itself, the run
        // went the other way round it, not along a finer copy of a-b.
        if (edges.get(id).has(edgeKey(a, b))) continue;
        let coarser = false;
        for (const j of owners.get(a)) {
          if (j === id || !owners.get(b).includes(j)) continue;
          if (edges.get(j).has(edgeKey(a, b))) coarser = true;
        }
        if (!coarser) continue;
        const pa = position.get(a), pb = position.get(b);
        const segments = run.length - 1;
        for (let k = 1; k + 1 < run.length; ++k) {
          const t = k / segments;
          target.set(run[k], [0, 1, 2].map((c) => (1 - t) * pa[c] + t * pb[c]));
        }
      }
    }
    if (target.size === 0) continue;
    const closed = Float32Array.from(r.positions);
    for (let v = 0; v < r.positions.length / 3; ++v) {
      const p = target.get(idOf(r, v));
      if (!p) continue;
      closed.set(p, 3 * v);
      ++moved;
    }
    out.set(id, closed);
  }
  return { positions: out, moved };
}

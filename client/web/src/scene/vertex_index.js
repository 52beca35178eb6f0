// Where each displayed control vertex is: every region vertex carries the id
// of the control vertex whose limit it is, at its birth level
// (docs/PROTOCOL.md 6.2), and the same index names the vertex at every finer
// level (3.2). So the control vertices of level L are the displayed vertices
// born at a level <= L; their limit positions and normals are looked up here
// by index, whatever level an id names (a collaborator's selection, a test's
// "v2:123", this viewer's pick).
//
// Kept up to date per region, like the GPU buffers (scene.js): a delta costs
// the vertices of the regions it changes or removes, not of the document.
// A vertex on a region border (or on both sides of a crease) is held by
// several regions at the same limit position; it stays while any holds it.
const TWO_32 = 4294967296;

export class VertexIndex {
  constructor() {
    this.byIndex = new Map(); // vertex index (number) -> {index, birth, position, normal, holders}
    this.held = new Map(); // region id -> the vertex indices it holds
    this.levels = new Map(); // level -> the control vertices of that level (lazy)
  }

  // A change from DocumentView.apply; `regions` is the view's region map
  // after it.
  apply(change, regions) {
    if (change.kind === 'snapshot') {
      this.byIndex.clear();
      this.held.clear();
      for (const [id, region] of regions) this.add(id, region);
    } else if (change.kind === 'delta') {
      for (const id of change.removed) this.drop(id);
      for (const id of change.changed) {
        this.drop(id);
        if (regions.has(id)) this.add(id, regions.get(id));
      }
    } else {
      return;
    }
    this.levels.clear();
  }

  add(id, r) {
    if (!r.idHi) return; // a region without ids names no control vertex
    const indices = new Array(r.idHi.length);
    for (let p = 0; p < r.idHi.length; ++p) {
      const index = (r.idHi[p] & 0x03ffffff) * TWO_32 + r.idLo[p];
      indices[p] = index;
      const position = [r.positions[3 * p], r.positions[3 * p + 1], r.positions[3 * p + 2]];
      const normal = [r.normals[3 * p], r.normals[3 * p + 1], r.normals[3 * p + 2]];
      const known = this.byIndex.get(index);
      if (known) {
        // The newest region has the newest limit position (an edit's delta
        // carries every region that holds a vertex it moved).
        known.position = position;
        known.normal = normal;
        ++known.holders;
      } else {
        this.byIndex.set(index, { index, birth: r.idHi[p] >>> 26, position, normal, holders: 1 });
      }
    }
    this.held.set(id, indices);
  }

  drop(id) {
    const indices = this.held.get(id);
    if (!indices) return;
    for (const index of indices) {
      const v = this.byIndex.get(index);
      if (v && --v.holders === 0) this.byIndex.delete(index);
    }
    this.held.delete(id);
  }

  // The vertex an id (BigInt, any level) names, or null when not displayed.
  lookup(id) {
    const index = Number(BigInt(id) & ((1n << 58n) - 1n));
    return this.byIndex.get(index) ?? null;
  }

  // The displayed control vertices of `level` (born at or above it).
  atLevel(level) {
    if (!this.levels.has(level)) {
      const out = [];
      for (const v of this.byIndex.values()) if (v.birth <= level) out.push(v);
      this.levels.set(level, out);
    }
    return this.levels.get(level);
  }
}

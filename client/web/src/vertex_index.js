// Where each displayed control vertex is: every region vertex carries the id
// of the control vertex whose limit it is, at its birth level
// (docs/PROTOCOL.md 6.2), and the same index names the vertex at every finer
// level (3.2). So the control vertices of level L are the displayed vertices
// born at a level <= L; their limit positions and normals are looked up here
// by index, whatever level an id names (a collaborator's selection, a test's
// "v2:123", this viewer's pick). Rebuilt lazily after each change.
const TWO_32 = 4294967296;

export class VertexIndex {
  constructor() {
    this.regions = null;
    this.byIndex = null; // vertex index (number) -> {birth, position, normal}
    this.levels = new Map(); // level -> the control vertices of that level
  }

  // regions: Map of decoded regions (document_view.js); call on every change.
  invalidate(regions) {
    this.regions = regions;
    this.byIndex = null;
    this.levels.clear();
  }

  build() {
    if (this.byIndex) return this.byIndex;
    this.byIndex = new Map();
    if (!this.regions) return this.byIndex;
    for (const r of this.regions.values()) {
      if (!r.idHi) continue;
      for (let p = 0; p < r.idHi.length; ++p) {
        const index = (r.idHi[p] & 0x03ffffff) * TWO_32 + r.idLo[p];
        if (this.byIndex.has(index)) continue; // a crease's sides share the position
        this.byIndex.set(index, {
          index,
          birth: r.idHi[p] >>> 26,
          position: [r.positions[3 * p], r.positions[3 * p + 1], r.positions[3 * p + 2]],
          normal: [r.normals[3 * p], r.normals[3 * p + 1], r.normals[3 * p + 2]],
        });
      }
    }
    return this.byIndex;
  }

  // The vertex an id (BigInt, any level) names, or null when not displayed.
  lookup(id) {
    const index = Number(BigInt(id) & ((1n << 58n) - 1n));
    return this.build().get(index) ?? null;
  }

  // The displayed control vertices of `level` (born at or above it).
  atLevel(level) {
    if (!this.levels.has(level)) {
      const out = [];
      for (const v of this.build().values()) if (v.birth <= level) out.push(v);
      this.levels.set(level, out);
    }
    return this.levels.get(level);
  }
}

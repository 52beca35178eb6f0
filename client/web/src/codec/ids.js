// Element ids (docs/PROTOCOL.md 3.1, 3.2): packed = (level << 58) | index,
// written "v3:1234" for people, and the counts of the uniform refinement,
// which give a vertex index its birth level (the coarsest level at which the
// index exists). Indices are plain numbers: a level's counts stay below 2^53
// for any mesh this server accepts (a million base faces at level 12 have
// 1.7e13 faces), and LevelCounts refuses counts that do not.
export const LEVEL_SHIFT = 58n;
export const INDEX_MASK = (1n << 58n) - 1n;
export const MAX_ID_LEVEL = 63;

export function packId(level, index) {
  return (BigInt(level) << LEVEL_SHIFT) | BigInt(index);
}

export function idLevel(packed) {
  return Number(BigInt(packed) >> LEVEL_SHIFT);
}

export function idIndex(packed) {
  return BigInt(packed) & INDEX_MASK;
}

// "v3:1234" (or "e2:55", "f4:1023" with another prefix).
export function idName(packed, prefix = 'v') {
  return `${prefix}${idLevel(packed)}:${idIndex(packed)}`;
}

// "v3:1234" back to the packed BigInt; null when the text is not such a name.
export function parseIdName(text, prefix = 'v') {
  const match = new RegExp(`^${prefix}(\\d{1,2}):(\\d+)$`).exec(String(text).trim());
  if (!match) return null;
  const level = Number(match[1]);
  const index = BigInt(match[2]);
  if (level > MAX_ID_LEVEL || index > INDEX_MASK) return null;
  return packId(level, index);
}

// The packed id of the same vertex at another level (birth level <= level):
// the index is kept, the level bits replaced (3.2, "vertices keep their index").
export function atLevel(packed, level) {
  return packId(level, idIndex(packed));
}

// V_l, E_l, F_l and C_l (corners: the sum of the face sizes) for levels
// 0..deepest. Loop's triangle split: V' = V + E, E' = 2E + 3F, F' = 4F,
// C = 3F. The quad split of Catmull-Clark (LevelCounts.quads; docs/
// ARCHITECTURE.md "The quad split"): V' = V + F + E (a vertex per face, then
// one per edge), E' = C + 2E (an interior edge per corner, then two halves
// per edge), F' = C (a child per corner), and C = 4F below the base level,
// where every face is a quad; C0 comes with the base counts, since base faces
// may have any number of corners.
export class LevelCounts {
  // Triangles. `corners` is for LevelCounts.quads alone.
  constructor(vertices, edges, faces, deepest, corners = null) {
    this.quads = corners !== null;
    this.v = [vertices];
    this.e = [edges];
    this.f = [faces];
    this.c = [this.quads ? corners : 3 * faces];
    for (let l = 0; l < deepest; ++l) {
      const V = this.v[l], E = this.e[l], F = this.f[l], C = this.c[l];
      this.v.push(this.quads ? V + F + E : V + E);
      this.e.push(this.quads ? C + 2 * E : 2 * E + 3 * F);
      this.f.push(this.quads ? C : 4 * F);
      this.c.push((this.quads ? 4 : 3) * this.f[l + 1]);
    }
    for (let l = 0; l <= deepest; ++l) {
      if (![this.v[l], this.e[l], this.f[l], this.c[l]].every(Number.isSafeInteger)) {
        const base = this.quads ? `${vertices}, ${edges}, ${faces}, ${corners}` : `${vertices}, ${edges}, ${faces}`;
        throw new RangeError(`level counts from (${base}) exceed 2^53 at level ${l}`);
      }
    }
  }

  // Polygons split into quads: V0, E0, F0 and C0 of the base mesh.
  static quads(vertices, edges, faces, corners, deepest) {
    return new LevelCounts(vertices, edges, faces, deepest, corners);
  }

  get deepest() {
    return this.v.length - 1;
  }

  vertices(level) {
    return this.v[level];
  }

  edges(level) {
    return this.e[level];
  }

  faces(level) {
    return this.f[level];
  }

  corners(level) {
    return this.c[level];
  }

  // The smallest level l with index < V_l; -1 when not even the deepest
  // level has it.
  birthLevel(index) {
    for (let l = 0; l < this.v.length; ++l) if (index < this.v[l]) return l;
    return -1;
  }
}

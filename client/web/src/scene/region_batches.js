// The regions on screen, as GPU buffers (one BufferGeometry each). While a
// document shows at most SEPARATE_REGIONS regions, each region has a buffer
// of its own, so a delta replaces exactly the buffers of the regions it
// changed (docs/WEB_VIEWER.md, "What the page does"). A document of many
// small regions (fandisk: 12,946 of about four triangles each) would cost a
// draw call per region, more than the triangles themselves; there regions
// share buffers of up to BATCH_VERTICES vertices, and a region that a delta
// replaces or removes marks its shared buffer, rebuilt (copied together
// again) once before the next frame. Each vertex also carries its region's
// colour, for the region-colour toggle.
import * as THREE from 'three';
import { isPreview } from './tile_assembly.js';

const BATCH_VERTICES = 65536;
const SEPARATE_REGIONS = 2048;

// A region's own colour, the same in every viewer: hues spread by the golden
// ratio over the region id.
export function regionColour(regionId) {
  const hue = Number(BigInt.asUintN(32, BigInt(regionId) * 2654435761n)) / 2 ** 32;
  return new THREE.Color().setHSL(hue, 0.5, 0.6);
}

// A view's tiles (PROTOCOL.md section 16): one colour per level, cool to
// warm. A cluster's id has bit 63 set and its level in bits 58..62; a
// one-face tile's id is its face's, of level L - 5. The surface's preview
// (level bits 31) is the level-0 surface simplified: level 0.
const LEVEL_HUES = [0.63, 0.56, 0.47, 0.33, 0.18, 0.11, 0.05, 0.0, 0.88];
export function tileLevel(regionId) {
  if (isPreview(regionId)) return 0;
  const id = BigInt(regionId);
  return Number(id >> 63n ? (id >> 58n) & 31n : ((id >> 58n) & 63n) + 5n);
}
export function levelColour(regionId) {
  return new THREE.Color().setHSL(LEVEL_HUES[Math.min(tileLevel(regionId), LEVEL_HUES.length - 1)], 0.6, 0.55);
}

export class RegionBatches {
  // onBatch(batch) / onDrop(batch): the scene adds or removes its meshes.
  // colourOf(id): a region's colour (regionColour, or levelColour for tiles).
  constructor(onBatch, onDrop, colourOf = regionColour) {
    this.onBatch = onBatch;
    this.onDrop = onDrop;
    this.colourOf = colourOf;
    this.batches = [];
    this.where = new Map(); // region id -> batch
    this.triangles = 0;
    this.separate = true;
  }

  // How many regions the document shows (a snapshot's count): decides
  // between a buffer per region and shared buffers for what is set next.
  expectRegions(count) {
    this.separate = count <= SEPARATE_REGIONS;
  }

  set(regionId, region) {
    this.remove(regionId);
    const vertices = region.positions.length / 3;
    let batch = this.separate ? null : this.batches.find((b) => b.shared && b.vertices + vertices <= BATCH_VERTICES);
    if (!batch) {
      batch = { regions: new Map(), vertices: 0, dirty: true, geometry: null, shared: !this.separate };
      this.batches.push(batch);
    }
    batch.regions.set(regionId, region);
    batch.vertices += vertices;
    batch.dirty = true;
    this.where.set(regionId, batch);
    this.triangles += region.indices.length / 3;
  }

  remove(regionId) {
    const batch = this.where.get(regionId);
    if (!batch) return;
    const region = batch.regions.get(regionId);
    batch.regions.delete(regionId);
    batch.vertices -= region.positions.length / 3;
    batch.dirty = true;
    this.where.delete(regionId);
    this.triangles -= region.indices.length / 3;
  }

  has(regionId) {
    return this.where.has(regionId);
  }

  ids() {
    return [...this.where.keys()];
  }

  // Rebuilds the marked batches; drops the empty ones.
  flush() {
    for (const batch of this.batches.filter((b) => b.dirty)) {
      batch.dirty = false;
      if (batch.geometry) {
        this.onDrop(batch);
        batch.geometry.dispose();
        batch.geometry = null;
      }
      if (batch.regions.size === 0) continue;
      batch.geometry = build(batch, this.colourOf);
      this.onBatch(batch);
    }
    this.batches = this.batches.filter((b) => b.regions.size > 0);
  }
}

function build(batch, colourOf) {
  const positions = new Float32Array(batch.vertices * 3);
  const normals = new Float32Array(batch.vertices * 3);
  const colours = new Float32Array(batch.vertices * 3);
  let triangles = 0;
  for (const r of batch.regions.values()) triangles += r.indices.length / 3;
  const indices = batch.vertices <= 65536 ? new Uint16Array(triangles * 3) : new Uint32Array(triangles * 3);
  let v = 0, i = 0;
  for (const [id, r] of batch.regions) {
    positions.set(r.positions, v * 3);
    normals.set(r.normals, v * 3);
    const c = colourOf(id);
    const n = r.positions.length / 3;
    for (let k = 0; k < n; ++k) colours.set([c.r, c.g, c.b], (v + k) * 3);
    for (let k = 0; k < r.indices.length; ++k) indices[i + k] = r.indices[k] + v;
    v += n;
    i += r.indices.length;
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setAttribute('normal', new THREE.BufferAttribute(normals, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
  geometry.setIndex(new THREE.BufferAttribute(indices, 1));
  geometry.computeBoundingSphere();
  geometry.computeBoundingBox();
  return geometry;
}

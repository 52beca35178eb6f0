// meshopt regions ("TSRM", docs/REGION_ENCODING.md "meshopt regions"):
// payloads written here from the document's text alone, with the
// meshoptimizer package's own encoder, decoded by the viewer's decoder:
// positions exactly the float32 values the text's Draco quantizer and
// dequantizer give, ids as 8 bytes and as lattice points, layouts adopted,
// and corrupted payloads refused.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { MeshoptEncoder } from 'meshoptimizer/meshopt_encoder.module.js';
import { crc32 } from '../src/codec/crc32.js';
import { decodeRegion, adoptLayoutIds } from '../src/codec/region_decoder.js';
import { loadMeshopt } from '../src/codec/meshopt_region.js';
import { idName, packId } from '../src/codec/ids.js';

const f = Math.fround;
const grid = { origin: [-2, -2, -2], range: 4, positionBits: 14, normalBits: 10 };
// The single triangle (0, 1, 2) refined once: 6 points on its level-1 lattice.
const points = [[0, 0], [2, 0], [0, 2], [1, 0], [1, 1], [0, 1]];
const faces = [0, 3, 5, 3, 1, 4, 5, 4, 2, 4, 5, 3];
const positions = points.flatMap(([u, v]) => [u * 0.5, v * 0.5, 0.25 * u * v]);
const expectedIds = ['v0:0', 'v0:1', 'v0:2', 'v1:3', 'v1:4', 'v1:5'];
const frame = [0, 0, 0, 1, 2, 0, 1, 2, 7, 3, 3, 1]; // level, face, corners, edges, forward, V E F (varints < 128)

// The text's quantizer: q = floor((p_f32 - origin_f32) * f32(max / range) + 0.5).
function quantize(value, k) {
  const max = 2 ** grid.positionBits - 1;
  const inverse = f(f(max) / f(grid.range));
  return Math.floor(f(f(f(value) - f(grid.origin[k])) * inverse) + 0.5);
}
function dequantized(q, k) {
  const delta = f(f(grid.range) / f(2 ** grid.positionBits - 1));
  return f(f(q * delta) + f(grid.origin[k]));
}

// flags 0: 8-byte ids; 4: lattice points; 2: no ids (the layout's).
function encodeMeshoptRegion(flags, { ids, lattice }) {
  const stride = flags === 0 ? 24 : flags === 4 ? 20 : 16;
  const n = points.length;
  const vertices = new DataView(new ArrayBuffer(n * stride));
  for (let i = 0; i < n; ++i) {
    for (let k = 0; k < 3; ++k) vertices.setUint32(i * stride + 4 * k, quantize(positions[3 * i + k], k), true);
    // The normal (0, 0, 1) on the octahedron: (0, 0), the middle of the
    // square, (2^10 - 2) / 2.
    vertices.setUint16(i * stride + 12, 511, true);
    vertices.setUint16(i * stride + 14, 511, true);
    if (flags === 0) vertices.setBigUint64(i * stride + 16, ids[i], true);
    if (flags === 4) {
      vertices.setUint16(i * stride + 16, lattice[i][0], true);
      vertices.setUint16(i * stride + 18, lattice[i][1], true);
    }
  }
  const vb = MeshoptEncoder.encodeVertexBuffer(new Uint8Array(vertices.buffer), n, stride);
  const ib = MeshoptEncoder.encodeIndexBuffer(new Uint8Array(new Uint32Array(faces).buffer), faces.length, 4);
  const payload = new Uint8Array(8 + vb.length + ib.length);
  new DataView(payload.buffer).setUint32(0, n, true);
  new DataView(payload.buffer).setUint32(4, vb.length, true);
  payload.set(vb, 8);
  payload.set(ib, 8 + vb.length);

  const withFrame = flags === 4 ? frame : [];
  const bytes = new Uint8Array(99 + withFrame.length + payload.length + 4);
  const head = new DataView(bytes.buffer);
  [0x54, 0x53, 0x52, 0x4d].forEach((b, i) => head.setUint8(i, b)); // "TSRM"
  head.setUint16(4, 2, true);
  head.setUint16(6, flags, true);
  head.setBigUint64(8, 0n, true); // region f0:0
  head.setBigUint64(16, 3n, true);
  head.setBigUint64(24, 2n, true);
  head.setInt32(32, 0, true);
  head.setInt32(36, 1, true); // max level 1: the lattice's depth below f0:0
  head.setFloat64(40, 15, true);
  head.setBigInt64(48, 4000000n, true);
  grid.origin.forEach((o, k) => head.setFloat64(57 + 8 * k, o, true));
  head.setFloat64(81, grid.range, true);
  head.setUint8(89, grid.positionBits);
  head.setUint8(90, grid.normalBits);
  head.setUint32(91, faces.length / 3, true);
  head.setUint32(95, payload.length, true);
  bytes.set(withFrame, 99);
  bytes.set(payload, 99 + withFrame.length);
  head.setUint32(bytes.length - 4, crc32(bytes, 0, bytes.length - 4), true);
  return bytes;
}

// Triangles as sorted strings, each rotated to start at its smallest
// index: the index codec may rotate a triangle's corners, never flip it.
function triangleSet(indices) {
  const out = [];
  for (let t = 0; t < indices.length; t += 3) {
    const c = [indices[t], indices[t + 1], indices[t + 2]];
    const m = c.indexOf(Math.min(...c));
    out.push([c[m], c[(m + 1) % 3], c[(m + 2) % 3]].join(','));
  }
  return out.sort();
}

const idsOf = (region) =>
  Array.from(region.idHi, (hi, p) => idName((BigInt(hi) << 32n) | BigInt(region.idLo[p])));

test('8-byte ids and lattice points decode to the text\'s floats, ids and triangles', async () => {
  await MeshoptEncoder.ready;
  const meshopt = await loadMeshopt();
  const ids = points.map((_, i) => packId(i < 3 ? 0 : 1, i));
  for (const flags of [0, 4]) {
    const region = decodeRegion(null, encodeMeshoptRegion(flags, { ids, lattice: points }), meshopt);
    assert.equal(region.header.codec, 'meshopt');
    assert.deepEqual(triangleSet(region.indices), triangleSet(faces));
    assert.deepEqual(idsOf(region), expectedIds, `flags ${flags}`);
    for (let i = 0; i < points.length; ++i) {
      for (let k = 0; k < 3; ++k) {
        const q = quantize(positions[3 * i + k], k);
        assert.equal(region.positions[3 * i + k], dequantized(q, k));
        assert.ok(Math.abs(region.positions[3 * i + k] - positions[3 * i + k]) <= grid.range / (2 ** grid.positionBits - 1));
      }
      assert.deepEqual(Array.from(region.normals.subarray(3 * i, 3 * i + 3)), [0, 0, 1]);
    }
  }
});

test('a payload with the layout\'s ids adopts the held ones', async () => {
  await MeshoptEncoder.ready;
  const meshopt = await loadMeshopt();
  const ids = points.map((_, i) => packId(i < 3 ? 0 : 1, i));
  const held = decodeRegion(null, encodeMeshoptRegion(0, { ids }), meshopt);
  const thin = decodeRegion(null, encodeMeshoptRegion(2, {}), meshopt);
  assert.equal(thin.idHi, null);
  adoptLayoutIds(thin, held, 2n);
  assert.deepEqual(idsOf(thin), expectedIds);
});

test('refused: no meshopt module, corruption, a foreign stream version', async () => {
  await MeshoptEncoder.ready;
  const meshopt = await loadMeshopt();
  const bytes = encodeMeshoptRegion(0, { ids: points.map((_, i) => BigInt(i)) });
  assert.throws(() => decodeRegion(null, bytes, null), /meshopt region, and this decoder has no meshopt module/);
  const flipped = bytes.slice();
  flipped[110] ^= 0x10;
  assert.throws(() => decodeRegion(null, flipped, meshopt), /checksum mismatch/);
  const version = bytes.slice();
  version[99 + 8] = 0xa7;
  new DataView(version.buffer).setUint32(version.length - 4, crc32(version, 0, version.length - 4), true);
  assert.throws(() => decodeRegion(null, version, meshopt), /stream versions 167 and 225/);
});

// The region payload (docs/PROTOCOL.md 6.2): CRC-32 against zlib's check
// value, then payloads made here with draco3d's encoder decoded by the
// viewer's decoder under flags 0, 4, 8 and 2, and corrupted ones refused.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { crc32 } from '../src/codec/crc32.js';
import { decodeRegion, adoptLayoutIds } from '../src/codec/region_decoder.js';
import { RegionLattice } from '../src/codec/region_lattice.js';
import { idName, packId } from '../src/codec/ids.js';
import { dracoDecoder, dracoEncoder } from './support/draco_node.mjs';
import { encodeTestRegion } from './support/region_encoder.mjs';

test('CRC-32 of "123456789" is zlib\'s 0xcbf43926', () => {
  assert.equal(crc32(new TextEncoder().encode('123456789')), 0xcbf43926);
  assert.equal(crc32(new Uint8Array(0)), 0);
});

const grid = { origin: [-2, -2, -2], range: 4, positionBits: 14, normalBits: 10 };

// The single triangle (0, 1, 2) refined once: 6 points on its level-1
// lattice, 4 faces in the order of 3.2's table.
const points = [[0, 0], [2, 0], [0, 2], [1, 0], [1, 1], [0, 1]];
const faces = [0, 3, 5, 3, 1, 4, 5, 4, 2, 4, 5, 3];
const positions = points.flatMap(([u, v]) => [u * 0.5, v * 0.5, 0.25 * u * v]);
const normals = points.flatMap(() => [0, 0, 1]);
const frame = { level: 0, index: 0, corners: [0, 1, 2], edges: [0, 1, 2], forward: 7, baseCounts: [3, 3, 1] };
const expectedIds = ['v0:0', 'v0:1', 'v0:2', 'v1:3', 'v1:4', 'v1:5'];

// Decoded vertices may come in another order: read them back by position.
function idsByPoint(region, at = points) {
  const out = new Map();
  for (let p = 0; p < region.positions.length / 3; ++p) {
    const key = [0, 1].map((k) => Math.round(region.positions[3 * p + k] * 2)).join(',');
    out.set(key, idName((BigInt(region.idHi[p]) << 32n) | BigInt(region.idLo[p])));
  }
  return at.map(([u, v]) => out.get(`${u},${v}`));
}

test('8-byte ids (flag 0) round-trip, positions within the grid step', async () => {
  const [draco, enc] = await Promise.all([dracoDecoder(), dracoEncoder()]);
  const ids = points.map(([u, v], i) => packId(i < 3 ? 0 : 1, i));
  const bytes = encodeTestRegion(enc, { flags: 0, regionId: 0n, documentVersion: 3n, layoutVersion: 2n, maxLevel: 1, grid },
    { positions, normals, faces, ids });
  const region = decodeRegion(draco, bytes);
  assert.equal(region.header.regionId, 0n);
  assert.equal(region.header.documentVersion, 3n);
  assert.equal(region.header.layoutVersion, 2n);
  assert.equal(region.indices.length, 12);
  assert.deepEqual(idsByPoint(region), expectedIds);
  const step = grid.range / (2 ** grid.positionBits - 1);
  for (let p = 0; p < region.positions.length / 3; ++p) {
    const z = region.positions[3 * p + 2], x = region.positions[3 * p], y = region.positions[3 * p + 1];
    assert.ok(Math.abs(z - x * y) <= step, `point ${p}`);
    assert.ok(Math.abs(Math.hypot(...region.normals.subarray(3 * p, 3 * p + 3)) - 1) < 1e-6);
  }
});

test('lattice ids (flag 4) become the ids of 3.2', async () => {
  const [draco, enc] = await Promise.all([dracoDecoder(), dracoEncoder()]);
  const bytes = encodeTestRegion(enc, { flags: 4, regionId: 0n, documentVersion: 1n, layoutVersion: 1n, maxLevel: 1, grid, frame },
    { positions, normals, faces, lattice: points });
  const region = decodeRegion(draco, bytes);
  assert.equal(region.header.latticeDepth, 1);
  assert.deepEqual(idsByPoint(region), expectedIds);
  const lattice = new RegionLattice(frame, 1);
  assert.equal(idName(lattice.idAt(1, 1)), 'v1:4');
});

test('a payload without ids (flag 2) adopts the held layout\'s, or is refused', async () => {
  const [draco, enc] = await Promise.all([dracoDecoder(), dracoEncoder()]);
  const held = decodeRegion(draco, encodeTestRegion(enc,
    { flags: 4, regionId: 0n, documentVersion: 1n, layoutVersion: 1n, maxLevel: 1, grid, frame },
    { positions, normals, faces, lattice: points }));
  const moved = positions.map((x, i) => (i % 3 === 2 ? x + 0.125 : x));
  const bytes = encodeTestRegion(enc, { flags: 2, regionId: 0n, documentVersion: 2n, layoutVersion: 1n, maxLevel: 1, grid },
    { positions: moved, normals, faces });
  const region = decodeRegion(draco, bytes);
  assert.equal(region.idHi, null);
  adoptLayoutIds(region, held, 1n);
  assert.deepEqual(idsByPoint(region), expectedIds);
  const again = decodeRegion(draco, bytes);
  assert.throws(() => adoptLayoutIds(again, held, 0n), /layout 1, the view holds layout 0/);
  assert.throws(() => adoptLayoutIds(again, null, 1n), /does not hold it/);
});

test('corrupted, truncated and foreign payloads are refused with the reason', async () => {
  const [draco, enc] = await Promise.all([dracoDecoder(), dracoEncoder()]);
  const bytes = encodeTestRegion(enc, { flags: 4, regionId: 0n, documentVersion: 1n, layoutVersion: 1n, maxLevel: 1, grid, frame },
    { positions, normals, faces, lattice: points });
  const flipped = bytes.slice();
  flipped[120] ^= 0x10;
  assert.throws(() => decodeRegion(draco, flipped), /checksum mismatch/);
  assert.throws(() => decodeRegion(draco, bytes.subarray(0, bytes.length - 1)), /truncated/);
  const foreign = bytes.slice();
  foreign[0] = 0x58;
  assert.throws(() => decodeRegion(draco, foreign), /TSRG/);
  const twoFlags = bytes.slice();
  twoFlags[6] = 5;
  assert.throws(() => decodeRegion(draco, twoFlags), /more than one way/);
});

// A quad refined once (docs/PROTOCOL.md 6.2 "Quad lattice ids"): 9 points,
// 4 child quads of 2 triangles each, positions as above.
const quadPoints = [[0, 0], [2, 0], [2, 2], [0, 2], [1, 1], [1, 0], [2, 1], [1, 2], [0, 1]];
const quadFaces = [0, 5, 4, 0, 4, 8, 5, 1, 6, 5, 6, 4, 4, 6, 2, 4, 2, 7, 8, 4, 7, 8, 7, 3];
const quadMesh = {
  positions: quadPoints.flatMap(([u, v]) => [u * 0.5, v * 0.5, 0.25 * u * v]),
  normals: quadPoints.flatMap(() => [0, 0, 1]),
  faces: quadFaces,
  lattice: quadPoints,
};
const quadFrame = { sides: 4, level: 0, index: 0, firstChild: 0, corners: [0, 1, 2, 3], edges: [0, 1, 2, 3], forward: 15,
  baseCounts: [4, 4, 1, 4] };
// A face of the quad cube's level 1 (V1 = 26, F1 = 24), its first child 4 x 17.
const cubeFrame = { sides: 4, level: 1, index: 17, firstChild: 68, corners: [3, 20, 11, 25], edges: [40, 5, 47, 30], forward: 5,
  baseCounts: [8, 12, 6, 24] };
const quadHeader = (frame, maxLevel) =>
  ({ flags: 8, regionId: packId(frame.level, frame.index), documentVersion: 1n, layoutVersion: 1n, maxLevel, grid, frame });

test('quad lattice ids (flag 8) become the ids of the quad split', async () => {
  const [draco, enc] = await Promise.all([dracoDecoder(), dracoEncoder()]);
  const region = decodeRegion(draco, encodeTestRegion(enc, quadHeader(quadFrame, 1), quadMesh));
  assert.equal(region.header.flags, 8);
  assert.equal(region.header.frame.sides, 4);
  assert.equal(region.header.frame.firstChild, 0);
  assert.deepEqual(region.header.frame.baseCounts, [4, 4, 1, 4]);
  assert.equal(region.header.latticeDepth, 1);
  assert.equal(region.indices.length, 24);
  // Corners keep their ids; the face vertex is V0 + 0 = 4, the edge vertices
  // V0 + F0 + e = 5 + e.
  assert.deepEqual(idsByPoint(region, quadPoints), ['v0:0', 'v0:1', 'v0:2', 'v0:3', 'v1:4', 'v1:5', 'v1:6', 'v1:7', 'v1:8']);
});

test('a level-1 quad\'s ids (flag 8) take their birth levels', async () => {
  const [draco, enc] = await Promise.all([dracoDecoder(), dracoEncoder()]);
  const region = decodeRegion(draco, encodeTestRegion(enc, quadHeader(cubeFrame, 2), quadMesh));
  assert.equal(region.header.regionId, packId(1, 17));
  assert.equal(region.header.frame.firstChild, 68);
  assert.equal(region.header.latticeDepth, 1);
  // Corners 3 < V0 = 8 (level 0), 20, 11, 25 < V1 = 26 (level 1); the face
  // vertex V1 + 17 = 43; the edge vertices V1 + F1 + e = 50 + e: 90, 55, 97
  // (V2 - 1 = 97), 80.
  assert.deepEqual(idsByPoint(region, quadPoints),
    ['v0:3', 'v1:20', 'v1:11', 'v1:25', 'v2:43', 'v2:90', 'v2:55', 'v2:97', 'v2:80']);
});

test('malformed quad frames and points are refused with the reason', async () => {
  const [draco, enc] = await Promise.all([dracoDecoder(), dracoEncoder()]);
  const decode = (frame, maxLevel, mesh = quadMesh, header = quadHeader(frame, maxLevel)) =>
    () => decodeRegion(draco, encodeTestRegion(enc, header, mesh));
  assert.throws(decode({ ...cubeFrame, firstChild: 69 }, 2),
    /the frame's first child 69 is not 4 x 17, as f1:17 is below the base level/);
  assert.throws(decode({ ...quadFrame, forward: 16 }, 1), /edge directions 16 set bits beyond the 4 edges of f0:0/);
  assert.throws(decode({ ...quadFrame, firstChild: 1 }, 1),
    /first child 1 leaves no room for 4 children among level 1's 4 faces/);
  assert.throws(decode(cubeFrame, 2, quadMesh, { ...quadHeader(cubeFrame, 2), regionId: packId(1, 16) }),
    /the frame names face f1:17, not the region's face f1:16/);
  // A triangle's frame (flag 4) keeps its three direction bits.
  const triangle = { positions, normals, faces, lattice: points };
  assert.throws(decode(frame, 1, triangle, { ...quadHeader(frame, 1), flags: 4, frame: { ...frame, forward: 8 } }),
    /edge directions 8 set bits beyond the 3 edges/);
  // (3, 0) lies beyond the side 2 of a depth-1 lattice.
  const outside = { ...quadMesh, lattice: quadPoints.map(([u, v], p) => (p === 1 ? [3, 0] : [u, v])) };
  assert.throws(decode(quadFrame, 1, outside),
    /region 0 \(document version 1\): point \d+: lattice point \(3, 0\) outside the root face's lattice of side 2/);
  // Depth 8 does not fit a byte's coordinates.
  assert.throws(decode(quadFrame, 8), /depth 8 outside \[0, 7\]/);

  // The frame cut short at every byte: level, index, first child, 4 corners,
  // 4 edges, directions and 4 base counts, one byte each here.
  const bytes = encodeTestRegion(enc, quadHeader(quadFrame, 1), quadMesh);
  const fields = ["face level", 'face', 'first child', ...Array(4).fill('corners'), ...Array(4).fill('edges'), 'edge directions',
    ...Array(4).fill('base counts')];
  fields.forEach((field, k) => {
    assert.throws(() => decodeRegion(draco, bytes.subarray(0, 99 + k)),
      new RegExp(`truncated at byte ${99 + k}: the frame's ${field} needs 1 bytes`), `cut after ${k} bytes of the frame`);
  });
  const both = bytes.slice();
  both[6] = 12;
  assert.throws(() => decodeRegion(draco, both), /flags 12 claim more than one way/);
  const unknown = bytes.slice();
  unknown[6] = 16;
  assert.throws(() => decodeRegion(draco, unknown), /unknown flags 16/);
});

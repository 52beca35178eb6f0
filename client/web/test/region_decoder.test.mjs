// The region payload (docs/PROTOCOL.md 6.2): CRC-32 against zlib's check
// value, then payloads made here with draco3d's encoder decoded by the
// viewer's decoder under flags 0, 4 and 2, and corrupted ones refused.
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
function idsByPoint(region) {
  const out = new Map();
  for (let p = 0; p < region.positions.length / 3; ++p) {
    const key = [0, 1].map((k) => Math.round(region.positions[3 * p + k] * 2)).join(',');
    out.set(key, idName((BigInt(region.idHi[p]) << 32n) | BigInt(region.idLo[p])));
  }
  return points.map(([u, v]) => out.get(`${u},${v}`));
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

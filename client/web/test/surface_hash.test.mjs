// docs/PROTOCOL.md 6.5's worked example, computed by the viewer's code: the
// reference BigInt form and the fast form over a decoded-region layout.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { canonicalTriangleBytes, fnv1a64, regionHash, sumHashes } from '../src/codec/surface_hash.js';
import { packId } from '../src/codec/ids.js';
import { hex64 } from '../src/codec/uint64.js';

const v1_26 = packId(1, 26), v3_1234 = packId(3, 1234), v0_7 = packId(0, 7);
const triangle = [
  { id: v1_26, x: 2.5, y: 0, z: -0.75 },
  { id: v3_1234, x: 0.25, y: -1.5, z: 3 },
  { id: v0_7, x: -0, y: 0.125, z: 1 },
];

// One triangle as a decoded region: positions, id halves, indices.
function asRegion(triangles, withIds = true) {
  const corners = triangles.flat();
  const positions = new Float32Array(corners.flatMap((c) => [c.x, c.y, c.z]));
  const idHi = withIds ? new Uint32Array(corners.map((c) => Number(BigInt(c.id) >> 32n))) : null;
  const idLo = withIds ? new Uint32Array(corners.map((c) => Number(BigInt(c.id) & 0xffffffffn))) : null;
  const indices = new Uint32Array(corners.map((_, i) => i));
  return { positions, idHi, idLo, indices };
}

test('the 60 canonical bytes start at v0:7 as the text shows them', () => {
  const expected = [
    '07 00 00 00 00 00 00 00 00 00 00 00 00 00 00 3e 00 00 80 3f',
    '1a 00 00 00 00 00 00 04 00 00 20 40 00 00 00 00 00 00 40 bf',
    'd2 04 00 00 00 00 00 0c 00 00 80 3e 00 00 c0 bf 00 00 40 40',
  ].join(' ');
  const got = [...canonicalTriangleBytes(triangle)].map((b) => b.toString(16).padStart(2, '0')).join(' ');
  assert.equal(got, expected);
});

test('the example triangle hashes to 0xe453ef2728c8a2b3 (reference and fast forms)', () => {
  assert.equal(hex64(fnv1a64(canonicalTriangleBytes(triangle))), '0xe453ef2728c8a2b3');
  assert.equal(hex64(regionHash(asRegion([triangle]))), '0xe453ef2728c8a2b3');
});

test('the reversed triangle hashes to 0x92866d435b9a347b', () => {
  const reversed = [triangle[1], triangle[0], triangle[2]];
  assert.equal(hex64(fnv1a64(canonicalTriangleBytes(reversed))), '0x92866d435b9a347b');
  assert.equal(hex64(regionHash(asRegion([reversed]))), '0x92866d435b9a347b');
});

test('a display-only triangle and the two-triangle surface', () => {
  const plain = [{ id: 0n, x: 1, y: 2, z: 3 }, { id: 0n, x: 1, y: 2, z: 2 }, { id: 0n, x: 0.5, y: 2, z: 3 }];
  assert.equal(hex64(regionHash(asRegion([plain], false))), '0xfe0234f5371dc0e8');
  const sum = sumHashes([regionHash(asRegion([triangle])), regionHash(asRegion([plain], false))]);
  assert.equal(hex64(sum), '0xe256241c5fe6639b');
});

test('a rotation of the corners does not change the hash', () => {
  const rotated = [triangle[2], triangle[0], triangle[1]];
  assert.equal(regionHash(asRegion([rotated])), regionHash(asRegion([triangle])));
});

test('the fast form equals the reference on random triangles, ids above 2^53 included', () => {
  let seed = 12345;
  const random = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) / 2147483648);
  for (let n = 0; n < 200; ++n) {
    const tri = [0, 1, 2].map(() => ({
      id: packId(Math.floor(random() * 64), BigInt(Math.floor(random() * 2 ** 30)) * BigInt(Math.floor(random() * 2 ** 28))),
      x: Math.fround((random() - 0.5) * 100),
      y: random() < 0.1 ? -0 : Math.fround((random() - 0.5) * 100),
      z: Math.fround((random() - 0.5) * 100),
    }));
    if (n % 7 === 0) tri[1].id = tri[0].id; // equal ids: the positions decide
    assert.equal(regionHash(asRegion([tri])), fnv1a64(canonicalTriangleBytes(tri)), `triangle ${n}`);
  }
});

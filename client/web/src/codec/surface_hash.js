// The surface hash of docs/PROTOCOL.md 6.5 (core/tessellation/surface_hash.h):
// per triangle, the FNV-1a 64 of 60 canonical bytes (three corners of id u64,
// x, y, z float32 bits, little-endian, in the rotation whose keys compare
// smallest, -0.0 taken as +0.0); the surface's hash is the sum modulo 2^64.
//
// Why two code paths: fnv1a64 is the text of 6.5 in BigInt, kept for the
// tests to read against; regionHash runs the same arithmetic on uint32
// halves, because a region of 10^5 triangles would need 6 million BigInt
// multiplications. test/surface_hash.test.mjs holds them equal.

const TWO_32 = 4294967296;
const FNV_OFFSET_HI = 0xcbf29ce4, FNV_OFFSET_LO = 0x84222325;

// FNV-1a 64 of bytes, the reference form.
export function fnv1a64(bytes) {
  let h = 0xcbf29ce484222325n;
  for (const b of bytes) h = BigInt.asUintN(64, (h ^ BigInt(b)) * 0x100000001b3n);
  return h;
}

// The canonical 60 bytes of a triangle whose corners are {id: BigInt, x, y,
// z} with float32 values: the reference form of steps 2-4.
export function canonicalTriangleBytes(corners) {
  const scratch = new DataView(new ArrayBuffer(4));
  const bits = (x) => {
    scratch.setFloat32(0, x, true);
    const b = scratch.getUint32(0, true);
    return b === 0x80000000 ? 0 : b;
  };
  const keys = corners.map((c) => [BigInt(c.id), bits(c.x), bits(c.y), bits(c.z)]);
  const compare = (a, b) => {
    for (let k = 0; k < 4; ++k) if (a[k] !== b[k]) return a[k] < b[k] ? -1 : 1;
    return 0;
  };
  let best = 0;
  for (let r = 1; r < 3; ++r) {
    for (let k = 0; k < 3; ++k) {
      const c = compare(keys[(r + k) % 3], keys[(best + k) % 3]);
      if (c < 0) { best = r; break; }
      if (c > 0) break;
    }
  }
  const out = new DataView(new ArrayBuffer(60));
  for (let k = 0; k < 3; ++k) {
    const key = keys[(best + k) % 3];
    out.setBigUint64(20 * k, key[0], true);
    for (let a = 0; a < 3; ++a) out.setUint32(20 * k + 8 + 4 * a, key[1 + a], true);
  }
  return new Uint8Array(out.buffer);
}

// Steps 3-5 for one triangle whose corners are given as keys: [idHi, idLo,
// xBits, yBits, zBits] per corner, uint32 each.
function compareKeys(keys, a, b) {
  for (let k = 0; k < 3; ++k) {
    const ka = keys[(a + k) % 3], kb = keys[(b + k) % 3];
    for (let f = 0; f < 5; ++f) if (ka[f] !== kb[f]) return ka[f] < kb[f] ? -1 : 1;
  }
  return 0;
}

const bytes = new Uint8Array(60);
const view = new DataView(bytes.buffer);
const result = [0, 0];

// FNV-1a 64 of the canonical bytes of one triangle into result[0] (hi) and
// result[1] (lo). The prime is 2^40 + 0x1b3: h * prime = h * 0x1b3 + (h << 40),
// and every partial product stays below 2^53.
function triangleHashHalves(keys) {
  let best = 0;
  if (compareKeys(keys, 1, best) < 0) best = 1;
  if (compareKeys(keys, 2, best) < 0) best = 2;
  for (let k = 0; k < 3; ++k) {
    const key = keys[(best + k) % 3];
    view.setUint32(20 * k, key[1], true);
    view.setUint32(20 * k + 4, key[0], true);
    view.setUint32(20 * k + 8, key[2], true);
    view.setUint32(20 * k + 12, key[3], true);
    view.setUint32(20 * k + 16, key[4], true);
  }
  let hi = FNV_OFFSET_HI, lo = FNV_OFFSET_LO;
  for (let i = 0; i < 60; ++i) {
    lo = (lo ^ bytes[i]) >>> 0;
    const low = lo * 0x1b3;
    const carry = Math.floor(low / TWO_32);
    hi = (hi * 0x1b3 + carry + ((lo << 8) >>> 0)) % TWO_32;
    lo = low % TWO_32;
  }
  result[0] = hi;
  result[1] = lo;
}

function floatBits(x) {
  return x === 0x80000000 ? 0 : x;
}

// The sum of the triangle hashes of one decoded region ({positions:
// Float32Array, idHi/idLo: Uint32Array or null, indices}), as a BigInt.
export function regionHash(region) {
  const bitsOf = new Uint32Array(region.positions.buffer, region.positions.byteOffset, region.positions.length);
  const { idHi, idLo, indices } = region;
  const keys = [[0, 0, 0, 0, 0], [0, 0, 0, 0, 0], [0, 0, 0, 0, 0]];
  let sumHi = 0, sumLo = 0;
  for (let t = 0; t < indices.length; t += 3) {
    for (let k = 0; k < 3; ++k) {
      const v = indices[t + k];
      const key = keys[k];
      key[0] = idHi ? idHi[v] : 0;
      key[1] = idLo ? idLo[v] : 0;
      key[2] = floatBits(bitsOf[3 * v]);
      key[3] = floatBits(bitsOf[3 * v + 1]);
      key[4] = floatBits(bitsOf[3 * v + 2]);
    }
    triangleHashHalves(keys);
    sumLo += result[1];
    sumHi += result[0];
    if (sumLo >= TWO_32) { sumLo -= TWO_32; sumHi += 1; }
    sumHi %= TWO_32;
  }
  return (BigInt(sumHi) << 32n) | BigInt(sumLo);
}

// The surface hash of regions already hashed: the sum modulo 2^64.
export function sumHashes(hashes) {
  let sum = 0n;
  for (const h of hashes) sum += h;
  return BigInt.asUintN(64, sum);
}

// 64-bit unsigned numbers as the viewer handles them. The wire's uint64
// fields arrive as long.js Longs (protobufjs), the region payloads carry them
// as little-endian byte pairs, and ids above 2^53 are common (a vertex of
// level 3 is 3 << 58), so JavaScript numbers would round them. BigInt is the
// one exact form the rest of the viewer uses; these helpers convert at the
// edges.
import Long from 'long';

const TWO_32 = 4294967296;

// A Long, number, string, BigInt or nothing (an unset proto3 field) as a BigInt.
export function toBig(value) {
  if (value === undefined || value === null) return 0n;
  if (typeof value === 'bigint') return value;
  if (typeof value === 'number') return BigInt(value);
  if (typeof value === 'string') return BigInt(value);
  if (Long.isLong(value)) return (BigInt(value.high >>> 0) << 32n) | BigInt(value.low >>> 0);
  throw new TypeError(`not a 64-bit number: ${value}`);
}

// A BigInt (or a small number) as the unsigned Long protobufjs writes exactly.
export function toLong(value) {
  const big = BigInt.asUintN(64, BigInt(value));
  return Long.fromBits(Number(big & 0xffffffffn) | 0, Number(big >> 32n) | 0, true);
}

// Two uint32 halves as a BigInt, and back: region ids and hashes are kept as
// halves in typed arrays, where millions of BigInts would be slow.
export function fromHalves(hi, lo) {
  return (BigInt(hi >>> 0) << 32n) | BigInt(lo >>> 0);
}

export function halvesOf(value) {
  const big = BigInt.asUintN(64, BigInt(value));
  return [Number(big >> 32n), Number(big & 0xffffffffn)];
}

// "0x" and 16 lower-case hex digits, as tessera-replay prints a hash.
export function hex64(value) {
  return '0x' + BigInt.asUintN(64, BigInt(value)).toString(16).padStart(16, '0');
}

// A safe integer (< 2^53) from halves, or an error naming what overflowed.
export function safeNumber(hi, lo, what) {
  const n = (hi >>> 0) * TWO_32 + (lo >>> 0);
  if (!Number.isSafeInteger(n)) throw new RangeError(`${what}: ${fromHalves(hi, lo)} is beyond 2^53`);
  return n;
}

// CRC-32 as zlib's crc32() computes it (reflected polynomial 0xEDB88320,
// initial and final XOR with all ones): the checksum that ends every region
// payload (docs/PROTOCOL.md 6.2). A table of 256 entries, built once.
const TABLE = (() => {
  const table = new Uint32Array(256);
  for (let n = 0; n < 256; ++n) {
    let c = n;
    for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    table[n] = c >>> 0;
  }
  return table;
})();

// The CRC-32 of bytes[begin, end) as an unsigned number.
export function crc32(bytes, begin = 0, end = bytes.length) {
  let c = 0xffffffff;
  for (let i = begin; i < end; ++i) c = TABLE[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

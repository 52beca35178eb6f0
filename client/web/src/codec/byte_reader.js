// A bounds-checked little-endian cursor over a Uint8Array, for the region
// header and frame (docs/PROTOCOL.md 6.2). Every read names what it wanted,
// so a truncated payload says which field ran out.
export class ByteReader {
  constructor(bytes, source) {
    this.bytes = bytes;
    this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    this.offset = 0;
    this.source = source;
  }

  get remaining() {
    return this.bytes.length - this.offset;
  }

  need(count, what) {
    if (this.remaining < count) {
      throw new Error(`${this.source}: truncated at byte ${this.offset}: ${what} needs ${count} bytes, ${this.remaining} remain`);
    }
  }

  u8(what) {
    this.need(1, what);
    return this.bytes[this.offset++];
  }

  // `bytes` little-endian bytes through the DataView getter `get`.
  fixed(bytes, get, what) {
    this.need(bytes, what);
    const x = this.view[get](this.offset, true);
    this.offset += bytes;
    return x;
  }

  u16(what) { return this.fixed(2, 'getUint16', what); }
  u32(what) { return this.fixed(4, 'getUint32', what); }
  i32(what) { return this.fixed(4, 'getInt32', what); }
  u64(what) { return this.fixed(8, 'getBigUint64', what); }
  i64(what) { return this.fixed(8, 'getBigInt64', what); }
  f64(what) { return this.fixed(8, 'getFloat64', what); }

  // An LEB128 varint of at most 64 bits, as a safe integer: the frame's
  // numbers are indices and counts, which the viewer keeps below 2^53.
  varint(what) {
    let value = 0n;
    for (let shift = 0n; shift < 64n; shift += 7n) {
      const byte = this.u8(what);
      value |= BigInt(byte & 0x7f) << shift;
      if ((byte & 0x80) === 0) {
        if (value > BigInt(Number.MAX_SAFE_INTEGER)) throw new RangeError(`${this.source}: ${what} ${value} is beyond 2^53`);
        return Number(value);
      }
    }
    throw new Error(`${this.source}: ${what}: a varint longer than 64 bits`);
  }
}

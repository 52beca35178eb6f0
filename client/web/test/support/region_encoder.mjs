// A region payload made in the test, as encodeRegion() lays it out
// (core/tessellation/region_codec.cc): header, optional frame, a Draco mesh
// from the draco3d encoder on the header's grid, CRC-32. Enough to round-trip
// the viewer's decoder without a server.
import { crc32 } from '../../src/codec/crc32.js';

function varint(out, n) {
  let x = BigInt(n);
  do {
    let byte = Number(x & 0x7fn);
    x >>= 7n;
    if (x > 0n) byte |= 0x80;
    out.push(byte);
  } while (x > 0n);
}

// mesh: {positions: number[] (3 per point), normals, faces: number[] (3 per
// face), ids: BigInt[] or null, lattice: [u, v][] or null}; header: {flags,
// regionId, documentVersion, layoutVersion, maxLevel, grid: {origin, range,
// positionBits, normalBits}, frame}; a frame with sides 4 is a quad's
// (flag 8), which carries its first child after the face.
export function encodeTestRegion(enc, header, mesh) {
  const encoder = new enc.Encoder();
  const builder = new enc.MeshBuilder();
  const dmesh = new enc.Mesh();
  const points = mesh.positions.length / 3;
  builder.AddFacesToMesh(dmesh, mesh.faces.length / 3, new Uint32Array(mesh.faces));
  builder.AddFloatAttribute(dmesh, enc.POSITION, points, 3, new Float32Array(mesh.positions));
  builder.AddFloatAttribute(dmesh, enc.NORMAL, points, 3, new Float32Array(mesh.normals));
  if (mesh.ids) {
    const raw = new Uint8Array(points * 8);
    mesh.ids.forEach((id, p) => { for (let c = 0; c < 8; ++c) raw[8 * p + c] = Number((id >> BigInt(8 * c)) & 0xffn); });
    builder.AddUInt8Attribute(dmesh, enc.GENERIC, points, 8, raw);
  } else if (mesh.lattice) {
    builder.AddUInt8Attribute(dmesh, enc.GENERIC, points, 2, new Uint8Array(mesh.lattice.flat()));
  }
  const g = header.grid;
  encoder.SetAttributeExplicitQuantization(enc.POSITION, g.positionBits, 3, g.origin, g.range);
  encoder.SetAttributeQuantization(enc.NORMAL, g.normalBits);
  encoder.SetSpeedOptions(7, 7);
  const out = new enc.DracoInt8Array();
  const length = encoder.EncodeMeshToDracoBuffer(dmesh, out);
  if (length <= 0) throw new Error('the Draco encoder failed');
  const draco = new Uint8Array(length);
  for (let i = 0; i < length; ++i) draco[i] = out.GetValue(i) & 0xff;
  [out, dmesh, builder, encoder].forEach((o) => enc.destroy(o));

  const head = new DataView(new ArrayBuffer(99));
  [0x54, 0x53, 0x52, 0x47].forEach((b, i) => head.setUint8(i, b));
  head.setUint16(4, 2, true);
  head.setUint16(6, header.flags, true);
  head.setBigUint64(8, header.regionId, true);
  head.setBigUint64(16, header.documentVersion, true);
  head.setBigUint64(24, header.layoutVersion, true);
  head.setInt32(32, 0, true);
  head.setInt32(36, header.maxLevel, true);
  head.setFloat64(40, 15, true);
  head.setBigInt64(48, 4000000n, true);
  head.setUint8(56, 0);
  g.origin.forEach((o, k) => head.setFloat64(57 + 8 * k, o, true));
  head.setFloat64(81, g.range, true);
  head.setUint8(89, g.positionBits);
  head.setUint8(90, g.normalBits);
  head.setUint32(91, mesh.faces.length / 3, true);
  head.setUint32(95, length, true);
  const frame = [];
  if (header.frame) {
    const f = header.frame;
    frame.push(f.level);
    varint(frame, f.index);
    if (f.sides === 4) varint(frame, f.firstChild);
    f.corners.forEach((c) => varint(frame, c));
    f.edges.forEach((e) => varint(frame, e));
    frame.push(f.forward);
    f.baseCounts.forEach((n) => varint(frame, n));
  }
  const bytes = new Uint8Array(99 + frame.length + length + 4);
  bytes.set(new Uint8Array(head.buffer));
  bytes.set(frame, 99);
  bytes.set(draco, 99 + frame.length);
  new DataView(bytes.buffer).setUint32(bytes.length - 4, crc32(bytes, 0, bytes.length - 4), true);
  return bytes;
}

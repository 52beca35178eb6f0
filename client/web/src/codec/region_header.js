// The bytes around a region's Draco mesh (docs/PROTOCOL.md 6.2,
// core/tessellation/region_codec.h): magic, format version, flags, ids and
// versions, the normalized LOD profile, the document's quantization grid,
// the counts, the lattice frame under flags 4 and 8, and the CRC-32
// trailer. Pure parsing and checking, no Draco, so it is tested on its own.
import { ByteReader } from './byte_reader.js';
import { crc32 } from './crc32.js';
import { idName, packId } from './ids.js';

export const REGION_FORMAT_VERSION = 2;
export const REGION_HEADER_BYTES = 99;
export const FLAG_NO_IDS = 1; // display-only profile: no GENERIC attribute
export const FLAG_LAYOUT_IDS = 2; // the ids of the held layout apply (adoptLayoutIds)
export const FLAG_LATTICE_IDS = 4; // a triangle's frame follows; GENERIC holds lattice points
export const FLAG_QUAD_LATTICE_IDS = 8; // the same for a quad of the quad split (Catmull-Clark)
const FLAGS = FLAG_NO_IDS | FLAG_LAYOUT_IDS | FLAG_LATTICE_IDS | FLAG_QUAD_LATTICE_IDS;
const MAGIC = [0x54, 0x53, 0x52, 0x47]; // "TSRG": a Draco payload
const MESHOPT_MAGIC = 0x4d; // "TSRM": a meshopt payload (docs/REGION_ENCODING.md "meshopt regions")

function hex32(x) {
  return '0x' + (x >>> 0).toString(16).padStart(8, '0');
}

// The frame of a lattice-id payload: the root face, its corners and edges
// (edge j joins corners j and j+1), their directions and the base counts. A
// quad's (flag 8, docs/PROTOCOL.md 6.2 "Quad lattice ids") also has the
// index of its first child face, which a base face's position among faces
// of other sizes decides, and the base mesh's corner count C0, which the
// quad split's counts need.
function readFrame(r, sides) {
  const quad = sides === 4;
  const level = r.u8("the frame's face level");
  const index = r.varint("the frame's face");
  const firstChild = quad ? r.varint("the frame's first child") : undefined;
  const corners = Array.from({ length: sides }, () => r.varint("the frame's corners"));
  const edges = Array.from({ length: sides }, () => r.varint("the frame's edges"));
  const forward = r.u8("the frame's edge directions");
  const baseCounts = Array.from({ length: quad ? 4 : 3 }, () => r.varint("the frame's base counts"));
  return quad
    ? { sides, level, index, firstChild, corners, edges, forward, baseCounts }
    : { sides, level, index, corners, edges, forward, baseCounts };
}

// Parses and checks one payload. Returns the header and where the Draco
// bytes lie; throws an Error naming the region and the reason.
export function parseRegion(bytes) {
  const r = new ByteReader(bytes, 'region payload');
  r.need(4, 'the magic');
  const meshopt = bytes[3] === MESHOPT_MAGIC;
  for (let k = 0; k < 4; ++k) {
    if (bytes[k] !== MAGIC[k] && !(k === 3 && meshopt)) {
      throw new Error('region payload: not a Tessera region (no "TSRG" or "TSRM" magic)');
    }
  }
  r.offset = 4;
  const version = r.u16('the format version');
  if (version !== REGION_FORMAT_VERSION) {
    throw new Error(`region payload: format version ${version} is not supported (this viewer reads ${REGION_FORMAT_VERSION})`);
  }
  const flags = r.u16('the flags');
  if (flags & ~FLAGS) throw new Error(`region payload: unknown flags ${flags}`);
  if (flags & (flags - 1)) throw new Error(`region payload: flags ${flags} claim more than one way of carrying ids`);
  const header = {
    codec: meshopt ? 'meshopt' : 'draco',
    flags,
    regionId: r.u64('the region id'),
    documentVersion: r.u64('the document version'),
    layoutVersion: r.u64('the layout version'),
    profile: {
      baseLevel: r.i32('the LOD base level'),
      maxLevel: r.i32('the LOD max level'),
      angleThresholdDegrees: r.f64('the LOD angle threshold'),
      triangleBudget: r.i64('the LOD triangle budget'),
      fidelity: r.u8('the LOD fidelity flag'),
    },
    grid: {
      origin: [r.f64('the grid origin'), r.f64('the grid origin'), r.f64('the grid origin')],
      range: r.f64('the grid range'),
      positionBits: r.u8('the position bits'),
      normalBits: r.u8('the normal bits'),
    },
    triangles: r.u32('the triangle count'),
    dracoBytes: r.u32('the Draco payload size'),
    frame: null,
  };
  header.hasIds = (flags & FLAG_NO_IDS) === 0;
  header.idsInline = (flags & FLAG_LAYOUT_IDS) === 0;
  if (flags & FLAG_LATTICE_IDS) header.frame = readFrame(r, 3);
  if (flags & FLAG_QUAD_LATTICE_IDS) header.frame = readFrame(r, 4);
  header.dracoOffset = r.offset;

  const where = `region ${header.regionId} (document version ${header.documentVersion})`;
  const expected = header.dracoBytes + 4;
  if (r.remaining < expected) {
    throw new Error(`${where}: truncated: the header announces ${header.dracoBytes} Draco bytes and a checksum, ${r.remaining} bytes follow`);
  }
  if (r.remaining > expected) throw new Error(`${where}: ${r.remaining - expected} trailing bytes after the checksum`);
  const end = bytes.length - 4;
  const stored = new DataView(bytes.buffer, bytes.byteOffset + end, 4).getUint32(0, true);
  const computed = crc32(bytes, 0, end);
  if (stored !== computed) {
    throw new Error(`${where}: checksum mismatch (stored ${hex32(stored)}, computed ${hex32(computed)}): the bytes are corrupted`);
  }
  if (header.layoutVersion > header.documentVersion) throw new Error(`${where}: layout version ${header.layoutVersion} is later than the document's`);
  if (header.triangles === 0) throw new Error(`${where}: no triangles`);
  if (header.profile.fidelity > 1) throw new Error(`${where}: LOD fidelity flag ${header.profile.fidelity} is not 0 or 1`);
  if (header.frame) {
    const f = header.frame;
    const face = `f${f.level}:${f.index}`;
    if (packId(f.level, f.index) !== header.regionId) {
      throw new Error(`${where}: the frame names face ${face}, not the region's face ${idName(header.regionId, 'f')}`);
    }
    if (f.forward >> f.sides) {
      throw new Error(`${where}: the frame's edge directions ${f.forward} set bits beyond the ${f.sides} edges of ${face}`);
    }
    // Below the base level every face is a quad with children 4f..4f+3; only
    // a base face's first child depends on the faces before it.
    if (f.sides === 4 && f.level >= 1 && f.firstChild !== 4 * f.index) {
      throw new Error(`${where}: the frame's first child ${f.firstChild} is not 4 x ${f.index}, ` +
        `as ${face} is below the base level`);
    }
    header.latticeDepth = header.profile.maxLevel - f.level;
  }
  return header;
}

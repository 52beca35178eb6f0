// One region payload (docs/PROTOCOL.md 6.2) to the arrays the scene and the
// hash use: float32 positions exactly as Draco dequantizes them, unit
// normals, triangle indices, and the vertex ids as uint32 halves (8-byte ids
// under flag 0, lattice points turned into ids under flag 4 for a triangle's
// lattice and flag 8 for a quad's, none under flags 1 and 2). The reference
// decoder is decodeRegion() in core/tessellation/region_codec.cc.
import { decodeMeshoptPayload } from './meshopt_region.js';
import { parseRegion } from './region_header.js';
import { RegionLattice } from './region_lattice.js';

// Copies one attribute of every point out of the module's heap.
function attributeArray(draco, decoder, mesh, attribute, dataType, ArrayType, components) {
  const count = mesh.num_points() * components;
  const byteLength = count * ArrayType.BYTES_PER_ELEMENT;
  const ptr = draco._malloc(byteLength);
  try {
    if (!decoder.GetAttributeDataArrayForAllPoints(mesh, attribute, dataType, byteLength, ptr)) {
      throw new Error('Draco could not read an attribute');
    }
    return new ArrayType(draco.HEAPF32.buffer, ptr, count).slice();
  } finally {
    draco._free(ptr);
  }
}

function findAttribute(decoder, mesh, type, name, components, where) {
  const id = decoder.GetAttributeId(mesh, type);
  if (id < 0) throw new Error(`${where}: no ${name} attribute`);
  const attribute = decoder.GetAttribute(mesh, id);
  if (attribute.num_components() !== components) {
    throw new Error(`${where}: ${name} has ${attribute.num_components()} components, expected ${components}`);
  }
  return attribute;
}

// Decodes `bytes` (a Uint8Array) with the draco3d module, or a meshopt
// region ("TSRM") with `meshopt`, the meshoptimizer decoder
// (meshopt_region.js). Throws an Error naming the region and the reason. A
// payload without its layout's ids (flag 2) decodes with ids null;
// session/document_view.js adopts the held ones.
export function decodeRegion(draco, bytes, meshopt = null) {
  const header = parseRegion(bytes);
  const where = `region ${header.regionId} (document version ${header.documentVersion})`;
  // The frame says whether the lattice is a triangle's or a quad's.
  const lattice = header.frame ? new RegionLattice(header.frame, header.latticeDepth) : null;
  if (header.codec === 'meshopt') {
    if (!meshopt) throw new Error(`${where}: a meshopt region, and this decoder has no meshopt module`);
    return decodeMeshoptPayload(meshopt, bytes, header, lattice);
  }
  const decoder = new draco.Decoder();
  const mesh = new draco.Mesh();
  try {
    const payload = bytes.subarray(header.dracoOffset, header.dracoOffset + header.dracoBytes);
    const status = decoder.DecodeArrayToMesh(payload, payload.length, mesh);
    if (!status.ok() || mesh.ptr === 0) throw new Error(`${where}: Draco rejected the payload: ${status.error_msg()}`);
    const points = mesh.num_points(), faces = mesh.num_faces();
    const withIds = header.hasIds && header.idsInline;
    const attributes = withIds ? 3 : 2;
    if (faces !== header.triangles || points > 3 * faces || mesh.num_attributes() !== attributes) {
      throw new Error(`${where}: Draco decoded ${faces} faces, ${points} points and ${mesh.num_attributes()} attributes; ` +
        `expected ${header.triangles} faces and ${attributes} attributes`);
    }
    const positions = attributeArray(draco, decoder, mesh, findAttribute(decoder, mesh, draco.POSITION, 'POSITION', 3, where),
      draco.DT_FLOAT32, Float32Array, 3);
    const normals = attributeArray(draco, decoder, mesh, findAttribute(decoder, mesh, draco.NORMAL, 'NORMAL', 3, where),
      draco.DT_FLOAT32, Float32Array, 3);
    for (let i = 0; i < normals.length; i += 3) {
      const length = Math.hypot(normals[i], normals[i + 1], normals[i + 2]);
      if (!(length > 0.5)) throw new Error(`${where}: point ${i / 3} has no unit normal`);
      normals[i] /= length;
      normals[i + 1] /= length;
      normals[i + 2] /= length;
    }
    let idHi = null, idLo = null;
    if (withIds) {
      const components = lattice ? 2 : 8;
      const raw = attributeArray(draco, decoder, mesh, findAttribute(decoder, mesh, draco.GENERIC, 'GENERIC (vertex ids)', components, where),
        draco.DT_UINT8, Uint8Array, components);
      idHi = new Uint32Array(points);
      idLo = new Uint32Array(points);
      for (let p = 0; p < points; ++p) {
        if (lattice) {
          try {
            [idHi[p], idLo[p]] = lattice.idHalvesAt(raw[2 * p], raw[2 * p + 1]);
          } catch (error) {
            throw new Error(`${where}: point ${p}: ${error.message}`);
          }
        } else {
          const b = 8 * p;
          idLo[p] = (raw[b] | (raw[b + 1] << 8) | (raw[b + 2] << 16) | (raw[b + 3] << 24)) >>> 0;
          idHi[p] = (raw[b + 4] | (raw[b + 5] << 8) | (raw[b + 6] << 16) | (raw[b + 7] << 24)) >>> 0;
        }
      }
    }
    const indices = new Uint32Array(faces * 3);
    const byteLength = indices.byteLength;
    const ptr = draco._malloc(byteLength);
    try {
      decoder.GetTrianglesUInt32Array(mesh, byteLength, ptr);
      indices.set(new Uint32Array(draco.HEAPF32.buffer, ptr, faces * 3));
    } finally {
      draco._free(ptr);
    }
    for (let i = 0; i < indices.length; ++i) {
      if (indices[i] >= points) throw new Error(`${where}: face ${Math.floor(i / 3)} uses a point beyond ${points}`);
    }
    return { header, positions, normals, indices, idHi, idLo, bytes: bytes.length };
  } finally {
    draco.destroy(mesh);
    draco.destroy(decoder);
  }
}

// Flag 2: gives `decoded` the ids of `held`, the copy of the same region at
// layout `heldLayout`, when the decoded triangles equal the held ones index
// for index (Draco then decoded the same order). Throws otherwise: the
// caller resubscribes (adoptLayoutIds() in region_codec.h).
export function adoptLayoutIds(decoded, held, heldLayout) {
  const where = `region ${decoded.header.regionId} (document version ${decoded.header.documentVersion})`;
  if (decoded.header.idsInline || !decoded.header.hasIds) throw new Error(`${where}: the payload has no layout ids to adopt`);
  if (!held) throw new Error(`${where}: comes without its ids, and this view does not hold it`);
  if (heldLayout !== decoded.header.layoutVersion) {
    throw new Error(`${where}: its ids are those of layout ${decoded.header.layoutVersion}, the view holds layout ${heldLayout}`);
  }
  const a = decoded.indices, b = held.indices;
  let same = a.length === b.length && held.idHi !== null && held.idHi.length === decoded.positions.length / 3;
  for (let i = 0; same && i < a.length; ++i) same = a[i] === b[i];
  if (!same) throw new Error(`${where}: its triangles differ from those of the held layout ${heldLayout}`);
  decoded.idHi = held.idHi;
  decoded.idLo = held.idLo;
}

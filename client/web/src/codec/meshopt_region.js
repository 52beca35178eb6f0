// The payload of a meshopt region ("TSRM", docs/REGION_ENCODING.md
// "meshopt regions") to the arrays decodeRegion() returns for Draco ones:
// float32 positions exactly as Draco would dequantize them (so both codecs
// give the same floats and the same surface hash), unit normals, triangle
// indices and the vertex ids as uint32 halves. The reference decoder is
// decodeMeshoptPayload() in core/tessellation/region_meshopt.cc; the
// streams are decoded by the meshoptimizer package's decoder (its
// WebAssembly is inside the module: nothing to fetch).
import { MeshoptDecoder } from 'meshoptimizer/meshopt_decoder.module.js';

const VERTEX_HEADER = 0xa0; // vertex codec version 0
const INDEX_HEADER = 0xe1; // index codec version 1
const MAX_NORMAL_BITS = 16;

// Resolves once the decoder's WebAssembly is instantiated.
export function loadMeshopt() {
  return MeshoptDecoder.ready.then(() => MeshoptDecoder);
}

function octahedral(qx, qy, max) {
  let x = (qx / max) * 2 - 1, y = (qy / max) * 2 - 1;
  const z = 1 - Math.abs(x) - Math.abs(y);
  if (z < 0) {
    const fx = (1 - Math.abs(y)) * (x < 0 ? -1 : 1), fy = (1 - Math.abs(x)) * (y < 0 ? -1 : 1);
    x = fx;
    y = fy;
  }
  const length = Math.hypot(x, y, z);
  return [x / length, y / length, z / length];
}

// `header` from parseRegion; `lattice` a RegionLattice when the ids travel
// as lattice points. Throws an Error naming the region and the reason.
export function decodeMeshoptPayload(decoder, bytes, header, lattice) {
  const where = `region ${header.regionId} (document version ${header.documentVersion}): meshopt payload`;
  const payload = bytes.subarray(header.dracoOffset, header.dracoOffset + header.dracoBytes);
  if (payload.length < 8) throw new Error(`${where}: truncated`);
  const view = new DataView(payload.buffer, payload.byteOffset, payload.length);
  const n = view.getUint32(0, true), vertexSize = view.getUint32(4, true);
  const triangles = header.triangles;
  if (n === 0 || n > 3 * triangles) throw new Error(`${where}: ${n} vertices for ${triangles} triangles (1 to 3 per triangle)`);
  if (vertexSize < 1 || vertexSize >= payload.length - 8) throw new Error(`${where}: a vertex buffer of ${vertexSize} bytes does not fit`);
  const vertexBytes = payload.subarray(8, 8 + vertexSize), indexBytes = payload.subarray(8 + vertexSize);
  if (vertexBytes[0] !== VERTEX_HEADER || indexBytes[0] !== INDEX_HEADER) {
    throw new Error(`${where}: stream versions ${vertexBytes[0]} and ${indexBytes[0]}, expected ${VERTEX_HEADER} and ${INDEX_HEADER}`);
  }
  if (triangles > indexBytes.length) throw new Error(`${where}: ${triangles} triangles in an index buffer of ${indexBytes.length} bytes`);
  const { positionBits, normalBits } = header.grid;
  if (normalBits > MAX_NORMAL_BITS) throw new Error(`${where}: ${normalBits} normal bits, at most ${MAX_NORMAL_BITS}`);
  const withIds = header.hasIds && header.idsInline;
  const stride = 16 + (withIds ? (lattice ? 4 : 8) : 0);
  const vertices = new Uint8Array(n * stride);
  const indices = new Uint32Array(triangles * 3);
  try {
    decoder.decodeVertexBuffer(vertices, n, stride, vertexBytes);
    decoder.decodeIndexBuffer(new Uint8Array(indices.buffer), indices.length, 4, indexBytes);
  } catch (error) {
    throw new Error(`${where}: ${error?.message ?? String(error)}`);
  }
  // Draco's Dequantizer (float32 throughout): delta = range / max, x = q * delta + origin.
  const f = Math.fround;
  const maxQ = 2 ** positionBits - 1;
  const delta = f(f(header.grid.range) / f(maxQ));
  const origin = header.grid.origin.map(f);
  const maxOct = 2 ** normalBits - 2; // an even count of steps: 0 is one
  const data = new DataView(vertices.buffer);
  const positions = new Float32Array(n * 3), normals = new Float32Array(n * 3);
  const idHi = withIds ? new Uint32Array(n) : null, idLo = withIds ? new Uint32Array(n) : null;
  for (let i = 0; i < n; ++i) {
    const at = i * stride;
    for (let k = 0; k < 3; ++k) {
      const q = data.getUint32(at + 4 * k, true);
      if (q > maxQ) throw new Error(`${where}: vertex ${i} lies outside the grid`);
      positions[3 * i + k] = f(f(q * delta) + origin[k]);
    }
    const ox = data.getUint16(at + 12, true), oy = data.getUint16(at + 14, true);
    if (ox > maxOct || oy > maxOct) throw new Error(`${where}: vertex ${i} has a normal outside its ${normalBits} bits`);
    normals.set(octahedral(ox, oy, maxOct), 3 * i);
    if (!withIds) continue;
    if (lattice) {
      try {
        [idHi[i], idLo[i]] = lattice.idHalvesAt(data.getUint16(at + 16, true), data.getUint16(at + 18, true));
      } catch (error) {
        throw new Error(`${where}: vertex ${i}: ${error.message}`);
      }
    } else {
      idLo[i] = data.getUint32(at + 16, true);
      idHi[i] = data.getUint32(at + 20, true);
    }
  }
  for (let t = 0; t < triangles; ++t) {
    const a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
    if (a >= n || b >= n || c >= n) throw new Error(`${where}: triangle ${t} uses a vertex beyond ${n}`);
    if (a === b || b === c || c === a) throw new Error(`${where}: triangle ${t} repeats a vertex`);
  }
  return { header, positions, normals, indices, idHi, idLo, bytes: bytes.length };
}

#include "core/tessellation/region_meshopt.h"

#include <draco/core/quantization_utils.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <mutex>
#include <vector>

#include "core/hierarchy/ids.h"
#include "core/util/byte_io.h"

namespace tessera::region_detail {
namespace {

// The first byte of each meshopt stream names its format: 0xa0 | version
// for vertex buffers, 0xe0 | version for index buffers (meshoptimizer's
// vertexcodec.cpp and indexcodec.cpp). The payload uses vertex version 0
// and index version 1 (smaller than 0: it codes a vertex index that repeats
// a recent one in fewer bytes), which every decoder since 0.14 reads (the
// npm decoder too). Debian's 0.18 writes index version 0 unless told.
constexpr uint8_t kVertexHeader = 0xa0;
constexpr uint8_t kIndexHeader = 0xe1;
constexpr size_t kPayloadPrefixBytes = 8;  // vertex count, vertex buffer size

// meshopt_encodeIndexVersion sets a process-wide value: set once, before
// the first encoding, never changed after.
void useIndexVersion1() {
  static std::once_flag once;
  std::call_once(once, [] { meshopt_encodeIndexVersion(1); });
}

size_t idBytes(IdCoding coding) {
  return coding == IdCoding::kBytes ? 8 : coding == IdCoding::kLattice ? 4 : 0;
}
size_t vertexBytes(IdCoding coding) {
  return 12 + 4 + idBytes(coding);
}

double signOf(double v) {
  return v < 0 ? -1.0 : 1.0;
}

// Octahedral normals (Meyer et al., "On Floating-Point Normal Vectors",
// EGSR 2010): the unit vector projected on the octahedron |x|+|y|+|z| = 1,
// its lower half folded over the upper, (x, y) in [-1, 1]^2 on 2^bits - 2
// steps, as Draco counts them: an even count puts 0, the poles' and the
// equator's coordinate, on a step.
std::array<uint16_t, 2> encodeOctahedral(const Vec3& normal, int bits) {
  const Vec3 n = normal.normalized();
  const double s = std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]);
  double x = n[0] / s, y = n[1] / s;
  if (n[2] < 0) {
    const double fx = (1.0 - std::fabs(y)) * signOf(x), fy = (1.0 - std::fabs(x)) * signOf(y);
    x = fx, y = fy;
  }
  const double max = static_cast<double>((1u << bits) - 2);
  const auto q = [max](double v) {
    return static_cast<uint16_t>(std::clamp(std::round((v + 1.0) * 0.5 * max), 0.0, max));
  };
  return {q(x), q(y)};
}

Vec3 decodeOctahedral(uint16_t qx, uint16_t qy, int bits) {
  const double max = static_cast<double>((1u << bits) - 2);
  double x = qx / max * 2.0 - 1.0, y = qy / max * 2.0 - 1.0;
  const double z = 1.0 - std::fabs(x) - std::fabs(y);
  if (z < 0) {
    const double fx = (1.0 - std::fabs(y)) * signOf(x), fy = (1.0 - std::fabs(x)) * signOf(y);
    x = fx, y = fy;
  }
  return Vec3(x, y, z).normalized();
}

template <typename T>
void store(unsigned char* at, T value) {
  std::memcpy(at, &value, sizeof(T));
}
template <typename T>
T load(const unsigned char* at) {
  T value;
  std::memcpy(&value, at, sizeof(T));
  return value;
}

}  // namespace

Expected<std::string> encodeMeshoptPayload(const RegionMesh& mesh, IdCoding coding,
                                           const RegionLattice* lattice, const QuantizationGrid& grid,
                                           const std::string& where) {
  if (grid.normalBits > kMaxMeshoptNormalBits) {
    return invalidArgument(where + ": " + std::to_string(grid.normalBits) +
                           " normal bits; the meshopt codec takes at most " +
                           std::to_string(kMaxMeshoptNormalBits));
  }
  useIndexVersion1();
  const size_t n = mesh.positions.size(), stride = vertexBytes(coding);
  // Draco's AttributeQuantizationTransform, as regionSurfaceHashOnGrid
  // (surface_hash.cc) applies it: the float32 position minus the float32
  // origin, rounded by Draco's Quantizer. Decoded with Draco's Dequantizer,
  // both codecs give the same floats.
  const float range = static_cast<float>(grid.range);
  const int32_t maxQuantized = static_cast<int32_t>((uint32_t{1} << grid.positionBits) - 1);
  draco::Quantizer quantizer;
  quantizer.Init(range, maxQuantized);
  const std::array<float, 3> origin{static_cast<float>(grid.origin[0]), static_cast<float>(grid.origin[1]),
                                    static_cast<float>(grid.origin[2])};
  std::vector<unsigned char> vertices(n * stride);
  for (size_t i = 0; i < n; ++i) {
    unsigned char* v = vertices.data() + i * stride;
    for (int k = 0; k < 3; ++k) {
      const int32_t q = quantizer.QuantizeFloat(static_cast<float>(mesh.positions[i][k]) - origin[k]);
      store<uint32_t>(v + 4 * k, static_cast<uint32_t>(std::clamp(q, 0, maxQuantized)));
    }
    const auto oct = encodeOctahedral(mesh.normals[i], grid.normalBits);
    store<uint16_t>(v + 12, oct[0]);
    store<uint16_t>(v + 14, oct[1]);
    if (coding == IdCoding::kBytes) {
      store<uint64_t>(v + 16, mesh.vertexIds[i]);
    } else if (coding == IdCoding::kLattice) {
      const auto point = lattice->pointOf(VertexId::fromPacked(mesh.vertexIds[i]));
      if (!point) {
        return invalidMesh(where + ": vertex " + std::to_string(i) + " (" +
                           VertexId::fromPacked(mesh.vertexIds[i]).toString() +
                           ") is not a vertex of the region's root face");
      }
      store<uint16_t>(v + 16, static_cast<uint16_t>((*point)[0]));
      store<uint16_t>(v + 18, static_cast<uint16_t>((*point)[1]));
    }
  }
  std::vector<unsigned int> indices;
  indices.reserve(mesh.triangles.size() * 3);
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) indices.push_back(static_cast<unsigned int>(t[c]));

  // Triangles in vertex cache order, then vertices in the order of first
  // use, which the index codec codes best; every vertex's bytes move as one.
  meshopt_optimizeVertexCache(indices.data(), indices.data(), indices.size(), n);
  std::vector<unsigned int> remap(n);
  const size_t used = meshopt_optimizeVertexFetchRemap(remap.data(), indices.data(), indices.size(), n);
  if (used != n)
    return internalError(where + ": " + std::to_string(n - used) + " vertices used by no triangle");
  meshopt_remapIndexBuffer(indices.data(), indices.data(), indices.size(), remap.data());
  meshopt_remapVertexBuffer(vertices.data(), vertices.data(), n, stride, remap.data());

  std::string out(kPayloadPrefixBytes + meshopt_encodeVertexBufferBound(n, stride) +
                      meshopt_encodeIndexBufferBound(indices.size(), n),
                  '\0');
  auto* bytes = reinterpret_cast<unsigned char*>(out.data());
  const size_t vertexSize = meshopt_encodeVertexBuffer(
      bytes + kPayloadPrefixBytes, meshopt_encodeVertexBufferBound(n, stride), vertices.data(), n, stride);
  if (vertexSize == 0) return internalError(where + ": meshopt_encodeVertexBuffer failed");
  unsigned char* indexAt = bytes + kPayloadPrefixBytes + vertexSize;
  const size_t indexSize = meshopt_encodeIndexBuffer(
      indexAt, meshopt_encodeIndexBufferBound(indices.size(), n), indices.data(), indices.size());
  if (indexSize == 0) return internalError(where + ": meshopt_encodeIndexBuffer failed");
  if (bytes[kPayloadPrefixBytes] != kVertexHeader || indexAt[0] != kIndexHeader) {
    return internalError(where + ": this meshoptimizer writes stream versions this decoder does not read");
  }
  store<uint32_t>(bytes, static_cast<uint32_t>(n));
  store<uint32_t>(bytes + 4, static_cast<uint32_t>(vertexSize));
  out.resize(kPayloadPrefixBytes + vertexSize + indexSize);
  return out;
}

Expected<RegionMesh> decodeMeshoptPayload(std::string_view payload, const QuantizationGrid& grid,
                                          bool withIds, uint32_t triangles, const RegionLattice* lattice,
                                          const std::string& where) {
  const std::string source = where + ": meshopt payload";
  if (grid.normalBits > kMaxMeshoptNormalBits) {
    return parseError(source + ": " + std::to_string(grid.normalBits) + " normal bits, at most " +
                      std::to_string(kMaxMeshoptNormalBits));
  }
  ByteReader r(payload.data(), payload.size(), source);
  uint32_t n = 0, vertexSize = 0;
  TESSERA_RETURN_IF_ERROR(r.get(n, "the vertex count"));
  TESSERA_RETURN_IF_ERROR(r.get(vertexSize, "the vertex buffer size"));
  if (n == 0 || n > 3 * static_cast<uint64_t>(triangles)) {
    return parseError(source + ": " + std::to_string(n) + " vertices for " + std::to_string(triangles) +
                      " triangles (1 to 3 per triangle)");
  }
  if (vertexSize < 1 || vertexSize >= r.remaining()) {
    return parseError(source + ": a vertex buffer of " + std::to_string(vertexSize) + " bytes in the " +
                      std::to_string(r.remaining()) + " that follow, with an index buffer after it");
  }
  const auto* bytes = reinterpret_cast<const unsigned char*>(payload.data());
  const unsigned char* vertexAt = bytes + kPayloadPrefixBytes;
  const unsigned char* indexAt = vertexAt + vertexSize;
  const size_t indexSize = payload.size() - kPayloadPrefixBytes - vertexSize;
  if (vertexAt[0] != kVertexHeader || indexAt[0] != kIndexHeader) {
    return parseError(source + ": stream versions " + std::to_string(vertexAt[0]) + " and " +
                      std::to_string(indexAt[0]) + ", expected " + std::to_string(kVertexHeader) + " and " +
                      std::to_string(kIndexHeader));
  }
  // The index codec spends at least one byte per triangle (its code
  // table), so the payload bounds the allocations below.
  if (triangles > indexSize) {
    return parseError(source + ": " + std::to_string(triangles) + " triangles in an index buffer of " +
                      std::to_string(indexSize) + " bytes");
  }
  const IdCoding coding = !withIds ? IdCoding::kNone : lattice ? IdCoding::kLattice : IdCoding::kBytes;
  const size_t stride = vertexBytes(coding);
  std::vector<unsigned char> vertices(static_cast<size_t>(n) * stride);
  if (const int rc = meshopt_decodeVertexBuffer(vertices.data(), n, stride, vertexAt, vertexSize); rc != 0) {
    return parseError(source + ": the vertex buffer does not decode (meshopt error " + std::to_string(rc) +
                      ")");
  }
  std::vector<unsigned int> indices(static_cast<size_t>(triangles) * 3);
  if (const int rc =
          meshopt_decodeIndexBuffer(indices.data(), indices.size(), sizeof(unsigned int), indexAt, indexSize);
      rc != 0) {
    return parseError(source + ": the index buffer does not decode (meshopt error " + std::to_string(rc) +
                      ")");
  }

  const float range = static_cast<float>(grid.range);
  const int32_t maxQuantized = static_cast<int32_t>((uint32_t{1} << grid.positionBits) - 1);
  draco::Dequantizer dequantizer;
  if (!dequantizer.Init(range, maxQuantized)) return parseError(source + ": unusable quantization range");
  const std::array<float, 3> origin{static_cast<float>(grid.origin[0]), static_cast<float>(grid.origin[1]),
                                    static_cast<float>(grid.origin[2])};
  RegionMesh out;
  out.positions.resize(n);
  out.normals.resize(n);
  if (withIds) out.vertexIds.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    const unsigned char* v = vertices.data() + static_cast<size_t>(i) * stride;
    for (int k = 0; k < 3; ++k) {
      const uint32_t q = load<uint32_t>(v + 4 * k);
      if (q > static_cast<uint32_t>(maxQuantized))
        return parseError(source + ": vertex " + std::to_string(i) + " lies outside the grid");
      // Draco's Dequantizer and float addition, as decodeDracoPayload.
      const float value = dequantizer.DequantizeFloat(static_cast<int32_t>(q));
      out.positions[i][k] = value + origin[k];
    }
    const uint16_t ox = load<uint16_t>(v + 12), oy = load<uint16_t>(v + 14);
    const uint32_t maxOct = (1u << grid.normalBits) - 2;
    if (ox > maxOct || oy > maxOct)
      return parseError(source + ": vertex " + std::to_string(i) + " has a normal outside its " +
                        std::to_string(grid.normalBits) + " bits");
    out.normals[i] = decodeOctahedral(ox, oy, grid.normalBits);
    if (coding == IdCoding::kBytes) {
      out.vertexIds[i] = load<uint64_t>(v + 16);
    } else if (coding == IdCoding::kLattice) {
      const int u = load<uint16_t>(v + 16), w = load<uint16_t>(v + 18);
      const auto at = lattice->idAt(u, w);
      if (!at) {
        return parseError(source + ": vertex " + std::to_string(i) + " has lattice point (" +
                          std::to_string(u) + ", " + std::to_string(w) +
                          "), outside the root face's lattice of side " + std::to_string(lattice->side()));
      }
      out.vertexIds[i] = at->packed();
    }
  }
  out.triangles.resize(triangles);
  for (uint32_t f = 0; f < triangles; ++f) {
    for (int c = 0; c < 3; ++c) {
      const unsigned int index = indices[3 * f + c];
      if (index >= n) {
        return parseError(source + ": triangle " + std::to_string(f) + " uses vertex " +
                          std::to_string(index) + " of " + std::to_string(n));
      }
      out.triangles[f][c] = static_cast<int>(index);
    }
    const auto& t = out.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      return parseError(source + ": triangle " + std::to_string(f) + " repeats a vertex");
  }
  // encodeRegion writes no vertex that no triangle uses (its mesh rules), so
  // such a vertex is a forged or corrupted count: the vertex codec can decode
  // V + 1 vertices from a stream of V without complaint (docs/FUZZING.md,
  // the region_meshopt target).
  std::vector<char> used(n, 0);
  for (const auto& t : out.triangles)
    for (int c : t) used[static_cast<size_t>(c)] = 1;
  if (const auto unused = std::find(used.begin(), used.end(), 0); unused != used.end()) {
    return parseError(source + ": vertex " + std::to_string(unused - used.begin()) + " of " +
                      std::to_string(n) + " is used by no triangle");
  }
  return out;
}

}  // namespace tessera::region_detail

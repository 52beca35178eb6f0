#include "core/tessellation/surface_hash.h"

#include <draco/core/quantization_utils.h>

#include <bit>
#include <vector>

#include "core/util/fnv1a.h"

namespace tessera {
namespace {

// -0.0 and +0.0 are the same coordinate; a decoder may produce either.
uint32_t coordinateBits(float value) {
  return value == 0.0f ? 0u : std::bit_cast<uint32_t>(value);
}

using CornerKey = std::array<uint64_t, 4>;  // id, then the bits of x, y, z

CornerKey keyOf(const HashedCorner& c) {
  return {c.id, coordinateBits(c.position[0]), coordinateBits(c.position[1]), coordinateBits(c.position[2])};
}

void mixLittleEndian(uint64_t& h, uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) h = fnv1aByte(h, static_cast<uint8_t>(value >> (8 * i)));
}

template <typename Position>
uint64_t sumOverTriangles(const RegionMesh& mesh, bool withIds, Position&& position) {
  uint64_t sum = 0;
  for (const auto& t : mesh.triangles) {
    std::array<HashedCorner, 3> corners;
    for (int k = 0; k < 3; ++k) {
      corners[k].id = withIds ? mesh.vertexIds[t[k]] : 0;
      corners[k].position = position(t[k]);
    }
    sum += triangleHash(corners);
  }
  return sum;
}

}  // namespace

uint64_t triangleHash(const std::array<HashedCorner, 3>& corners) {
  const std::array<CornerKey, 3> keys{keyOf(corners[0]), keyOf(corners[1]), keyOf(corners[2])};
  // The rotation (orientation kept) whose key sequence is smallest.
  int first = 0;
  for (int r = 1; r < 3; ++r) {
    const std::array<CornerKey, 3> candidate{keys[r], keys[(r + 1) % 3], keys[(r + 2) % 3]};
    const std::array<CornerKey, 3> best{keys[first], keys[(first + 1) % 3], keys[(first + 2) % 3]};
    if (candidate < best) first = r;
  }
  uint64_t h = kFnv1aOffsetBasis;
  for (int k = 0; k < 3; ++k) {
    const CornerKey& key = keys[(first + k) % 3];
    mixLittleEndian(h, key[0], 8);
    for (int c = 1; c < 4; ++c) mixLittleEndian(h, key[c], 4);
  }
  return h;
}

uint64_t regionSurfaceHash(const RegionMesh& decoded) {
  const bool withIds = !decoded.vertexIds.empty();
  return sumOverTriangles(decoded, withIds, [&](int v) {
    const Vec3& p = decoded.positions[v];
    return std::array<float, 3>{static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])};
  });
}

uint64_t regionSurfaceHashOnGrid(const RegionMesh& mesh, const QuantizationGrid& grid, bool withIds) {
  // Draco's AttributeQuantizationTransform: the float32 position minus the
  // float32 origin, scaled and rounded by its Quantizer; the decoder's
  // Dequantizer plus the origin (region_draco.cc decodeDracoPayload).
  const float range = static_cast<float>(grid.range);
  const int32_t maxQuantized = static_cast<int32_t>((uint32_t{1} << grid.positionBits) - 1);
  draco::Quantizer quantizer;
  quantizer.Init(range, maxQuantized);
  draco::Dequantizer dequantizer;
  dequantizer.Init(range, maxQuantized);
  const std::array<float, 3> origin{static_cast<float>(grid.origin[0]), static_cast<float>(grid.origin[1]),
                                    static_cast<float>(grid.origin[2])};
  std::vector<std::array<float, 3>> decoded(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const float value = static_cast<float>(mesh.positions[i][k]) - origin[k];
      decoded[i][k] = dequantizer.DequantizeFloat(quantizer.QuantizeFloat(value)) + origin[k];
    }
  }
  return sumOverTriangles(mesh, withIds && !mesh.vertexIds.empty(), [&](int v) { return decoded[v]; });
}

uint64_t surfaceHash(const std::map<uint64_t, RegionMesh>& decodedRegions) {
  uint64_t sum = 0;
  for (const auto& [id, mesh] : decodedRegions) sum += regionSurfaceHash(mesh);
  return sum;
}

}  // namespace tessera

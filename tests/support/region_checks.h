// Region comparisons shared by the tessellation and region codec suites.
#pragma once

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <set>
#include <string>

#include "core/hierarchy/ids.h"
#include "core/tessellation/tessellation.h"

namespace tessera::testing {

// `actual` holds what `expected` holds: the same regions, and in each the
// same ids, triangles, and positions and normals bit for bit (memcmp, so
// -0.0 and 0.0 differ); the message names the first vertex that differs.
inline void expectSameRegions(const Tessellation& actual, const Tessellation& expected,
                              const std::string& where) {
  ASSERT_EQ(actual.regions().size(), expected.regions().size()) << where;
  for (const auto& [id, region] : expected.regions()) {
    ASSERT_EQ(actual.regions().count(id), 1u) << where << " region " << id;
    const RegionMesh& kept = actual.regions().at(id);
    ASSERT_EQ(kept.vertexIds, region.vertexIds) << where << " region " << id;
    ASSERT_EQ(kept.triangles, region.triangles) << where << " region " << id;
    ASSERT_EQ(kept.positions.size(), region.positions.size()) << where << " region " << id;
    ASSERT_EQ(kept.normals.size(), region.normals.size()) << where << " region " << id;
    for (size_t i = 0; i < region.positions.size(); ++i) {
      const std::string vertex = VertexId::fromPacked(region.vertexIds[i]).toString();
      ASSERT_EQ(std::memcmp(&kept.positions[i], &region.positions[i], sizeof(Vec3)), 0)
          << where << " region " << id << " vertex " << vertex << " position " << kept.positions[i][0] << " "
          << kept.positions[i][1] << " " << kept.positions[i][2] << " vs " << region.positions[i][0] << " "
          << region.positions[i][1] << " " << region.positions[i][2];
      ASSERT_EQ(std::memcmp(&kept.normals[i], &region.normals[i], sizeof(Vec3)), 0)
          << where << " region " << id << " vertex " << vertex << " normal";
    }
  }
}

using TriangleKey = std::array<uint64_t, 3>;

// A region's triangles over ids, each rotated to start at its smallest id:
// orientation is kept, the starting corner (which Draco may change) is not.
inline std::multiset<TriangleKey> trianglesOverIds(const RegionMesh& m) {
  std::multiset<TriangleKey> keys;
  for (const auto& t : m.triangles) {
    TriangleKey key{m.vertexIds[t[0]], m.vertexIds[t[1]], m.vertexIds[t[2]]};
    std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
    keys.insert(key);
  }
  return keys;
}

// Rewrites an encoded region's CRC-32 trailer after a test changed bytes
// before it, so that the decoder looks past the checksum.
inline void refreshRegionChecksum(std::string& bytes) {
  const uint32_t crc = static_cast<uint32_t>(
      ::crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size() - 4)));
  std::memcpy(bytes.data() + bytes.size() - 4, &crc, 4);
}

}  // namespace tessera::testing

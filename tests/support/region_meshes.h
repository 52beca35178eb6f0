// Regions the region codec suites encode (region_codec_test.cc,
// region_meshopt_test.cc): a smooth closed surface with real ids, and a
// non-manifold, disconnected one (docs/REGION_ENCODING.md).
#pragma once

#include <gtest/gtest.h>

#include <cstddef>

#include "core/hierarchy/ids.h"
#include "core/loop/loop_refiner.h"
#include "core/tessellation/region_codec.h"
#include "support/procedural_meshes.h"

namespace tessera::testing {

// The Loop limit surface of a jittered torus at level `levels`, each
// vertex's id that of the level-`levels` vertex it is the limit of. No
// creases: the limit surface has no split copies, one vertex per id.
inline RegionMesh torusLimitRegion(int levels) {
  const auto mesh = withJitter(torus(8, 6), 0.03, 11);
  auto refiner = LoopRefiner::create(mesh.topology, {}, {.levels = levels});
  EXPECT_TRUE(refiner.isOk()) << refiner.status().toString();
  auto limit = refiner->limitSurface(refiner->refinePoints(mesh.points));
  EXPECT_TRUE(limit.isOk()) << limit.status().toString();
  RegionMesh m{limit->positions, limit->normals, {}, limit->triangles};
  EXPECT_EQ(m.positions.size(), static_cast<size_t>(refiner->finestLevel().numVertices));
  for (size_t i = 0; i < m.positions.size(); ++i) m.vertexIds.push_back(VertexId(levels, i).packed());
  return m;
}

// A bow tie (two triangles sharing one vertex, which Draco's Edgebreaker
// splits) beside a lone triangle, in the plane z = 0 inside [-1, 3]^2, ids
// v0:100 to v0:107.
inline RegionMesh bowTieAndIsland() {
  RegionMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {2, 2, 0}, {3, 2, 0}, {2, 3, 0}};
  m.normals.assign(m.positions.size(), Vec3(0, 0, 1));
  for (size_t i = 0; i < m.positions.size(); ++i) m.vertexIds.push_back(VertexId(0, 100 + i).packed());
  m.triangles = {{0, 1, 2}, {0, 3, 4}, {5, 6, 7}};
  return m;
}

}  // namespace tessera::testing

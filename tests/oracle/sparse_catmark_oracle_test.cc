// Sparse Catmull-Clark levels against OpenSubdiv 3.5: levels that hold a
// random part of the uniform refinement, built at once and then grown in
// place (core/hierarchy/sparse_level.h), their points computed from the
// parent level alone (core/catmark/stencils.h), must equal Far's refined
// points (PrimvarRefinerReal<double>) at the vertex of the same canonical
// id, within 1e-12 of the bounding-box diagonal, and the limit position and
// normal of every complete vertex (core/catmark/limit.h) must equal Far's
// Limit() there, within 1e-9 of the diagonal and 1e-6 rad: on quads, triangles and
// n-gons, closed and open, a real polygon mesh from CGAL, random
// semi-sharp and infinitely sharp tags from fixed seeds, both crease
// methods and both boundary rules.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/catmark/limit.h"
#include "core/catmark/stencils.h"
#include "core/hierarchy/sparse_level.h"
#include "core/schemes/polygon_reader.h"
#include "core/schemes/quad_refiner.h"
#include "oracle/catmark_cases.h"
#include "oracle/osd_catmark_reference.h"
#include "support/polygon_meshes.h"
#include "support/sparse_levels.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using testing::PolyTestMesh;

using oracle::kNormalTolerance;
using oracle::kPointTolerance;
using oracle::kPositionTolerance;

// The points of every vertex of `child`, from its parent's.
std::vector<Vec3> childPoints(const SparseLevel& parent, const SparseLevel& child,
                              const std::vector<Vec3>& parentPoints, const LoopOptions& options) {
  CatmarkStencils stencils(parent.mesh, options);
  std::vector<Vec3> out(child.mesh.numVertices);
  for (Index v = 0; v < child.mesh.numVertices; ++v) {
    const Index o = child.origin[v];
    if (child.isVertexChild(v)) {
      out[v] = stencils.vertexChild(o, parentPoints);
    } else if (child.isFaceChild(v)) {
      out[v] = stencils.faceChild(o, parentPoints);
    } else {
      out[v] = stencils.edgeChild(o, parentPoints);
    }
  }
  return out;
}

struct Counted {
  long long points = 0, sparseLevels = 0, absentVertices = 0, limits = 0, normals = 0, degenerateNormals = 0,
            notLimits = 0;
};

void checkSparseAgainstOsd(const PolyTestMesh& mesh, const CreaseOptions& options, int levels, uint32_t seed,
                           Counted& counted) {
  SCOPED_TRACE(mesh.name + (options.creaseMethod == CreaseMethod::kChaikin ? " chaikin" : " uniform") +
               (options.boundary == BoundaryInterpolation::kEdgeOnly ? " edge-only" : " edge-and-corner"));
  auto refiner = schemes::QuadRefiner::create(mesh.topology, schemes::QuadScheme::kCatmullClark, options,
                                              {.levels = levels});
  ASSERT_TRUE(refiner.isOk()) << refiner.status().toString();
  // Limits from level 1 on, where every face is a quad.
  const auto osd = oracle::refineQuadsWithOpenSubdiv(mesh.topology, mesh.points, options, *refiner, true, 1);
  const double diag = oracle::boundingDiagonal(mesh.points);
  const LevelCounts counts = testing::quadCountsOf(refiner->level(0), levels);

  std::mt19937 rng(seed);
  std::vector<SparseLevel> sparse;
  sparse.push_back(sparseBaseLevel(refiner->level(0)));
  std::vector<Vec3> points = mesh.points;
  for (int l = 0; l < levels; ++l) {
    // Built from one random selection, then grown by a second.
    const std::vector<Index> first = testing::refinableFaces(sparse[l], 0.5, rng);
    if (first.empty()) break;
    Buffer<uint8_t> flags(sparse[l].mesh.numFaces(), 0);
    for (Index f : first) flags[f] = 1;
    sparse.push_back(refineSparse(sparse[l], flags, counts, options));
    const std::vector<Index> second = testing::refinableFaces(sparse[l], 0.5, rng);
    extendSparse(sparse[l], sparse[l + 1], second, counts, options);
    const SparseLevel& child = sparse[l + 1];
    std::vector<Vec3> next = childPoints(sparse[l], child, points, options);
    ASSERT_EQ(static_cast<int>(osd[l + 1].points.size()), refiner->level(l + 1).numVertices);
    for (Index v = 0; v < child.mesh.numVertices; ++v) {
      const uint64_t id = child.vertexIds[v];
      ASSERT_LE((next[v] - osd[l + 1].points[id]).norm(), kPointTolerance * diag)
          << "level " << l + 1 << " vertex v" << l + 1 << ":" << id;
    }
    for (Index v = 0; v < child.mesh.numVertices; ++v) {
      if (!child.isComplete(v)) continue;
      const uint64_t id = child.vertexIds[v];
      const CatmarkLimitFrame frame = catmarkLimitFrame(child.mesh, v, next, options);
      if (oracle::limitNormalDiffersFromFar(child.mesh, v, options)) {
        ++counted.notLimits;  // Limit() is not the surface here
        continue;
      }
      ASSERT_LE((frame.position - osd[l + 1].limitPositions[id]).norm(), kPositionTolerance * diag)
          << "limit at v" << l + 1 << ":" << id;
      ++counted.limits;
      const Vec3 osdNormal = osd[l + 1].limitTangent1[id] % osd[l + 1].limitTangent2[id];
      const double scale = osd[l + 1].limitTangent1[id].norm() * osd[l + 1].limitTangent2[id].norm();
      if (!(osdNormal.norm() > 1e-12 * scale)) {
        ++counted.degenerateNormals;  // parallel tangents: Limit() gives no normal
        continue;
      }
      const Vec3 normal = frame.tangent1 % frame.tangent2;
      ASSERT_LE(std::atan2((normal % osdNormal).norm(), normal | osdNormal), kNormalTolerance)
          << "normal at v" << l + 1 << ":" << id;
      ++counted.normals;
    }
    counted.points += child.mesh.numVertices;
    counted.absentVertices += refiner->level(l + 1).numVertices - child.mesh.numVertices;
    ++counted.sparseLevels;
    points = std::move(next);
  }
}

TEST(SparseCatmarkOracle, SparseLevelsEqualFarOnPolygonMeshesWithRandomTags) {
  using namespace testing;
  const std::vector<PolyTestMesh> shapes = catmarkShapes();
  Counted counted;
  uint32_t seed = 1;
  for (const PolyTestMesh& shape : shapes) {
    for (uint32_t tags : {0u, 1u, 2u}) {
      const PolyTestMesh mesh = tags == 0 ? shape : withRandomPolyTags(shape, 0.3, 0.1, tags);
      for (const CreaseOptions& options : oracle::allCreaseOptions())
        checkSparseAgainstOsd(mesh, options, 3, seed++, counted);
    }
  }
  // Sparse, not whole: the selections left vertices out at every level.
  EXPECT_GT(counted.absentVertices, 0);
  EXPECT_GE(counted.sparseLevels, 100);
  EXPECT_GT(counted.normals, 0);
  std::printf(
      "sparse levels %lld, points compared %lld, vertices not held %lld, limits %lld, normals %lld "
      "(parallel OpenSubdiv tangents skipped: %lld; darts and crease spans of 3+ faces left to the Bfr test: "
      "%lld)\n",
      counted.sparseLevels, counted.points, counted.absentVertices, counted.limits, counted.normals,
      counted.degenerateNormals, counted.notLimits);
}

TEST(SparseCatmarkOracle, RealPolygonMeshDoubleTorus) {
  auto mesh = schemes::importPolygonMesh(testing::cgalMeshPath("double-torus-example.off"), "");
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  const PolyTestMesh real{"double-torus-example", mesh->topology, mesh->points};
  Counted counted;
  checkSparseAgainstOsd(real, {}, 3, 5, counted);
  checkSparseAgainstOsd(testing::withRandomPolyTags(real, 0.2, 0.05, 5),
                        {CreaseMethod::kChaikin, BoundaryInterpolation::kEdgeOnly}, 3, 6, counted);
  EXPECT_EQ(counted.sparseLevels, 6);
  EXPECT_GT(counted.absentVertices, 0);
}

}  // namespace
}  // namespace tessera

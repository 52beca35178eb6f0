// Catmull-Clark documents (core/document/document.h, DocumentScheme::
// kCatmullClark) against OpenSubdiv 3.5. A document made through its public
// commands (plain moves and direct manipulation at every level, creases and
// corners at the base level, undo, redo and removal) must show, at every
// level, the points Far's PrimvarRefiner gives when each level's edits are
// added to its interpolated points before the next level is interpolated
// (Pulli & Lounsbery, "Hierarchical Editing and Rendering of Subdivision
// Surfaces" §2), within 1e-12 of the bounding-box diagonal, and Far's
// Limit() positions and normals within 1e-9 of the diagonal and 1e-6 rad.
// Both its evaluations are held to that: the from-scratch surface() and the
// incremental hierarchy.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "core/document/document.h"
#include "core/schemes/polygon_reader.h"
#include "core/schemes/quad_refiner.h"
#include "oracle/catmark_cases.h"
#include "oracle/osd_catmark_reference.h"
#include "support/polygon_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using testing::PolyTestMesh;

constexpr int kLevels = 3;
using oracle::kNormalTolerance;
using oracle::kPointTolerance;
using oracle::kPositionTolerance;

struct Counted {
  long long points = 0, limits = 0, normals = 0, heldPoints = 0, edits = 0, drags = 0, undos = 0;
};

double angleBetween(const Vec3& a, const Vec3& b) {
  return std::atan2((a % b).norm(), a | b);
}

// Far's normal, or none where its tangents are parallel.
std::optional<Vec3> farNormal(const oracle::OsdQuadLevel& far, size_t v) {
  const Vec3 n = far.limitTangent1[v] % far.limitTangent2[v];
  if (!(n.norm() > 1e-12 * far.limitTangent1[v].norm() * far.limitTangent2[v].norm())) return std::nullopt;
  return n;
}

// Every level's control points and limit surface, and every point the
// hierarchy holds, against Far.
void expectDocumentIsFar(const Document& doc, const PolyTestMesh& mesh, const schemes::QuadRefiner& ours,
                         double diag, const std::string& when, Counted& counted) {
  const auto far = oracle::refineEditedQuadsWithOpenSubdiv(mesh.topology, mesh.points, doc.options().loop,
                                                           ours, doc.edits());
  for (int l = 0; l <= kLevels; ++l) {
    auto control = doc.surface(l, SurfaceKind::kControl);
    ASSERT_TRUE(control.isOk()) << when << ": " << control.status().toString();
    ASSERT_EQ(control->positions.size(), far[l].points.size()) << when;
    ASSERT_EQ(control->numPolygons(), doc.counts().faces(l)) << when << " level " << l;
    for (size_t v = 0; v < far[l].points.size(); ++v) {
      ASSERT_LE((control->positions[v] - far[l].points[v]).norm(), kPointTolerance * diag)
          << when << ": point of v" << l << ":" << v;
      ++counted.points;
    }
    const SparseHierarchy& h = doc.hierarchy();
    for (Index v = 0; l < h.numLevels() && v < h.level(l).mesh.numVertices; ++v) {
      const uint64_t id = h.level(l).vertexIds[v];
      ASSERT_LE((h.points(l)[v] - far[l].points[id]).norm(), kPointTolerance * diag)
          << when << ": held point of v" << l << ":" << id;
      ++counted.heldPoints;
    }
    auto limit = doc.surface(l, SurfaceKind::kLimit);
    if (far[l].limitPositions.empty()) {
      // A base with other polygons than quads has no limit at level 0.
      ASSERT_FALSE(limit.isOk()) << when;
      EXPECT_NE(limit.status().message().find("level 0"), std::string::npos) << limit.status().message();
      continue;
    }
    ASSERT_TRUE(limit.isOk()) << when << ": " << limit.status().toString();
    // Limit() is not the surface at darts, nor its normal across a crease
    // into three faces or more (bfr_catmark_limit_test.cc holds those to Bfr).
    auto evaluation = doc.evaluate(l);
    ASSERT_TRUE(evaluation.isOk()) << when << ": " << evaluation.status().toString();
    const Level& topology = (*evaluation)->levels[l];
    for (size_t v = 0; v < far[l].limitPositions.size(); ++v) {
      if (oracle::limitPositionDiffersFromFar(topology, static_cast<Index>(v), doc.options().loop)) continue;
      ASSERT_LE((limit->positions[v] - far[l].limitPositions[v]).norm(), kPositionTolerance * diag)
          << when << ": limit of v" << l << ":" << v;
      ++counted.limits;
      const auto n = farNormal(far[l], v);
      if (!n || oracle::limitNormalDiffersFromFar(topology, static_cast<Index>(v), doc.options().loop))
        continue;
      ASSERT_LE(angleBetween(limit->normals[v], *n), kNormalTolerance)
          << when << ": normal of v" << l << ":" << v;
      ++counted.normals;
    }
  }
}

// Commands as a client sends them, some refused (a crease on the boundary),
// then checks after undo, redo and removal.
void checkDocument(const PolyTestMesh& mesh, const CreaseOptions& options, uint32_t seed, Counted& counted) {
  SCOPED_TRACE(mesh.name + (options.creaseMethod == CreaseMethod::kChaikin ? " chaikin" : " uniform") +
               (options.boundary == BoundaryInterpolation::kEdgeOnly ? " edge-only" : " edge-and-corner") +
               " seed " + std::to_string(seed));
  auto doc =
      Document::create(mesh.topology, mesh.points,
                       {.loop = options, .maxLevel = kLevels, .scheme = DocumentScheme::kCatmullClark});
  ASSERT_TRUE(doc.isOk()) << doc.status().toString();
  auto ours = schemes::QuadRefiner::create(mesh.topology, schemes::QuadScheme::kCatmullClark, options,
                                           {.levels = kLevels});
  ASSERT_TRUE(ours.isOk()) << ours.status().toString();
  const double diag = oracle::boundingDiagonal(mesh.points);
  expectDocumentIsFar(*doc, mesh, *ours, diag, "without edits", counted);
  if (::testing::Test::HasFatalFailure()) return;

  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  auto offset = [&] { return Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5) * (0.1 * diag); };
  auto vertexAt = [&](int l) {
    return VertexId(l, static_cast<uint64_t>(unit(rng) * static_cast<double>(doc->counts().vertices(l))));
  };
  const Level& base = ours->level(0);
  std::set<Index> creased;
  std::vector<EditId> moves, tags;
  for (int k = 0; k < 14; ++k) {
    const int l = k % (kLevels + 1);
    const int op = static_cast<int>(unit(rng) * 4);
    if (op == 0 && l > 0) {
      // Direct manipulation: the limit goes where the user dragged it.
      const VertexId v = vertexAt(l);
      auto before = doc->surface(l, SurfaceKind::kLimit);
      ASSERT_TRUE(before.isOk()) << before.status().toString();
      const Vec3 target = before->positions[v.index()] + offset();
      auto id = doc->moveToLimit(std::span(&v, 1), target);
      ASSERT_TRUE(id.isOk()) << id.status().toString();
      moves.push_back(*id);
      const auto far =
          oracle::refineEditedQuadsWithOpenSubdiv(mesh.topology, mesh.points, options, *ours, doc->edits());
      auto after = doc->evaluate(l);
      ASSERT_TRUE(after.isOk()) << after.status().toString();
      if (!oracle::limitPositionDiffersFromFar((*after)->levels[l], static_cast<Index>(v.index()), options)) {
        ASSERT_LE((far[l].limitPositions[v.index()] - target).norm(), kPositionTolerance * diag)
            << "Far's limit of " << v.toString() << " after it was dragged";
      }  // at a dart, its own limit goes to the target, not Limit()'s
      ++counted.drags;
    } else if (op == 1) {
      // An interior base edge not creased before: a boundary edge is refused.
      const auto e = static_cast<Index>(unit(rng) * base.numEdges());
      const float sharpness = std::array<float, 4>{0.5f, 1.5f, 2.5f, kSharpnessInfinite}[k % 4];
      auto id = doc->setEdgeSharpness(EdgeId(0, static_cast<uint64_t>(e)), sharpness);
      if (base.isBoundaryEdge(e)) {
        ASSERT_FALSE(id.isOk());
        EXPECT_NE(id.status().message().find("boundary"), std::string::npos) << id.status().message();
        continue;
      }
      ASSERT_TRUE(id.isOk()) << id.status().toString();
      if (!creased.insert(e).second) {
        ASSERT_TRUE(doc->remove(*id).isOk());  // Far takes one tag per edge
        continue;
      }
      tags.push_back(*id);
    } else {
      std::vector<VertexId> vertices{vertexAt(l)};
      auto id = doc->moveBy(vertices, offset());
      ASSERT_TRUE(id.isOk()) << id.status().toString();
      moves.push_back(*id);
    }
    ++counted.edits;
  }
  auto corner = doc->setVertexSharpness(vertexAt(0), 3.0f);
  ASSERT_TRUE(corner.isOk()) << corner.status().toString();
  tags.push_back(*corner);
  expectDocumentIsFar(*doc, mesh, *ours, diag, "after the edits", counted);
  if (::testing::Test::HasFatalFailure()) return;

  ASSERT_TRUE(doc->undo(moves.front()).isOk());
  ASSERT_TRUE(doc->undo(tags.front()).isOk());
  expectDocumentIsFar(*doc, mesh, *ours, diag, "after two undos", counted);
  if (::testing::Test::HasFatalFailure()) return;
  ASSERT_TRUE(doc->redo(moves.front()).isOk());
  ASSERT_TRUE(doc->remove(moves.back()).isOk());
  counted.undos += 4;
  expectDocumentIsFar(*doc, mesh, *ours, diag, "after a redo and a removal", counted);
}

TEST(CatmarkDocumentOracle, CommandsGiveFarsPointsAndLimitsAtEveryLevel) {
  Counted counted;
  uint32_t seed = 1;
  for (const PolyTestMesh& shape : testing::catmarkShapes()) {
    for (const CreaseOptions& options : oracle::allCreaseOptions()) {
      checkDocument(shape, options, seed++, counted);
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_GT(counted.drags, 0);
  EXPECT_GT(counted.normals, 0);
  std::printf(
      "points %lld, held points %lld, limits %lld, normals %lld; edits %lld (%lld drags), undos %lld\n",
      counted.points, counted.heldPoints, counted.limits, counted.normals, counted.edits, counted.drags,
      counted.undos);
}

TEST(CatmarkDocumentOracle, RealPolygonMeshDoubleTorus) {
  auto mesh = schemes::importPolygonMesh(testing::cgalMeshPath("double-torus-example.off"), "");
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  const PolyTestMesh real{"double-torus-example", mesh->topology, mesh->points};
  Counted counted;
  checkDocument(real, {}, 51, counted);
  checkDocument(real, {CreaseMethod::kChaikin, BoundaryInterpolation::kEdgeAndCorner}, 52, counted);
  EXPECT_GT(counted.limits, 0);
}

// A base with other polygons than quads has no limits on level 0: a base
// vertex shows its child's limit on level 1, and dragging it must put that
// limit at the target (SparseHierarchy::solveControlPoint). Each drag
// follows moves of other base vertices (no finer offset, which would turn
// with its frame); OpenSubdiv's level-1 limit is the judge.
TEST(CatmarkDocumentOracle, DraggedBaseVerticesOfPolygonBasesLandOnFarsLevelOneLimit) {
  auto torus = schemes::importPolygonMesh(testing::cgalMeshPath("double-torus-example.off"), "");
  ASSERT_TRUE(torus.isOk()) << torus.status().toString();
  int drags = 0, dartDrags = 0;
  uint32_t seed = 60;
  for (const PolyTestMesh& mesh :
       {testing::withPolyJitter(testing::mixedPrism(5, false), 0.05, 11),
        testing::withRandomPolyTags(testing::withPolyJitter(testing::mixedPrism(7, true), 0.05, 12), 0.3, 0.1,
                                    13),
        PolyTestMesh{"double-torus-example", torus->topology, torus->points}}) {
    SCOPED_TRACE(mesh.name);
    const CreaseOptions options{};
    auto doc =
        Document::create(mesh.topology, mesh.points,
                         {.loop = options, .maxLevel = kLevels, .scheme = DocumentScheme::kCatmullClark});
    ASSERT_TRUE(doc.isOk()) << doc.status().toString();
    ASSERT_FALSE(doc->hierarchy().hasLimits(0)) << "the base has other polygons than quads";
    auto ours = schemes::QuadRefiner::create(mesh.topology, schemes::QuadScheme::kCatmullClark, options,
                                             {.levels = kLevels});
    ASSERT_TRUE(ours.isOk()) << ours.status().toString();
    const double diag = oracle::boundingDiagonal(mesh.points);
    std::mt19937 rng(seed++);
    std::uniform_real_distribution<double> unit(-0.5, 0.5);
    for (int k = 0; k < 6; ++k) {
      const VertexId v(0, rng() % doc->counts().vertices(0));
      auto before = doc->surface(1, SurfaceKind::kLimit);
      ASSERT_TRUE(before.isOk()) << before.status().toString();
      const Vec3 target = before->positions[v.index()] + Vec3(unit(rng), unit(rng), unit(rng)) * (0.1 * diag);
      ASSERT_TRUE(doc->moveToLimit(std::span(&v, 1), target).isOk());
      const auto far =
          oracle::refineEditedQuadsWithOpenSubdiv(mesh.topology, mesh.points, options, *ours, doc->edits());
      auto after = doc->evaluate(1);
      ASSERT_TRUE(after.isOk()) << after.status().toString();
      if (oracle::limitPositionDiffersFromFar((*after)->levels[1], static_cast<Index>(v.index()), options)) {
        ++dartDrags;  // its own limit goes to the target, not Limit()'s
      } else {
        EXPECT_LE((far[1].limitPositions[v.index()] - target).norm(), kPositionTolerance * diag)
            << "Far's level-1 limit of " << v.toString() << " after drag " << k;
      }
      ++drags;
    }
  }
  EXPECT_EQ(drags, 18);
}

}  // namespace
}  // namespace tessera

// The sparse hierarchy on Catmull-Clark's quad split
// (core/hierarchy/sparse_hierarchy.h) against OpenSubdiv 3.5: with moves
// at every level stored as offsets in local frames, sharpness edits at the
// base level and a tessellation's demand for random deep faces, every
// vertex the hierarchy holds must equal the point Far's PrimvarRefiner
// gives when each level's edits are added to its interpolated points before
// the next level is interpolated (the edit semantics of Pulli & Lounsbery,
// "Hierarchical Editing and Rendering of Subdivision Surfaces" §2), within
// 1e-12 of the bounding-box diagonal; every complete vertex's limit must
// equal Far's Limit() there, within 1e-9 of the diagonal and 1e-6 rad
// (except at darts, and the normal across a crease into three faces or
// more, where Limit()'s masks are not the surface's). The edits are applied one at a time through the
// incremental update, then one is undone, and the hierarchy is compared again after each step.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>

#include "core/catmark/limit.h"
#include "core/catmark/polygon_level.h"
#include "core/catmark/semi_sharp_limit.h"
#include "core/hierarchy/incidence.h"
#include "core/hierarchy/sparse_hierarchy.h"
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

constexpr int kLevels = 3;
using oracle::kNormalTolerance;
using oracle::kPointTolerance;
using oracle::kPositionTolerance;

struct Counted {
  long long points = 0, limits = 0, normals = 0, notLimits = 0, absentVertices = 0, moves = 0, dartMoves = 0,
            tags = 0, semiSharp = 0;
};

// The whole levels of the base with the edits' tags.
schemes::QuadRefiner denseWith(const PolyTestMesh& mesh, const CreaseOptions& options,
                               const schemes::QuadRefiner& ours, const std::vector<Edit>& edits) {
  auto dense = schemes::QuadRefiner::create(oracle::taggedTopology(mesh.topology, ours.level(0), edits),
                                            schemes::QuadScheme::kCatmullClark, options, {.levels = kLevels});
  if (!dense.isOk()) throw std::runtime_error(dense.status().toString());
  return std::move(*dense);
}

std::vector<oracle::OsdQuadLevel> farWithEdits(const PolyTestMesh& mesh, const CreaseOptions& options,
                                               const schemes::QuadRefiner& ours,
                                               const std::vector<Edit>& edits) {
  return oracle::refineEditedQuadsWithOpenSubdiv(mesh.topology, mesh.points, options, ours, edits);
}

// A complete vertex whose semi-sharp feature has not decayed: the limit the
// sparse level gives (its far rings derived from the parent where it does
// not hold them, core/hierarchy/sparse_far_rings.h) is the one the whole
// level, `dense` (tagged as the edits tag the base), gives from Far's
// points (semi_sharp_limit_test.cc holds that one to Far's refinement past
// the decay).
void expectSemiSharpLimitIsTheWholeLevels(const SparseHierarchy& h, int l, Index v,
                                          const oracle::OsdQuadLevel& far, const schemes::QuadRefiner& dense,
                                          double diag, const std::string& when) {
  const uint64_t id = h.level(l).vertexIds[v];
  const Index whole = static_cast<Index>(id);
  const CatmarkLimitFrame frame = catmarkLimitFrame(dense.level(l), whole, far.points, h.options());
  ASSERT_LE((h.limitPosition(l, v) - frame.position).norm(), kPositionTolerance * diag)
      << when << ": semi-sharp limit of v" << l << ":" << id;
  const Vec3 normal = (frame.tangent1 % frame.tangent2).normalized();
  const Vec3 held = h.limitNormal(l, v);
  ASSERT_LE(std::atan2((held % normal).norm(), held | normal), kNormalTolerance)
      << when << ": semi-sharp normal of v" << l << ":" << id;
}

void expectHierarchyIsFar(const SparseHierarchy& h, const std::vector<oracle::OsdQuadLevel>& far,
                          const schemes::QuadRefiner& dense, double diag, const std::string& when,
                          Counted& counted) {
  ASSERT_EQ(h.numLevels(), kLevels + 1) << when;
  for (int l = 0; l < h.numLevels(); ++l) {
    const SparseLevel& topo = h.level(l);
    for (Index v = 0; v < topo.mesh.numVertices; ++v) {
      const uint64_t id = topo.vertexIds[v];
      ASSERT_LE((h.points(l)[v] - far[l].points[id]).norm(), kPointTolerance * diag)
          << when << ": point of v" << l << ":" << id;
      ++counted.points;
      if (far[l].limitPositions.empty() || !topo.isComplete(v)) continue;
      if (takesDecayedLimit(topo.mesh, v, h.options())) {
        expectSemiSharpLimitIsTheWholeLevels(h, l, v, far[l], dense, diag, when);
        if (::testing::Test::HasFatalFailure()) return;
        ++counted.semiSharp;
      }
      if (oracle::limitNormalDiffersFromFar(topo.mesh, v, h.options())) {  // Limit() is not the surface here
        ++counted.notLimits;
        if (oracle::limitPositionDiffersFromFar(topo.mesh, v, h.options())) continue;
      }
      ASSERT_LE((h.limitPosition(l, v) - far[l].limitPositions[id]).norm(), kPositionTolerance * diag)
          << when << ": limit of v" << l << ":" << id;
      ++counted.limits;
      if (oracle::limitNormalDiffersFromFar(topo.mesh, v, h.options())) continue;
      const Vec3 farNormal = far[l].limitTangent1[id] % far[l].limitTangent2[id];
      const double scale = far[l].limitTangent1[id].norm() * far[l].limitTangent2[id].norm();
      if (!(farNormal.norm() > 1e-12 * scale)) continue;  // parallel tangents: Limit() gives no normal
      const Vec3 normal = h.limitNormal(l, v);
      ASSERT_LE(std::atan2((normal % farNormal).norm(), normal | farNormal), kNormalTolerance)
          << when << ": normal of v" << l << ":" << id;
      ++counted.normals;
    }
    counted.absentVertices += static_cast<long long>(far[l].points.size()) - topo.mesh.numVertices;
  }
}

// Random moves at every level (one of two vertices), base-level sharpness
// edits when `withTags`, in a random order.
std::vector<Edit> randomEdits(const LevelCounts& counts, const Level& base, double diag, bool withTags,
                              std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  auto offset = [&] { return Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5) * (0.1 * diag); };
  auto vertexAt = [&](int l) {
    return VertexId(l, static_cast<uint64_t>(unit(rng) * static_cast<double>(counts.vertices(l))));
  };
  std::vector<Edit> edits;
  for (int l = 0; l <= kLevels; ++l) {
    MoveEdit move{{{vertexAt(l), offset()}}};
    if (l > 0) move.offsets.push_back({vertexAt(l), offset()});
    edits.push_back({{}, true, move});
    edits.push_back({{}, true, MoveEdit{{{vertexAt(l), offset()}}}});
  }
  if (withTags) {
    // Distinct interior edges (the document refuses a boundary edge's tag,
    // which Sdc holds infinitely sharp).
    const float sharpness[] = {0.5f, 1.5f, 2.5f, 10.0f};
    std::set<Index> tagged;
    for (int k = 0, tries = 0; k < 4 && tries < 1000; ++tries) {
      const auto e = static_cast<Index>(unit(rng) * base.numEdges());
      if (base.isBoundaryEdge(e) || !tagged.insert(e).second) continue;
      edits.push_back({{}, true, EdgeSharpnessEdit{EdgeId(0, static_cast<uint64_t>(e)), sharpness[k++]}});
    }
    edits.push_back({{}, true, VertexSharpnessEdit{vertexAt(0), 3.0f}});
  }
  std::shuffle(edits.begin(), edits.end(), rng);
  for (size_t i = 0; i < edits.size(); ++i) edits[i].id = EditId{i + 1};
  return edits;
}

// A mesh's uniform levels (for Far's numbering and frames), its split's
// counts and a hierarchy without edits, whole at level 1.
struct Case {
  schemes::QuadRefiner ours;
  LevelCounts counts;
  double diag;
  SparseHierarchy h;
};

std::optional<Case> makeCase(const PolyTestMesh& mesh, const CreaseOptions& options) {
  auto ours = schemes::QuadRefiner::create(mesh.topology, schemes::QuadScheme::kCatmullClark, options,
                                           {.levels = kLevels});
  auto level0 = buildPolyLevel(mesh.topology, options);
  if (!ours.isOk() || !level0.isOk()) {
    ADD_FAILURE() << mesh.name << ": " << ours.status().toString() << " " << level0.status().toString();
    return std::nullopt;
  }
  const LevelCounts counts = testing::quadCountsOf(ours->level(0), kLevels);
  auto h = SparseHierarchy::create(std::move(*level0), mesh.points, options, counts, 1, {});
  if (!h.isOk()) {
    ADD_FAILURE() << mesh.name << ": " << h.status().toString();
    return std::nullopt;
  }
  return Case{std::move(*ours), counts, oracle::boundingDiagonal(mesh.points), std::move(*h)};
}

void checkHierarchy(const PolyTestMesh& mesh, const CreaseOptions& options, bool withTags, uint32_t seed,
                    Counted& counted) {
  SCOPED_TRACE(mesh.name + (options.creaseMethod == CreaseMethod::kChaikin ? " chaikin" : " uniform") +
               (options.boundary == BoundaryInterpolation::kEdgeOnly ? " edge-only" : " edge-and-corner") +
               " seed " + std::to_string(seed));
  std::optional<Case> c = makeCase(mesh, options);
  ASSERT_TRUE(c.has_value());
  auto& [ours, counts, diag, h] = *c;

  std::mt19937 rng(seed);
  const std::vector<Edit> planned = randomEdits(counts, ours.level(0), diag, withTags, rng);
  std::vector<Edit> edits;
  for (const Edit& edit : planned) {
    h.reserve(edit, edits);
    edits.push_back(edit);
    h.update(edits.back(), edits);
    counted.moves += std::holds_alternative<MoveEdit>(edit.change) ? 1 : 0;
    counted.tags += std::holds_alternative<MoveEdit>(edit.change) ? 0 : 1;
  }
  // A tessellation's demand: random faces of the deepest level.
  std::vector<FaceId> faces;
  std::uniform_real_distribution<double> unit(0, 1);
  for (int k = 0; k < 6; ++k) {
    faces.push_back(
        FaceId(kLevels, static_cast<uint64_t>(unit(rng) * static_cast<double>(counts.faces(kLevels)))));
  }
  h.reserveFaces(faces, edits);
  expectHierarchyIsFar(h, farWithEdits(mesh, options, ours, edits), denseWith(mesh, options, ours, edits),
                       diag, "after every edit", counted);
  if (::testing::Test::HasFatalFailure()) return;

  // Undo a coarse move and a fine one.
  for (int level : {0, 2}) {
    auto it = std::find_if(edits.begin(), edits.end(), [&](const Edit& e) {
      return e.active && e.level() == level && std::holds_alternative<MoveEdit>(e.change);
    });
    ASSERT_NE(it, edits.end());
    it->active = false;
    h.update(*it, edits);
    expectHierarchyIsFar(h, farWithEdits(mesh, options, ours, edits), denseWith(mesh, options, ours, edits),
                         diag, "after undoing " + it->id.toString() + " at level " + std::to_string(level),
                         counted);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

TEST(CatmarkHierarchyOracle, EditedSparseHierarchiesHoldFarsPointsAndLimits) {
  using namespace testing;
  const std::vector<PolyTestMesh> shapes = catmarkShapes();
  Counted counted;
  uint32_t seed = 1;
  for (const PolyTestMesh& shape : shapes) {
    for (const CreaseOptions& options : oracle::allCreaseOptions()) {
      checkHierarchy(shape, options, true, seed++, counted);
      if (HasFatalFailure()) return;
    }
    checkHierarchy(withRandomPolyTags(shape, 0.3, 0.1, seed), {}, false, seed, counted);
    ++seed;
    if (HasFatalFailure()) return;
  }
  // Sparse, not whole: the deepest levels held a part of the uniform ones.
  EXPECT_GT(counted.absentVertices, 0);
  EXPECT_GT(counted.normals, 0);
  EXPECT_GT(counted.semiSharp, 0);
  std::printf(
      "points compared %lld, limits %lld, normals %lld (and %lld darts and crease spans of 3+ faces, left to "
      "the "
      "Bfr test), semi-sharp limits held to the whole level's %lld, vertices not held %lld, moves %lld (%lld "
      "of darts), tags %lld\n",
      counted.points, counted.limits, counted.normals, counted.notLimits, counted.semiSharp,
      counted.absentVertices, counted.moves, counted.dartMoves, counted.tags);
}

// Direct manipulation (Pulli & Lounsbery §2.2) on the quad split: a move
// solved for a target limit position puts Far's Limit() there, at levels
// 1 to 3, one move after another.
void checkDirectManipulation(const PolyTestMesh& mesh, const CreaseOptions& options, uint32_t seed,
                             Counted& counted) {
  SCOPED_TRACE(mesh.name + " seed " + std::to_string(seed));
  std::optional<Case> c = makeCase(mesh, options);
  ASSERT_TRUE(c.has_value());
  auto& [ours, counts, diag, h] = *c;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Edit> edits;
  for (int k = 0; k < 9; ++k) {
    const int l = 1 + k % kLevels;
    const VertexId id(l, static_cast<uint64_t>(unit(rng) * static_cast<double>(counts.vertices(l))));
    const FaceId around = incidentFace(h.level(0).mesh, counts, id);
    h.reserveFaces(std::span(&around, 1), edits);
    auto v = h.completeVertex(id);
    ASSERT_TRUE(v.isOk()) << v.status().toString();
    const Vec3 target =
        h.limitPosition(l, *v) + Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5) * (0.1 * diag);
    const Vec3 solved = h.solveControlPoint(l, *v, target);
    const Edit edit{EditId{edits.size() + 1}, true,
                    MoveEdit{{{id, h.frameOf(l, *v).toLocal(solved - h.points(l)[*v])}}}};
    h.reserve(edit, edits);
    edits.push_back(edit);
    h.update(edits.back(), edits);
    const auto far = farWithEdits(mesh, options, ours, edits);
    if (oracle::limitPositionDiffersFromFar(h.level(l).mesh, *v, h.options())) {
      ++counted.dartMoves;  // the dart's own limit, not Limit()'s, goes to the target
    } else {
      ASSERT_LE((far[l].limitPositions[id.index()] - target).norm(), kPositionTolerance * diag)
          << "Far's limit of " << id.toString() << " after its move";
    }
    ASSERT_LE((h.limitPosition(l, *v) - target).norm(), kPositionTolerance * diag)
        << "the hierarchy's limit of " << id.toString() << " after its move";
    ++counted.moves;
  }
  expectHierarchyIsFar(h, farWithEdits(mesh, options, ours, edits), denseWith(mesh, options, ours, edits),
                       diag, "after the moves", counted);
}

TEST(CatmarkHierarchyOracle, DirectManipulationPutsFarsLimitAtTheTarget) {
  using namespace testing;
  Counted counted;
  uint32_t seed = 100;
  for (const PolyTestMesh& mesh :
       {quadCube(), withPolyJitter(quadTorus(7, 5), 0.05, 3), withRandomPolyTags(quadGrid(5, 4), 0.3, 0.1, 4),
        withRandomPolyTags(withPolyJitter(mixedPrism(6, true), 0.05, 5), 0.3, 0.1, 6)}) {
    for (const CreaseOptions& options : oracle::allCreaseOptions()) {
      checkDirectManipulation(mesh, options, seed++, counted);
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_EQ(counted.moves, 4 * 4 * 9);
}

TEST(CatmarkHierarchyOracle, RealPolygonMeshDoubleTorus) {
  auto mesh = schemes::importPolygonMesh(testing::cgalMeshPath("double-torus-example.off"), "");
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  const PolyTestMesh real{"double-torus-example", mesh->topology, mesh->points};
  Counted counted;
  checkHierarchy(real, {}, true, 41, counted);
  checkHierarchy(real, {CreaseMethod::kChaikin, BoundaryInterpolation::kEdgeOnly}, true, 42, counted);
  EXPECT_GT(counted.limits, 0);
}

}  // namespace
}  // namespace tessera

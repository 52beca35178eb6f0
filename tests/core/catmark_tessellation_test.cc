// Regions of Catmull-Clark documents (core/tessellation/tessellation.h on
// the quad split): what a profile shows is a closed, consistently oriented
// surface at the document's limit positions after random edits, and a function of the document alone -- a
// document edited step by step, its tessellations kept up to date through
// undo, redo and removal, shows bit for bit what a fresh document given the
// same edit list shows. Profiles cover grouped base faces (deepest level 3),
// a region per base face, and regions below the base (deepest level 6,
// regions at level 1), whose ids and extents follow the quad numbering
// (docs/ARCHITECTURE.md "Numbering"). A crease or corner vertex is shown
// once per side, each with its side's normal.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

#include "core/document/document.h"
#include "core/document/document_file.h"
#include "core/tessellation/tessellation.h"
#include "support/polygon_meshes.h"
#include "support/region_checks.h"

namespace tessera {
namespace {

using testing::PolyTestMesh;

const LodProfile kGrouped{.baseLevel = 1, .maxLevel = 3, .angleThresholdDegrees = 10};
const LodProfile kPerBaseFace{.baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 10};
const LodProfile kBelowBase{.baseLevel = 1, .maxLevel = 6, .angleThresholdDegrees = 20};

// Every directed edge of the merged surface once and its reverse once (so
// no crack, no T-vertex, one orientation), no degenerate triangle, and
// every vertex's limit finite. Vertices are welded by id: a crease or
// corner vertex has a copy per side (docs/LIMITS.md), which share it.
void expectClosedAndOriented(const Tessellation& t, const std::string& when) {
  std::map<std::pair<uint64_t, uint64_t>, int> directed;
  for (const auto& [id, region] : t.regions()) {
    for (const auto& tri : region.triangles) {
      const uint64_t a = region.vertexIds[tri[0]], b = region.vertexIds[tri[1]], c = region.vertexIds[tri[2]];
      ASSERT_TRUE(a != b && b != c && c != a) << when << ": a degenerate triangle";
      ++directed[{a, b}], ++directed[{b, c}], ++directed[{c, a}];
    }
    for (const Vec3& p : region.positions) ASSERT_TRUE(std::isfinite(p[0] + p[1] + p[2])) << when;
  }
  ASSERT_GT(directed.size(), 0u) << when;
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << when << ": directed edge " << VertexId::fromPacked(edge.first).toString() << " -> "
                        << VertexId::fromPacked(edge.second).toString() << " used " << count << " times";
    ASSERT_EQ(directed.count({edge.second, edge.first}), 1u)
        << when << ": a crack at " << VertexId::fromPacked(edge.first).toString() << " -> "
        << VertexId::fromPacked(edge.second).toString();
  }
}

// Every displayed vertex lies at its limit: the limit position of the
// uniform limit surface at the document's deepest level (Document::surface,
// held to OpenSubdiv's Limit() by CatmarkDocumentOracle), where a vertex
// keeps its index (ids.h). Every level from the one an edit reaches on
// gives the same limit up to rounding, so 1e-9 holds wherever the
// tessellation took it.
void expectDisplayedLimits(const Document& doc, const Tessellation& t, const std::string& when) {
  auto limit = doc.surface(doc.options().maxLevel, SurfaceKind::kLimit);
  ASSERT_TRUE(limit.isOk()) << limit.status().toString();
  double worst = 0;
  size_t checked = 0;
  for (const auto& [id, region] : t.regions()) {
    for (size_t v = 0; v < region.positions.size(); ++v) {
      const uint64_t index = VertexId::fromPacked(region.vertexIds[v]).index();
      ASSERT_LT(index, limit->positions.size()) << when;
      worst = std::max(worst, (region.positions[v] - limit->positions[index]).norm());
      ++checked;
    }
  }
  EXPECT_LE(worst, 1e-9) << when << ": " << checked << " displayed vertices";
}

// One random edit of a Catmull-Clark document: mostly moves at levels 0..3
// (plain and to a limit position), sometimes a semi-sharp or sharp crease
// or a vertex sharpness at level 1 or 2. False when the document refused
// it (a tag on the boundary), which is fine.
bool randomEdit(Document& doc, std::mt19937& rng) {
  auto pick = [&](uint64_t n) { return std::uniform_int_distribution<uint64_t>(0, n - 1)(rng); };
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const int op = static_cast<int>(pick(10));
  if (op < 7) {
    const int level = static_cast<int>(pick(4));
    const VertexId v(level, pick(doc.counts().vertices(level)));
    const Vec3 d(uniform(-.08, .08), uniform(-.08, .08), uniform(-.08, .08));
    if (op < 5 || level == 0) return doc.moveBy(std::span(&v, 1), d).isOk();
    const SparseHierarchy& h = doc.hierarchy();
    Vec3 target = d;
    if (v.level() < h.numLevels()) {
      const Index local = h.level(v.level()).findVertex(v.index());
      if (local >= 0 && h.level(v.level()).isComplete(local)) target += h.limitPosition(v.level(), local);
    }
    return doc.moveToLimit(std::span(&v, 1), target).isOk();
  }
  const int level = 1 + static_cast<int>(pick(2));
  if (op < 9) {
    const float sharpness = pick(3) == 0 ? kSharpnessInfinite : (pick(2) ? 1.5f : 2.0f);
    return doc.setEdgeSharpness(EdgeId(level, pick(doc.counts().edges(level))), sharpness).isOk();
  }
  return doc.setVertexSharpness(VertexId(level, pick(doc.counts().vertices(level))), pick(2) ? 1.0f : 0.0f)
      .isOk();
}

Expected<Document> catmarkDocument(const PolyTestMesh& mesh) {
  return Document::create(mesh.topology, mesh.points,
                          {.maxLevel = 6, .scheme = DocumentScheme::kCatmullClark});
}

TEST(CatmarkTessellation, RegionsFormAClosedOrientedSurfaceAfterEdits) {
  using namespace testing;
  long long triangles = 0;
  uint32_t seed = 11;
  for (const PolyTestMesh& mesh :
       {quadCube(), withPolyJitter(quadTorus(7, 5), 0.05, 3),
        withRandomPolyTags(withPolyJitter(mixedPrism(6, false), 0.05, 5), 0.3, 0.1, 6)}) {
    SCOPED_TRACE(mesh.name);
    auto doc = catmarkDocument(mesh);
    ASSERT_TRUE(doc.isOk()) << doc.status().toString();
    for (const LodProfile& profile : {kGrouped, kPerBaseFace, kBelowBase}) {
      auto t = Tessellation::build(*doc, profile);
      ASSERT_TRUE(t.isOk()) << profile.describe() << ": " << t.status().toString();
      EXPECT_EQ(t->regionsAreGroups(), profile.maxLevel <= kMaxGroupedLevel);
      expectClosedAndOriented(*t, profile.describe() + " without edits");
      expectDisplayedLimits(*doc, *t, profile.describe() + " without edits");
      if (HasFatalFailure()) return;
    }
    auto t = Tessellation::build(*doc, kBelowBase);
    ASSERT_TRUE(t.isOk());
    EXPECT_EQ(t->regionLevel(), 1);
    std::mt19937 rng(seed++);
    for (int step = 0; step < 12; ++step) {
      if (!randomEdit(*doc, rng)) continue;
      auto changes = t->update(*doc);
      ASSERT_TRUE(changes.isOk()) << changes.status().toString();
      expectClosedAndOriented(*t, "after step " + std::to_string(step));
      if (HasFatalFailure()) return;
    }
    expectDisplayedLimits(*doc, *t, "after the edits");
    triangles += t->numTriangles();
  }
  std::printf("%lld triangles at the end, profile %s\n", triangles, kBelowBase.describe().c_str());
}

void expectHistoryIndependent(const PolyTestMesh& mesh, uint32_t seed) {
  SCOPED_TRACE(mesh.name + " seed " + std::to_string(seed));
  auto a = catmarkDocument(mesh);
  ASSERT_TRUE(a.isOk()) << a.status().toString();
  std::vector<Tessellation> kept;
  for (const LodProfile& profile : {kGrouped, kPerBaseFace, kBelowBase}) {
    auto t = Tessellation::build(*a, profile);
    ASSERT_TRUE(t.isOk()) << t.status().toString();
    kept.push_back(std::move(*t));
  }
  auto updateAll = [&](const std::string& when) {
    for (Tessellation& t : kept) {
      auto changes = t.update(*a);
      ASSERT_TRUE(changes.isOk()) << when << ": " << changes.status().toString();
    }
  };
  std::mt19937 rng(seed);
  constexpr int kEdits = 16;
  int applied = 0;
  for (int i = 0; i < kEdits; ++i) {
    if (!randomEdit(*a, rng)) continue;
    ++applied;
    updateAll("edit " + std::to_string(i));
    if (::testing::Test::HasFatalFailure()) return;
    if (i == kEdits / 2) {
      const EditId undone = a->edits()[a->edits().size() / 2].id;
      ASSERT_TRUE(a->undo(undone).isOk());
      updateAll("undo");
      ASSERT_TRUE(a->redo(undone).isOk());
      updateAll("redo");
      ASSERT_TRUE(a->remove(a->edits()[a->edits().size() / 3].id).isOk());
      updateAll("remove");
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  ASSERT_GE(applied, 8);
  // The same edit list through the file format, tessellated once.
  auto b = deserializeDocument(serializeDocument(*a), mesh.name);
  ASSERT_TRUE(b.isOk()) << b.status().toString();
  for (const Tessellation& t : kept) {
    auto fresh = Tessellation::build(*b, t.profile());
    ASSERT_TRUE(fresh.isOk()) << fresh.status().toString();
    testing::expectSameRegions(t, *fresh, "updated vs fresh, " + t.profile().describe());
    if (::testing::Test::HasFatalFailure()) return;
  }
}

// The quad cube with its twelve edges infinitely sharp is its own limit:
// six flat squares, each edge a straight crease, each corner meeting three
// one-face sides. So every displayed triangle is flat on a face of the cube
// and each of its vertices carries that face's normal exactly -- a crease
// vertex once per side, a corner three times.
TEST(CatmarkTessellation, EachSideOfASharpEdgeShowsItsOwnNormal) {
  PolyTestMesh cube = testing::quadCube();
  for (int f = 0; f < cube.topology.numFaces(); ++f) {
    const int from = cube.topology.faceOffsets[f], n = cube.topology.faceOffsets[f + 1] - from;
    for (int j = 0; j < n; ++j) {
      const int a = cube.topology.indices[from + j], b = cube.topology.indices[from + (j + 1) % n];
      if (a < b) cube.topology.creases.push_back({a, b, 10.0f});
    }
  }
  auto doc =
      Document::create(cube.topology, cube.points, {.maxLevel = 3, .scheme = DocumentScheme::kCatmullClark});
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  auto t = Tessellation::build(*doc, kGrouped);
  ASSERT_TRUE(t.isOk()) << t.status().message();
  std::map<uint64_t, std::set<std::array<double, 3>>> normalsOf;
  int triangles = 0;
  for (const auto& [id, region] : t->regions()) {
    for (const auto& tri : region.triangles) {
      const Vec3 face = ((region.positions[tri[1]] - region.positions[tri[0]]) %
                         (region.positions[tri[2]] - region.positions[tri[0]]))
                            .normalized();
      ++triangles;
      for (int k = 0; k < 3; ++k) {
        const Vec3& normal = region.normals[tri[k]];
        EXPECT_LE((normal - face).norm(), 1e-12) << VertexId::fromPacked(region.vertexIds[tri[k]]).toString();
        normalsOf[region.vertexIds[tri[k]]].insert({normal[0], normal[1], normal[2]});
      }
    }
  }
  std::map<size_t, int> vertices;  // by how many sides they show
  for (const auto& [id, normals] : normalsOf) ++vertices[normals.size()];
  EXPECT_GT(triangles, 100);
  EXPECT_EQ(vertices[3], 8) << "each corner of the cube shows three sides";
  EXPECT_GT(vertices[2], 12) << "crease vertices show two";
}

// Where a semi-sharp feature meets an infinitely sharp one and the document
// stops before it decays, a vertex's limit and its sides come from its ring
// refined until it has (core/catmark/semi_sharp_limit.h); where the document
// is deep enough, from the level where it has decayed, whose masks and sides
// are Limit()'s (both held to Bfr in bfr_catmark_limit_test.cc). So the same
// level-1 surface, shown from a document held to level 1 and from one held
// to level 4 (where sharpness up to 3.8 has decayed), carries at every
// triangle corner the same side with the same normal. Counting the
// semi-sharp edges as sharp at level 1, some corners took another side's
// normal.
TEST(CatmarkTessellation, UndecayedSemiSharpVerticesShowTheSidesTheyHaveOnceDecayed) {
  PolyTestMesh mesh =
      testing::withRandomPolyTags(testing::withPolyJitter(testing::quadTorus(8, 6), 0.05, 7), 0.35, 0.1, 50);
  for (size_t i = 0; i < mesh.topology.creases.size(); i += 2) mesh.topology.creases[i].sharpness = 10.0f;
  const LodProfile levelOne{.baseLevel = 1, .maxLevel = 1, .angleThresholdDegrees = 10};
  for (CreaseMethod method : {CreaseMethod::kUniform, CreaseMethod::kChaikin}) {
    SCOPED_TRACE(method == CreaseMethod::kChaikin ? "chaikin" : "uniform");
    // Per triangle corner (its vertex and the triangle's ids), the normal.
    auto cornerNormals = [&](int maxLevel) {
      auto doc = Document::create(
          mesh.topology, mesh.points,
          {.loop = {.creaseMethod = method}, .maxLevel = maxLevel, .scheme = DocumentScheme::kCatmullClark});
      if (!doc.isOk()) throw std::runtime_error(doc.status().toString());
      auto t = Tessellation::build(*doc, levelOne);
      if (!t.isOk()) throw std::runtime_error(t.status().toString());
      std::map<std::array<uint64_t, 4>, Vec3> normals;
      for (const auto& [id, region] : t->regions()) {
        for (const auto& tri : region.triangles) {
          std::array<uint64_t, 3> ids{region.vertexIds[tri[0]], region.vertexIds[tri[1]],
                                      region.vertexIds[tri[2]]};
          std::sort(ids.begin(), ids.end());
          for (int k = 0; k < 3; ++k)
            normals[{region.vertexIds[tri[k]], ids[0], ids[1], ids[2]}] = region.normals[tri[k]];
        }
      }
      return normals;
    };
    const auto shallow = cornerNormals(1), deep = cornerNormals(4);
    ASSERT_EQ(shallow.size(), deep.size());
    int compared = 0;
    for (const auto& [corner, normal] : shallow) {
      auto other = deep.find(corner);
      ASSERT_NE(other, deep.end()) << VertexId::fromPacked(corner[0]).toString();
      const double angle = std::atan2((normal % other->second).norm(), dot(normal, other->second));
      EXPECT_LE(angle, 1e-9) << VertexId::fromPacked(corner[0]).toString();
      ++compared;
    }
    EXPECT_GT(compared, 1000);
  }
}

TEST(CatmarkTessellation, UpdatedRegionsEqualAFreshDocumentsBitForBit) {
  using namespace testing;
  uint32_t seed = 21;
  for (const PolyTestMesh& mesh :
       {quadCube(), withPolyJitter(quadTorus(6, 5), 0.05, 4),
        withRandomPolyTags(withPolyJitter(mixedPrism(5, false), 0.05, 7), 0.3, 0.1, 8),
        withPolyJitter(quadGrid(4, 3), 0.05, 9)}) {
    for (int run = 0; run < 2; ++run) {
      expectHistoryIndependent(mesh, seed++);
      if (HasFatalFailure()) return;
    }
  }
}

}  // namespace
}  // namespace tessera

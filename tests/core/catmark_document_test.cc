// Catmull-Clark documents (core/document/document.h, DocumentScheme::
// kCatmullClark): the incremental hierarchy equals the from-scratch
// evaluation after every step of long random histories (moves, drags,
// creases and corners at every level, undo, redo, removal, growth); the
// document file keeps the scheme and the polygons bit for bit; what only
// Loop defines is refused with a message naming it. OpenSubdiv's view of
// the same documents is tests/oracle/catmark_document_oracle_test.cc.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <random>

#include "core/catmark/limit.h"
#include "core/document/document.h"
#include "core/document/document_file.h"
#include "core/morph/keyed_document.h"
#include "core/schemes/polygon_reader.h"
#include "support/polygon_meshes.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

using testing::PolyTestMesh;

constexpr int kMaxLevel = 4;

DocumentOptions catmark(const LoopOptions& loop = {}, int uniformLevel = 0) {
  return {.loop = loop,
          .maxLevel = kMaxLevel,
          .uniformLevel = uniformLevel,
          .scheme = DocumentScheme::kCatmullClark};
}

// Every held point equals the dense evaluation's; every complete vertex's
// limit equals Catmull-Clark's limit of the dense level where the level
// has one (all quads).
void expectMatchesDense(const Document& doc, const std::string& where) {
  const SparseHierarchy& sparse = doc.hierarchy();
  auto dense = doc.evaluate(sparse.numLevels() - 1);
  ASSERT_TRUE(dense.isOk()) << dense.status().message();
  double worstPoint = 0.0, worstLimit = 0.0, worstNormal = 0.0;
  for (int l = 0; l < sparse.numLevels(); ++l) {
    const SparseLevel& level = sparse.level(l);
    const Level& full = (*dense)->levels[l];
    const auto points = sparse.points(l);
    for (Index v = 0; v < level.mesh.numVertices; ++v) {
      const uint64_t id = level.vertexIds[v];
      worstPoint = std::max(worstPoint, (points[v] - (*dense)->points[l][id]).norm());
      if (!level.isComplete(v) || !full.allQuads()) continue;
      const CatmarkLimitFrame ref =
          catmarkLimitFrame(full, static_cast<Index>(id), (*dense)->points[l], doc.options().loop);
      worstLimit = std::max(worstLimit, (sparse.limitPosition(l, v) - ref.position).norm());
      const Vec3 n = ref.tangent1 % ref.tangent2;
      if (n.norm() > 1e-12 * ref.tangent1.norm() * ref.tangent2.norm())
        worstNormal = std::max(worstNormal, (sparse.limitNormal(l, v) - n.normalized()).norm());
    }
  }
  EXPECT_LE(worstPoint, 1e-9) << where;
  EXPECT_LE(worstLimit, 1e-9) << where;
  EXPECT_LE(worstNormal, 1e-9) << where;
}

struct HistoryCase {
  PolyTestMesh mesh;
  LoopOptions options;
  int uniformLevel;
  int steps;
  int growEvery;  // a view's growth at random faces before every this many steps; 0: none
};

void runRandomHistory(const HistoryCase& c, uint32_t seed) {
  auto doc = Document::create(c.mesh.topology, c.mesh.points, catmark(c.options, c.uniformLevel));
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  std::mt19937 rng(seed);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto pick = [&](uint64_t n) { return std::uniform_int_distribution<uint64_t>(0, n - 1)(rng); };
  std::vector<EditId> made;
  int applied = 0;
  for (int step = 0; step < c.steps; ++step) {
    if (c.growEvery > 0 && step % c.growEvery == 0) {
      const int at = 1 + static_cast<int>(pick(kMaxLevel));
      std::vector<FaceId> faces;
      for (int k = 0; k < 3; ++k) faces.push_back(FaceId(at, pick(doc->counts().faces(at))));
      doc->refineHierarchy(faces);
      expectMatchesDense(*doc, c.mesh.name + " step " + std::to_string(step) + " (growth)");
    }
    const int level = static_cast<int>(pick(kMaxLevel + 1));
    // Near a few spots, so that later edits land on refined areas.
    const uint64_t spot = pick(std::min<uint64_t>(doc->counts().vertices(0), 3));
    const uint64_t vertex = pick(10) < 7 ? spot : pick(doc->counts().vertices(level));
    const VertexId v(level, vertex);
    const int op = static_cast<int>(pick(100));
    std::string what;
    if (op < 40) {
      auto id = doc->moveBy(std::span(&v, 1), Vec3(uniform(-.1, .1), uniform(-.1, .1), uniform(-.1, .1)));
      ASSERT_TRUE(id.isOk()) << id.status().message();
      made.push_back(*id);
      what = "move " + v.toString();
    } else if (op < 52) {
      auto id = doc->moveToLimit(std::span(&v, 1), Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
      ASSERT_TRUE(id.isOk()) << id.status().message();
      made.push_back(*id);
      what = "drag " + v.toString();
    } else if (op < 66) {
      const EdgeId e(level, pick(doc->counts().edges(level)));
      const float sharpness = std::array<float, 5>{0.0f, 0.5f, 1.5f, 3.0f, kSharpnessInfinite}[pick(5)];
      auto id = doc->setEdgeSharpness(e, sharpness);
      if (!id.isOk()) {
        EXPECT_NE(id.status().message().find("boundary"), std::string::npos) << id.status().message();
        continue;
      }
      made.push_back(*id);
      what = "crease " + e.toString();
    } else if (op < 74) {
      auto id = doc->setVertexSharpness(v, std::array<float, 3>{0.0f, 1.5f, kSharpnessInfinite}[pick(3)]);
      ASSERT_TRUE(id.isOk()) << id.status().message();
      made.push_back(*id);
      what = "corner " + v.toString();
    } else if (!made.empty()) {
      const EditId id = made[pick(made.size())];
      Status s = op < 86 ? doc->undo(id) : (op < 97 ? doc->redo(id) : doc->remove(id));
      if (!s.isOk()) continue;  // undoing an undone edit, or one removed
      what = (op < 86 ? "undo " : op < 97 ? "redo " : "remove ") + id.toString();
    } else {
      continue;
    }
    ++applied;
    expectMatchesDense(*doc, c.mesh.name + " step " + std::to_string(step) + " (" + what + ")");
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(applied, c.steps / 2);
}

TEST(CatmarkDocument, RandomHistoriesMatchTheDenseReferenceAtEveryStep) {
  using namespace testing;
  const LoopOptions chaikin{CreaseMethod::kChaikin, BoundaryInterpolation::kEdgeOnly};
  const LoopOptions corners{CreaseMethod::kUniform, BoundaryInterpolation::kEdgeAndCorner};
  const std::vector<HistoryCase> cases = {
      {quadCube(), {}, 0, 250, 0},
      {withRandomPolyTags(withPolyJitter(quadTorus(6, 4), 0.05, 3), 0.2, 0.1, 7), chaikin, 1, 250, 0},
      {withPolyJitter(quadGrid(5, 4), 0.05, 7), corners, 0, 250, 3},
      {withRandomPolyTags(withPolyJitter(mixedPrism(6, true), 0.05, 5), 0.3, 0.2, 11), {}, 0, 250, 2},
      {withPolyJitter(mixedPrism(5, false), 0.05, 12), chaikin, 2, 150, 0},
  };
  uint32_t seed = 1;
  for (const HistoryCase& c : cases) {
    SCOPED_TRACE(c.mesh.name);
    runRandomHistory(c, seed++);
    if (HasFailure()) return;
  }
}

// What the Loop numbering and the quad numbering say of boundary edges at
// every level (docs/ARCHITECTURE.md "Numbering"): a crease is refused on
// exactly the edges the uniform level has on its boundary.
TEST(CatmarkDocument, BoundaryEdgesAreRefusedAtEveryLevelAndOnlyThere) {
  const PolyTestMesh mesh = testing::withPolyJitter(testing::mixedPrism(5, true), 0.05, 9);
  auto doc = Document::create(mesh.topology, mesh.points, catmark());
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  auto dense = doc->evaluate(3);
  ASSERT_TRUE(dense.isOk());
  int boundary = 0;
  for (int l = 0; l <= 3; ++l) {
    const Level& level = (*dense)->levels[l];
    for (Index e = 0; e < level.numEdges(); ++e) {
      auto id = doc->setEdgeSharpness(EdgeId(l, static_cast<uint64_t>(e)), 1.0f);
      ASSERT_EQ(id.isOk(), !level.isBoundaryEdge(e)) << "e" << l << ":" << e;
      if (id.isOk()) {
        ASSERT_TRUE(doc->remove(*id).isOk());
      } else {
        EXPECT_NE(id.status().message().find("e" + std::to_string(l) + ":" + std::to_string(e) +
                                             " lies on the boundary"),
                  std::string::npos)
            << id.status().message();
        ++boundary;
      }
    }
  }
  EXPECT_GT(boundary, 0);
}

Document editedCatmarkDocument() {
  const PolyTestMesh mesh = testing::withRandomPolyTags(
      testing::withPolyJitter(testing::mixedPrism(6, true), 0.05, 4), 0.3, 0.1, 5);
  auto doc = Document::create(mesh.topology, mesh.points,
                              catmark({CreaseMethod::kChaikin, BoundaryInterpolation::kEdgeAndCorner}));
  if (!doc.isOk()) throw std::runtime_error(doc.status().toString());
  auto a = doc->moveToLimit(std::vector<VertexId>{VertexId(2, 40)}, Vec3(0.3, 0.1, 0.4));
  auto b = doc->moveBy(std::vector<VertexId>{VertexId(3, 7), VertexId(3, 300)}, Vec3(1e-3, 2e-3, -0.1 / 3.0));
  auto c = doc->setEdgeSharpness(EdgeId(1, 5), 1.5f);
  auto d = doc->setVertexSharpness(VertexId(4, 900), kSharpnessInfinite);
  if (!a.isOk() || !b.isOk() || !c.isOk() || !d.isOk()) throw std::runtime_error("edit failed");
  if (!doc->undo(*c).isOk()) throw std::runtime_error("undo failed");
  return std::move(doc).value();
}

// A restart: the file holds the scheme, the polygons and the edits, and
// the document read back shows the same surfaces, bit for bit.
TEST(CatmarkDocument, TheFileKeepsSchemePolygonsAndEditsBitForBit) {
  const Document doc = editedCatmarkDocument();
  const std::string bytes = serializeDocument(doc);
  uint32_t version = 0;
  std::memcpy(&version, bytes.data() + 8, 4);
  EXPECT_EQ(version, 3u);
  auto back = deserializeDocument(bytes, "cc.tsd");
  ASSERT_TRUE(back.isOk()) << back.status().toString();
  EXPECT_EQ(back->scheme(), DocumentScheme::kCatmullClark);
  EXPECT_EQ(serializeDocument(*back), bytes);
  EXPECT_EQ(back->polygonTopology().faceOffsets, doc.polygonTopology().faceOffsets);
  EXPECT_EQ(back->polygonTopology().indices, doc.polygonTopology().indices);
  for (int level : {0, 2, 4}) {
    for (SurfaceKind kind : {SurfaceKind::kControl, SurfaceKind::kLimit}) {
      auto a = doc.surface(level, kind);
      auto b = back->surface(level, kind);
      ASSERT_EQ(a.isOk(), b.isOk());
      if (!a.isOk()) continue;  // level 0's limit: the base has other polygons than quads
      EXPECT_EQ(a->positions, b->positions) << "level " << level;  // bit for bit
      EXPECT_EQ(a->normals, b->normals) << "level " << level;
      EXPECT_EQ(a->polygonCorners, b->polygonCorners) << "level " << level;
    }
  }
  // The hierarchy read back holds what the one edited step by step held,
  // vertex for vertex by canonical id.
  ASSERT_EQ(back->hierarchy().numLevels(), doc.hierarchy().numLevels());
  long long compared = 0;
  for (int l = 0; l < doc.hierarchy().numLevels(); ++l) {
    std::map<uint64_t, Vec3> held;
    const SparseLevel& level = doc.hierarchy().level(l);
    for (Index v = 0; v < level.mesh.numVertices; ++v)
      held[level.vertexIds[v]] = doc.hierarchy().points(l)[v];
    const SparseLevel& levelBack = back->hierarchy().level(l);
    for (Index v = 0; v < levelBack.mesh.numVertices; ++v) {
      auto it = held.find(levelBack.vertexIds[v]);
      if (it == held.end()) continue;
      ASSERT_EQ(it->second, back->hierarchy().points(l)[v]) << "v" << l << ":" << levelBack.vertexIds[v];
      ++compared;
    }
  }
  EXPECT_GT(compared, 100);
}

// A Loop document is still written as format 2, which builds that know no
// other scheme read; format 2 has no scheme byte, and a Catmull-Clark
// payload under a version-2 header is refused.
TEST(CatmarkDocument, LoopFilesStayFormatTwoAndOldHeadersCannotCarryAScheme) {
  const testing::TestMesh mesh = testing::torus(6, 4);
  auto loop = Document::create(mesh.topology, mesh.points, {.maxLevel = 3});
  ASSERT_TRUE(loop.isOk());
  const std::string loopBytes = serializeDocument(*loop);
  EXPECT_EQ(loopBytes[8], 2);
  std::string cc = serializeDocument(editedCatmarkDocument());
  cc[8] = 2;
  auto refused = deserializeDocument(cc, "cc.tsd");
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("cc.tsd: bad options"), std::string::npos)
      << refused.status().message();
}

TEST(CatmarkDocument, WhatOnlyLoopDefinesIsRefusedByName) {
  const PolyTestMesh cube = testing::quadCube();
  // A Loop document takes triangles.
  auto loop = Document::create(cube.topology, cube.points, {.maxLevel = 3});
  ASSERT_FALSE(loop.isOk());
  EXPECT_NE(loop.status().message().find("face 0 has 4 corners: a Loop document takes triangles only"),
            std::string::npos)
      << loop.status().message();
  auto doc = Document::create(cube.topology, cube.points, catmark());
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  // Ghost rings (interpolating vertices) are Loop's.
  auto tag = doc->setInterpolation(VertexId(1, 3), true, 1.0);
  ASSERT_FALSE(tag.isOk());
  EXPECT_NE(tag.status().message().find("v1:3: interpolating vertices are defined for Loop documents only"),
            std::string::npos)
      << tag.status().message();
  EXPECT_TRUE(doc->edits().empty());
  // Morph keys are Loop documents.
  KeyedDocument keyed(std::move(*doc));
  std::vector<Vec3> moved = cube.points;
  for (Vec3& p : moved) p *= 1.5;
  Status second = keyed.addKey(moved, {});
  ASSERT_FALSE(second.isOk());
  EXPECT_NE(second.message().find("key 0 is a catmull-clark document: morph keys are Loop documents"),
            std::string::npos)
      << second.message();
  // The level-0 limit of a base with a triangle or a pentagon is refused, naming the level.
  const PolyTestMesh prism = testing::mixedPrism(5, false);
  auto mixed = Document::create(prism.topology, prism.points, catmark());
  ASSERT_TRUE(mixed.isOk());
  auto limit = mixed->surface(0, SurfaceKind::kLimit);
  ASSERT_FALSE(limit.isOk());
  EXPECT_NE(limit.status().message().find("level 0: the Catmull-Clark limit needs a level of quads"),
            std::string::npos)
      << limit.status().message();
  EXPECT_TRUE(mixed->surface(1, SurfaceKind::kLimit).isOk());
}

// A polygon file as a client sends it, mutated (digits changed, lines
// dropped or repeated, a face's index replaced): the polygon import and a
// Catmull-Clark document of what it lets through either refuse with an error
// that is not internal, or give a document whose limit surface at level 2
// evaluates. The same path as a CreateDocument with faces that are not
// triangles (server/document/mesh_intake.cc).
TEST(CatmarkDocument, MutatedPolygonFilesAreRefusedOrBecomeDocuments) {
  std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nv 0.5 0.5 1.4\n"
      "f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\nf 5 6 9\nf 6 7 9\nf 7 8 9\nf 8 5 9\n"
      "t crease 2/1/0 5 6 1.5\nt corner 1/1/0 0 2\n";
  std::mt19937 rng(5);
  int documents = 0, refused = 0;
  for (int i = 0; i < 3000; ++i) {
    std::vector<std::string> lines;
    for (size_t at = 0, next; at < obj.size(); at = next + 1) {
      next = obj.find('\n', at);
      lines.push_back(obj.substr(at, next - at));
    }
    for (int k = 0; k < 1 + static_cast<int>(rng() % 3); ++k) {
      std::string& line = lines[rng() % lines.size()];
      switch (rng() % 4) {
        case 0:  // a digit changed
          for (char& c : line)
            if (std::isdigit(static_cast<unsigned char>(c)) && rng() % 3 == 0)
              c = static_cast<char>('0' + rng() % 10);
          break;
        case 1:  // a line dropped
          line.clear();
          break;
        case 2:  // a line repeated
          lines.push_back(line);
          break;
        default:  // a face's corner repeated or a vertex index out of range
          if (line.starts_with("f ")) line += rng() % 2 ? " 1" : " 12";
      }
    }
    std::string text;
    for (const std::string& line : lines) text += line + "\n";
    auto mesh = schemes::importPolygonMeshFromBytes(text, ".obj", "mutated.obj");
    if (!mesh.isOk()) {
      EXPECT_NE(mesh.status().code(), ErrorCode::kInternal) << mesh.status().toString();
      EXPECT_NE(mesh.status().message().find("mutated.obj"), std::string::npos) << mesh.status().message();
      ++refused;
      continue;
    }
    auto doc = Document::create(std::move(mesh->topology), std::move(mesh->points), catmark({}, 0));
    if (!doc.isOk()) {
      EXPECT_NE(doc.status().code(), ErrorCode::kInternal) << doc.status().toString() << "\n" << text;
      ++refused;
      continue;
    }
    auto limit = doc->surface(2, SurfaceKind::kLimit);
    EXPECT_TRUE(limit.isOk() || limit.status().code() != ErrorCode::kInternal) << limit.status().toString();
    ++documents;
  }
  EXPECT_GT(documents, 300);
  EXPECT_GT(refused, 300);
  std::printf("[ measured ] 3000 mutated polygon files: %d documents, %d refused by name\n", documents,
              refused);
}

}  // namespace
}  // namespace tessera

// Region lattices (core/tessellation/region_lattice.h): the id the lattice
// gives each point of a region's root face is the canonical id the sparse
// hierarchy computes for the vertex there, on whole uniform levels of
// several meshes, for root faces at levels 0 and 1 and depths up to 4.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include <map>
#include <random>
#include <set>

#include "core/document/document.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/region_codec.h"
#include "core/tessellation/region_lattice.h"
#include "core/tessellation/tessellation.h"
#include "support/polygon_meshes.h"
#include "support/procedural_meshes.h"
#include "support/region_checks.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using Point = std::array<int, 2>;
using testing::refreshRegionChecksum;
using testing::trianglesOverIds;

// The corner points of child k of a face with corners `at` (refinement.h:
// children 0..2 at the corners, 3 in the middle).
std::array<Point, 3> childCorners(const std::array<Point, 3>& at, int k) {
  auto mid = [&](int a, int b) { return Point{(at[a][0] + at[b][0]) / 2, (at[a][1] + at[b][1]) / 2}; };
  const Point m0 = mid(0, 1), m1 = mid(1, 2), m2 = mid(2, 0);
  switch (k) {
    case 0:
      return {at[0], m0, m2};
    case 1:
      return {m0, at[1], m1};
    case 2:
      return {m2, m1, at[2]};
    default:
      return {m1, m2, m0};
  }
}

void expectLatticeMatchesHierarchy(const testing::TestMesh& mesh, int rootLevel, int depth) {
  const int deepest = rootLevel + depth;
  auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = deepest, .uniformLevel = deepest});
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  const SparseHierarchy& h = doc->hierarchy();
  const LevelCounts& counts = doc->counts();
  const int n = 1 << depth;
  int checked = 0;
  for (uint64_t root = 0; root < counts.faces(rootLevel); ++root) {
    const FaceId face(rootLevel, root);
    auto frame = regionFrame(h, counts, face);
    ASSERT_TRUE(frame.isOk()) << frame.status().message();
    auto lattice = RegionLattice::build(*frame, depth);
    ASSERT_TRUE(lattice.isOk()) << lattice.status().message();
    // Every descendant face at the deepest level, found by its path of
    // child numbers, with the corner points that path gives.
    for (uint64_t path = 0; path < (uint64_t{1} << (2 * depth)); ++path) {
      std::array<Point, 3> at{Point{0, 0}, Point{n, 0}, Point{0, n}};
      for (int d = depth - 1; d >= 0; --d) at = childCorners(at, static_cast<int>((path >> (2 * d)) & 3));
      const uint64_t canonical = (root << (2 * depth)) | path;
      const Index local = h.level(deepest).findFace(canonical);
      ASSERT_GE(local, 0);
      for (int k = 0; k < 3; ++k) {
        const uint64_t index = h.level(deepest).vertexIds[h.level(deepest).mesh.triangleVertices(local)[k]];
        const auto id = lattice->idAt(at[k][0], at[k][1]);
        ASSERT_TRUE(id.has_value());
        ASSERT_EQ(id->index(), index)
            << mesh.name << " root " << face.toString() << " point (" << at[k][0] << ", " << at[k][1] << ")";
        ASSERT_EQ(id->level(), counts.birthLevel(*id));
        ASSERT_EQ(lattice->pointOf(*id), at[k]);
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 0);
}

TEST(RegionLattice, IdsEqualTheHierarchysOnUniformLevels) {
  for (const auto& mesh : {testing::icosahedron(), testing::torus(5, 4), testing::openGrid(3, 2)}) {
    for (int rootLevel : {0, 1}) {
      for (int depth : {0, 1, 2, 4}) {
        expectLatticeMatchesHierarchy(mesh, rootLevel, depth);
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  }
}

// The corner points of child j of a quad with corners `at` (quad_split.h:
// child j at corner j keeps it at position j; then the vertex on edge j, the
// face vertex and the vertex on edge j - 1), as docs/PROTOCOL.md 6.2 states.
std::array<Point, 4> quadChildCorners(const std::array<Point, 4>& at, int j) {
  auto mid = [](const Point& a, const Point& b) { return Point{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2}; };
  const int prev = (j + 3) & 3;
  const std::array<Point, 4> byKind{at[j], mid(at[j], at[(j + 1) & 3]), mid(at[0], at[2]),
                                    mid(at[prev], at[j])};
  std::array<Point, 4> child;
  for (int k = 0; k < 4; ++k) child[(j + k) & 3] = byKind[k];
  return child;
}

// The same on Catmull-Clark documents: every quad root face of a level, its
// every descendant at the deepest level by its path of child numbers, each
// corner's lattice id against the hierarchy's id of that corner. Returns the
// number of points checked.
int expectQuadLatticeMatchesHierarchy(const testing::PolyTestMesh& mesh, int rootLevel, int depth) {
  const int deepest = rootLevel + depth;
  auto doc = Document::create(
      mesh.topology, mesh.points,
      {.maxLevel = deepest, .uniformLevel = deepest, .scheme = DocumentScheme::kCatmullClark});
  EXPECT_TRUE(doc.isOk()) << doc.status().message();
  if (!doc.isOk()) return 0;
  const SparseHierarchy& h = doc->hierarchy();
  const LevelCounts& counts = doc->counts();
  const int n = 1 << depth;
  int checked = 0;
  for (uint64_t root = 0; root < counts.faces(rootLevel); ++root) {
    const FaceId face(rootLevel, root);
    auto frame = regionFrame(h, counts, face);
    if (counts.faceSize(face) != 4) {
      EXPECT_EQ(frame.status().code(), ErrorCode::kUnsupported) << face.toString();
      continue;
    }
    EXPECT_TRUE(frame.isOk()) << frame.status().message();
    if (!frame.isOk()) return checked;
    EXPECT_EQ(frame->sides, 4);
    auto lattice = RegionLattice::build(*frame, depth);
    EXPECT_TRUE(lattice.isOk()) << lattice.status().message();
    if (!lattice.isOk()) return checked;
    for (uint64_t path = 0; path < (uint64_t{1} << (2 * depth)); ++path) {
      std::array<Point, 4> at{Point{0, 0}, Point{n, 0}, Point{n, n}, Point{0, n}};
      FaceId f = face;
      for (int d = depth - 1; d >= 0; --d) {
        const int j = static_cast<int>((path >> (2 * d)) & 3);
        at = quadChildCorners(at, j);
        f = counts.childFace(f, j);
      }
      const SparseLevel& level = h.level(deepest);
      const Index local = level.findFace(f.index());
      EXPECT_GE(local, 0) << f.toString();
      if (local < 0) return checked;
      for (int k = 0; k < 4; ++k) {
        const uint64_t index = level.vertexIds[level.mesh.faceVerticesOf(local)[k]];
        const auto id = lattice->idAt(at[k][0], at[k][1]);
        EXPECT_TRUE(id.has_value());
        if (!id) return checked;
        EXPECT_EQ(id->index(), index)
            << mesh.name << " root " << face.toString() << " point (" << at[k][0] << ", " << at[k][1] << ")";
        EXPECT_EQ(id->level(), counts.birthLevel(*id));
        EXPECT_EQ(lattice->pointOf(*id), at[k]);
        if (id->index() != index) return checked;
        ++checked;
      }
    }
    EXPECT_FALSE(lattice->idAt(n + 1, 0).has_value());
    EXPECT_TRUE(lattice->idAt(n, n).has_value());
  }
  return checked;
}

TEST(RegionLattice, QuadIdsEqualTheHierarchysOnUniformLevels) {
  using namespace testing;
  int checked = 0;
  // Quads, a closed mesh of triangles, quads and an n-gon (a prism), an open
  // one, and a jittered torus; root faces at levels 0 (the base quads) and
  // 1 and 2 (every face a quad).
  for (const PolyTestMesh& mesh : {quadCube(), mixedPrism(5, false), mixedPrism(6, true), quadGrid(3, 2),
                                   withPolyJitter(quadTorus(5, 4), 0.05, 3)}) {
    for (int rootLevel : {0, 1, 2}) {
      for (int depth : {0, 1, 2, 3}) {
        checked += expectQuadLatticeMatchesHierarchy(mesh, rootLevel, depth);
        if (::testing::Test::HasFailure()) return;
      }
    }
  }
  EXPECT_GT(checked, 100000);
}

TEST(RegionLattice, RefusesBadDepthsAndFrames) {
  const auto mesh = testing::icosahedron();
  auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = 3, .uniformLevel = 1});
  ASSERT_TRUE(doc.isOk());
  auto frame = regionFrame(doc->hierarchy(), doc->counts(), FaceId(1, 7));
  ASSERT_TRUE(frame.isOk());
  EXPECT_EQ(RegionLattice::build(*frame, -1).status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(RegionLattice::build(*frame, kMaxLatticeDepth + 1).status().code(), ErrorCode::kInvalidArgument);
  RegionFrame bad = *frame;
  bad.corners[1] = doc->counts().vertices(1);
  Status status = RegionLattice::build(bad, 2).status();
  EXPECT_NE(status.message().find("corner or edge 1"), std::string::npos) << status.toString();
  bad = *frame;
  bad.face = FaceId(1, doc->counts().faces(1)).packed();
  EXPECT_NE(RegionLattice::build(bad, 2).status().message().find("does not exist"), std::string::npos);
  bad = *frame;
  bad.baseCounts = {uint64_t{1} << 57, uint64_t{1} << 57, uint64_t{1} << 57};
  EXPECT_NE(RegionLattice::build(bad, 3).status().message().find("overflow"), std::string::npos);
  auto lattice = RegionLattice::build(*frame, 2);
  ASSERT_TRUE(lattice.isOk());
  EXPECT_FALSE(lattice->idAt(3, 2).has_value());  // 3 + 2 > 4
  EXPECT_FALSE(lattice->idAt(-1, 0).has_value());
  EXPECT_TRUE(lattice->idAt(4, 0).has_value());
  EXPECT_EQ(RegionLattice::build(*frame, 2)->idAt(0, 0)->index(), frame->corners[0]);
  EXPECT_EQ(regionFrame(doc->hierarchy(), doc->counts(), FaceId(3, 0)).status().code(), ErrorCode::kNotFound);
}

// The first region of an icosahedron's tessellation under `profile`, with
// a header that carries the region's own frame, and the document.
struct IcosahedronRegion {
  std::optional<Document> doc;
  RegionHeader header;
  RegionMesh mesh;
};

void firstIcosahedronRegion(const LodProfile& profile, IcosahedronRegion& out) {
  const auto ico = testing::icosahedron();
  auto doc = Document::create(ico.topology, ico.points, {.maxLevel = 4});
  ASSERT_TRUE(doc.isOk());
  out.doc.emplace(std::move(*doc));
  auto t = Tessellation::build(*out.doc, profile);
  ASSERT_TRUE(t.isOk());
  auto grid = documentGrid(*out.doc);
  ASSERT_TRUE(grid.isOk());
  const auto& [id, region] = *t->regions().begin();
  out.header = {.regionId = id, .documentVersion = 1, .layoutVersion = 1, .profile = profile, .grid = *grid};
  auto frame = regionFrame(out.doc->hierarchy(), out.doc->counts(), FaceId::fromPacked(id));
  ASSERT_TRUE(frame.isOk());
  out.header.frame = *frame;
  out.mesh = region;
}

// Every region of real tessellations (the creased cube after edits, an
// icosahedron at a profile deeper than five levels, whose regions lie at
// level 1) round-trips its ids through lattice points, in fewer bytes.
TEST(RegionLattice, RegionsCarryTheirIdsAsLatticePoints) {
  auto cube = testing::creasedCube();
  ASSERT_TRUE(cube.isOk()) << cube.status().message();
  auto cubeDoc = Document::create(*cube, {.maxLevel = 5});
  ASSERT_TRUE(cubeDoc.isOk());
  for (int i = 0; i < 6; ++i) {
    const VertexId v(2, static_cast<uint64_t>(i * 17 % 98));
    ASSERT_TRUE(cubeDoc->moveBy(std::span(&v, 1), Vec3(0.01 * i, -0.02, 0.015)).isOk());
  }
  const auto ico = testing::icosahedron();
  auto icoDoc = Document::create(ico.topology, ico.points, {.maxLevel = 6});
  ASSERT_TRUE(icoDoc.isOk());
  struct Case {
    Document* doc;
    LodProfile profile;
  };
  for (const Case& c : {Case{&*cubeDoc, {.baseLevel = 2, .maxLevel = 5, .angleThresholdDegrees = 10}},
                        Case{&*icoDoc, {.baseLevel = 2, .maxLevel = 6, .angleThresholdDegrees = 5}}}) {
    auto t = Tessellation::build(*c.doc, c.profile);
    ASSERT_TRUE(t.isOk()) << t.status().message();
    auto grid = documentGrid(*c.doc);
    ASSERT_TRUE(grid.isOk());
    size_t bytesAsIds = 0, bytesAsPoints = 0;
    for (const auto& [id, region] : t->regions()) {
      RegionHeader header{
          .regionId = id, .documentVersion = 3, .layoutVersion = 2, .profile = c.profile, .grid = *grid};
      auto plain = encodeRegion(header, region);
      auto frame = regionFrame(c.doc->hierarchy(), c.doc->counts(), FaceId::fromPacked(id));
      ASSERT_TRUE(frame.isOk()) << frame.status().message();
      header.frame = *frame;
      auto lattice = encodeRegion(header, region);
      ASSERT_TRUE(plain.isOk() && lattice.isOk()) << lattice.status().message();
      bytesAsIds += plain->size();
      bytesAsPoints += lattice->size();
      auto decoded = decodeRegion(*lattice);
      ASSERT_TRUE(decoded.isOk()) << decoded.status().message();
      EXPECT_EQ(decoded->first, header);
      EXPECT_EQ(trianglesOverIds(decoded->second), trianglesOverIds(region))
          << FaceId::fromPacked(id).toString();
    }
    EXPECT_LT(bytesAsPoints, bytesAsIds);
    std::printf(
        "[ measured ] %zu regions, %lld triangles: %zu bytes with 8-byte ids, %zu with lattice points\n",
        t->regions().size(), static_cast<long long>(t->numTriangles()), bytesAsIds, bytesAsPoints);
  }
}

// The regions of Catmull-Clark documents carry their ids as points of their
// quad's lattice (flag 8) and decode to the same triangles over the same ids;
// a region rooted at a base face that is not a quad keeps 8-byte labels.
TEST(RegionLattice, CatmarkRegionsCarryTheirIdsAsQuadLatticePoints) {
  using namespace testing;
  for (const PolyTestMesh& mesh : {withPolyJitter(quadTorus(6, 4), 0.05, 7), mixedPrism(5, true)}) {
    auto doc = Document::create(mesh.topology, mesh.points,
                                {.maxLevel = 6, .scheme = DocumentScheme::kCatmullClark});
    ASSERT_TRUE(doc.isOk()) << doc.status().message();
    for (int i = 0; i < 5; ++i) {
      const VertexId v(1 + i % 2, static_cast<uint64_t>(i * 7 % doc->counts().vertices(1)));
      ASSERT_TRUE(doc->moveBy(std::span(&v, 1), Vec3(0.02 * i, -0.03, 0.01)).isOk());
    }
    auto grid = documentGrid(*doc);
    ASSERT_TRUE(grid.isOk());
    // Regions at level 1 (max level 6) and at the base faces (max level 5).
    for (const LodProfile& profile :
         {LodProfile{.baseLevel = 2, .maxLevel = 6, .angleThresholdDegrees = 5},
          LodProfile{.baseLevel = 1, .maxLevel = 5, .angleThresholdDegrees = 5}}) {
      auto t = Tessellation::build(*doc, profile);
      ASSERT_TRUE(t.isOk()) << t.status().message();
      ASSERT_FALSE(t->regionsAreGroups());
      size_t bytesAsIds = 0, bytesAsPoints = 0;
      int framed = 0, labelled = 0;
      for (const auto& [id, region] : t->regions()) {
        RegionHeader header{
            .regionId = id, .documentVersion = 3, .layoutVersion = 2, .profile = profile, .grid = *grid};
        auto plain = encodeRegion(header, region);
        ASSERT_TRUE(plain.isOk()) << plain.status().message();
        auto frame = regionFrame(doc->hierarchy(), doc->counts(), FaceId::fromPacked(id));
        if (!frame.isOk()) {
          EXPECT_NE(doc->counts().faceSize(FaceId::fromPacked(id)), 4) << frame.status().message();
          ++labelled;
          continue;
        }
        header.frame = *frame;
        auto lattice = encodeRegion(header, region);
        ASSERT_TRUE(lattice.isOk()) << lattice.status().message();
        EXPECT_EQ(static_cast<uint8_t>((*lattice)[6]), 8) << "flags";
        bytesAsIds += plain->size();
        bytesAsPoints += lattice->size();
        auto decoded = decodeRegion(*lattice);
        ASSERT_TRUE(decoded.isOk()) << decoded.status().message();
        EXPECT_EQ(decoded->first, header);
        EXPECT_EQ(trianglesOverIds(decoded->second), trianglesOverIds(region))
            << FaceId::fromPacked(id).toString();
        ++framed;
      }
      EXPECT_GT(framed, 0);
      EXPECT_LT(bytesAsPoints, bytesAsIds);
      std::printf(
          "[ measured ] %s, profile %s: %d regions on quad lattices (%zu bytes, %zu with 8-byte ids), %d "
          "with labels\n",
          mesh.name.c_str(), profile.describe().c_str(), framed, bytesAsPoints, bytesAsIds, labelled);
    }
  }
}

// A frame that names another region, and flags that combine two ways of
// carrying ids, are refused.
TEST(RegionLattice, RefusesFramesOfOtherRegionsAndMixedFlags) {
  IcosahedronRegion r;
  // Deepest level 4: a region per base face, which has a frame.
  firstIcosahedronRegion({.baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 10}, r);
  if (::testing::Test::HasFatalFailure()) return;
  auto other = regionFrame(r.doc->hierarchy(), r.doc->counts(), FaceId(0, 5));
  ASSERT_TRUE(other.isOk());
  RegionHeader foreign = r.header;
  foreign.frame = *other;
  Status status = encodeRegion(foreign, r.mesh).status();
  EXPECT_EQ(status.code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(status.message().find("the frame is that of region"), std::string::npos) << status.toString();

  auto bytes = encodeRegion(r.header, r.mesh);
  ASSERT_TRUE(bytes.isOk());
  std::string mixed = *bytes;
  mixed[6] = 6;  // layout ids and lattice ids
  refreshRegionChecksum(mixed);
  status = decodeRegion(mixed).status();
  EXPECT_EQ(status.code(), ErrorCode::kParseError);
  EXPECT_NE(status.message().find("more than one way"), std::string::npos) << status.toString();
  std::string moved = *bytes;
  ASSERT_EQ(FaceId::fromPacked(r.header.regionId), FaceId(0, 0));
  moved[kRegionHeaderBytes + 1] = 5;  // the frame's face index (a one-byte varint here)
  refreshRegionChecksum(moved);
  status = decodeRegion(moved).status();
  EXPECT_EQ(status.code(), ErrorCode::kParseError);
  EXPECT_NE(status.message().find("the frame names region"), std::string::npos) << status.toString();
  // A face index longer than any 64-bit varint.
  std::string overlong = bytes->substr(0, kRegionHeaderBytes + 1) + std::string(10, '\xff') + '\x01' +
                         bytes->substr(kRegionHeaderBytes + 2);
  status = decodeRegion(overlong).status();
  EXPECT_EQ(status.code(), ErrorCode::kParseError);
  EXPECT_NE(status.message().find("the frame's face is not a 64-bit varint"), std::string::npos)
      << status.toString();
}

// Random byte changes behind a valid checksum, in the frame and the Draco
// payload of a lattice-coded region: every decode ends in a clear error or
// a region whose ids are lattice ids of its face, never a crash (run under
// the sanitizers in the asan preset).
// 2,000 mutations of a region payload after its header (one to three bytes;
// every other one within the first `frameBytes` after the header when that
// is not 0), each with its CRC-32 recomputed: each is refused as a parse
// error or decodes to a region with one id per position. How many decoded.
int decodedMutations(const std::string& bytes, uint32_t seed, size_t frameBytes) {
  std::mt19937 rng(seed);
  int decoded = 0;
  for (int i = 0; i < 2000; ++i) {
    std::string b = bytes;
    const size_t from = kRegionHeaderBytes, span = frameBytes && i % 2 ? frameBytes : b.size() - 4 - from;
    for (int k = 0; k < 1 + static_cast<int>(rng() % 3); ++k)
      b[from + rng() % span] = static_cast<char>(rng());
    refreshRegionChecksum(b);
    auto result = decodeRegion(b);
    if (!result.isOk()) {
      EXPECT_EQ(result.status().code(), ErrorCode::kParseError) << result.status().toString();
      continue;
    }
    ++decoded;
    EXPECT_EQ(result->second.vertexIds.size(), result->second.positions.size());
  }
  return decoded;
}

TEST(RegionLattice, MutatedLatticeRegionsNeverCrash) {
  IcosahedronRegion r;
  firstIcosahedronRegion({.baseLevel = 1, .maxLevel = 4, .angleThresholdDegrees = 10}, r);
  if (::testing::Test::HasFatalFailure()) return;
  auto bytes = encodeRegion(r.header, r.mesh);
  ASSERT_TRUE(bytes.isOk());
  const int decoded = decodedMutations(*bytes, 17, 0);
  std::printf("[ measured ] %d of 2000 mutations decoded to a valid region\n", decoded);
}

// The same for a quad lattice region (flag 8): mutations of its frame and
// payload, the CRC-32 recomputed, are refused as parse errors or decode to a
// consistent region, never anything else.
TEST(RegionLattice, MutatedQuadLatticeRegionsNeverCrash) {
  const auto mesh = testing::withPolyJitter(testing::quadTorus(6, 4), 0.05, 7);
  auto doc =
      Document::create(mesh.topology, mesh.points, {.maxLevel = 5, .scheme = DocumentScheme::kCatmullClark});
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  const LodProfile profile{.baseLevel = 1, .maxLevel = 5, .angleThresholdDegrees = 10};
  auto t = Tessellation::build(*doc, profile);
  ASSERT_TRUE(t.isOk());
  auto grid = documentGrid(*doc);
  ASSERT_TRUE(grid.isOk());
  const auto& [id, region] = *t->regions().begin();
  RegionHeader header{
      .regionId = id, .documentVersion = 3, .layoutVersion = 2, .profile = profile, .grid = *grid};
  header.frame = regionFrame(doc->hierarchy(), doc->counts(), FaceId::fromPacked(id)).value();
  auto bytes = encodeRegion(header, region);
  ASSERT_TRUE(bytes.isOk()) << bytes.status().message();
  ASSERT_EQ((*bytes)[6], 8);
  // Half the mutations in the frame (right after the header), half anywhere after it.
  const int decoded = decodedMutations(*bytes, 23, 24);
  std::printf("[ measured ] %d of 2000 quad lattice mutations decoded to a valid region\n", decoded);
}

}  // namespace
}  // namespace tessera

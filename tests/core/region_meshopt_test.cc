// The meshopt region codec (docs/REGION_ENCODING.md, "meshopt regions"):
// round trips on several shapes against the input (positions within the
// grid's stated bound, the same triangles over the same ids, exactly),
// lattice ids from a real document's regions, layouts adopted in the
// decoded order, the same decoded floats as a Draco region of the same
// mesh, and refusal of truncated, corrupted and foreign payloads.
//
// Normal bound: the octahedral square has a step of 2 / (2^bits - 2), as
// Draco's, so rounding moves a normal at most sqrt(2) / (2^bits - 2) there,
// stretched at most 3x back onto the sphere: Draco's stated bound
// 3 sqrt(2) / (2^bits - 2) (region_codec_test.cc), plus 2% for float32.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "core/document/document.h"
#include "core/hierarchy/ids.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/region_codec.h"
#include "core/tessellation/region_lattice.h"
#include "core/tessellation/tessellation.h"
#include "support/region_checks.h"
#include "support/region_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using testing::refreshRegionChecksum;
using testing::trianglesOverIds;

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

double normalBoundDegrees(int bits) {
  return 1.02 * 3.0 * std::sqrt(2.0) / (std::ldexp(1.0, bits) - 2.0) * kDegrees;
}

double angleDegrees(const Vec3& a, const Vec3& b) {
  return std::atan2(cross(a, b).norm(), dot(a, b)) * kDegrees;
}

// A region with its grid, made from an input whose values the test knows.
struct Shape {
  std::string name;
  RegionMesh mesh;
  QuantizationGrid grid;
};

QuantizationGrid gridAround(const RegionMesh& m) {
  Vec3 lo = m.positions[0], hi = m.positions[0];
  for (const Vec3& p : m.positions) lo.minimize(p), hi.maximize(p);
  auto grid = gridFor(lo, hi);
  EXPECT_TRUE(grid.isOk()) << grid.status().toString();
  return *grid;
}

// Random triangles over random points and random normals in a thin slab
// far from the origin, with extreme ids: nothing the codec could predict.
RegionMesh randomSoup(uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(99.0, 101.0), z(-0.01, 0.01), n(-1.0, 1.0);
  RegionMesh m;
  const int count = 600;
  for (int i = 0; i < count; ++i) {
    m.positions.emplace_back(x(rng), x(rng), z(rng));
    Vec3 normal(n(rng), n(rng), n(rng));
    if (normal.norm() < 1e-3) normal = Vec3(0, 0, -1);
    m.normals.push_back(normal.normalized());
    m.vertexIds.push_back(rng());
  }
  m.vertexIds[0] = 0;
  m.vertexIds[1] = ~uint64_t{0};
  m.vertexIds[2] = uint64_t{1} << 63;
  for (int i = 0; i + 2 < count; i += 3) m.triangles.push_back({i, i + 1, i + 2});
  for (int i = 0; i + 5 < count; i += 5) m.triangles.push_back({i + 5, i + 1, i});
  return m;
}

std::vector<Shape> shapes() {
  std::vector<Shape> out;
  for (RegionMesh m : {testing::torusLimitRegion(1), testing::torusLimitRegion(3), testing::bowTieAndIsland(),
                       randomSoup(7)}) {
    const QuantizationGrid grid = gridAround(m);
    out.push_back({"shape " + std::to_string(out.size()), std::move(m), grid});
  }
  out[0].name = "torus limit, level 1";
  out[1].name = "torus limit, level 3";
  out[2].name = "bow tie and island";
  out[3].name = "random soup at (100, 100, 0)";
  return out;
}

RegionHeader headerWith(const QuantizationGrid& grid, RegionCodec codec) {
  RegionHeader h;
  h.regionId = 0x0123456789ABCDEFull;
  h.documentVersion = 12;
  h.layoutVersion = 9;
  h.profile.baseLevel = 1;
  h.profile.maxLevel = 4;
  h.profile.angleThresholdDegrees = 7.5;
  h.grid = grid;
  h.codec = codec;
  return h;
}

// Position and normal errors against the input, matched by id (unique ids).
void expectWithinBounds(const RegionMesh& input, const RegionMesh& decoded, const QuantizationGrid& grid) {
  std::map<uint64_t, size_t> byId;
  for (size_t i = 0; i < input.vertexIds.size(); ++i) byId[input.vertexIds[i]] = i;
  ASSERT_EQ(byId.size(), input.vertexIds.size()) << "the test needs unique ids";
  for (size_t i = 0; i < decoded.vertexIds.size(); ++i) {
    auto it = byId.find(decoded.vertexIds[i]);
    ASSERT_NE(it, byId.end()) << "decoded id " << decoded.vertexIds[i];
    EXPECT_LE((decoded.positions[i] - input.positions[it->second]).norm(), grid.maxPositionError()) << i;
    EXPECT_LE(angleDegrees(decoded.normals[i], input.normals[it->second]),
              normalBoundDegrees(grid.normalBits))
        << i;
    EXPECT_NEAR(decoded.normals[i].norm(), 1.0, 1e-12);
  }
}

TEST(RegionMeshopt, RoundTripOnSeveralShapesKeepsHeaderIdsAndTriangles) {
  for (const Shape& s : shapes()) {
    SCOPED_TRACE(s.name);
    const RegionHeader header = headerWith(s.grid, RegionCodec::kMeshopt);
    auto bytes = encodeRegion(header, s.mesh);
    ASSERT_TRUE(bytes.isOk()) << bytes.status().toString();
    EXPECT_EQ(bytes->substr(0, 4), "TSRM");
    auto decoded = decodeRegion(*bytes);
    ASSERT_TRUE(decoded.isOk()) << decoded.status().toString();
    EXPECT_EQ(decoded->first, header);
    EXPECT_EQ(decoded->second.positions.size(), s.mesh.positions.size());
    EXPECT_EQ(trianglesOverIds(decoded->second), trianglesOverIds(s.mesh));
    EXPECT_EQ(std::multiset<uint64_t>(decoded->second.vertexIds.begin(), decoded->second.vertexIds.end()),
              std::multiset<uint64_t>(s.mesh.vertexIds.begin(), s.mesh.vertexIds.end()));
    expectWithinBounds(s.mesh, decoded->second, s.grid);
  }
}

TEST(RegionMeshopt, DisplayOnlyRegionsKeepTheGeometry) {
  const Shape s = shapes()[1];
  RegionHeader header = headerWith(s.grid, RegionCodec::kMeshopt);
  header.profile.vertexIds = false;
  auto bytes = encodeRegion(header, s.mesh);
  ASSERT_TRUE(bytes.isOk()) << bytes.status().toString();
  RegionHeader withIds = header;
  withIds.profile.vertexIds = true;
  auto full = encodeRegion(withIds, s.mesh);
  ASSERT_TRUE(full.isOk());
  EXPECT_LT(bytes->size(), full->size());
  auto decoded = decodeRegion(*bytes);
  ASSERT_TRUE(decoded.isOk()) << decoded.status().toString();
  EXPECT_EQ(decoded->first, header);
  EXPECT_TRUE(decoded->second.vertexIds.empty());
  // Without ids, positions name the vertices: each decoded vertex is the
  // one input vertex within the bound, and gets its id.
  const double bound = s.grid.maxPositionError();
  RegionMesh named = decoded->second;
  for (const Vec3& p : named.positions) {
    std::vector<size_t> near;
    for (size_t i = 0; i < s.mesh.positions.size(); ++i) {
      if ((s.mesh.positions[i] - p).norm() <= bound) near.push_back(i);
    }
    ASSERT_EQ(near.size(), 1u) << "input vertices within the bound of a decoded one";
    named.vertexIds.push_back(s.mesh.vertexIds[near[0]]);
  }
  EXPECT_EQ(trianglesOverIds(named), trianglesOverIds(s.mesh));
}

TEST(RegionMeshopt, DecodesToTheSameFloatsAsDraco) {
  for (const Shape& s : shapes()) {
    SCOPED_TRACE(s.name);
    auto draco = encodeRegion(headerWith(s.grid, RegionCodec::kDraco), s.mesh);
    auto meshopt = encodeRegion(headerWith(s.grid, RegionCodec::kMeshopt), s.mesh);
    ASSERT_TRUE(draco.isOk() && meshopt.isOk());
    auto a = decodeRegion(*draco);
    auto b = decodeRegion(*meshopt);
    ASSERT_TRUE(a.isOk() && b.isOk());
    std::map<uint64_t, Vec3> byId;
    for (size_t i = 0; i < a->second.vertexIds.size(); ++i)
      byId[a->second.vertexIds[i]] = a->second.positions[i];
    for (size_t i = 0; i < b->second.vertexIds.size(); ++i) {
      auto it = byId.find(b->second.vertexIds[i]);
      ASSERT_NE(it, byId.end());
      EXPECT_EQ(std::memcmp(&it->second, &b->second.positions[i], sizeof(Vec3)), 0)
          << "vertex " << i << ": " << it->second[0] << " vs " << b->second.positions[i][0];
    }
  }
}

TEST(RegionMeshopt, RegionsOfADocumentCarryLatticeIds) {
  auto cube = testing::creasedCube();
  ASSERT_TRUE(cube.isOk()) << cube.status().message();
  auto doc = Document::create(*cube, {.maxLevel = 5});
  ASSERT_TRUE(doc.isOk());
  for (int i = 0; i < 6; ++i) {
    const VertexId v(2, static_cast<uint64_t>(i * 17 % 98));
    ASSERT_TRUE(doc->moveBy(std::span(&v, 1), Vec3(0.01 * i, -0.02, 0.015)).isOk());
  }
  const LodProfile profile{.baseLevel = 2, .maxLevel = 5, .angleThresholdDegrees = 10};
  auto t = Tessellation::build(*doc, profile);
  ASSERT_TRUE(t.isOk()) << t.status().message();
  auto grid = documentGrid(*doc);
  ASSERT_TRUE(grid.isOk());
  size_t lattices = 0;
  for (const auto& [id, region] : t->regions()) {
    RegionHeader header{
        .regionId = id, .documentVersion = 3, .layoutVersion = 2, .profile = profile, .grid = *grid};
    header.codec = RegionCodec::kMeshopt;
    auto frame = regionFrame(doc->hierarchy(), doc->counts(), FaceId::fromPacked(id));
    ASSERT_TRUE(frame.isOk()) << frame.status().message();
    header.frame = *frame;
    auto bytes = encodeRegion(header, region);
    ASSERT_TRUE(bytes.isOk()) << bytes.status().message();
    auto decoded = decodeRegion(*bytes);
    ASSERT_TRUE(decoded.isOk()) << decoded.status().message();
    EXPECT_EQ(decoded->first, header);
    lattices += decoded->first.frame.has_value();
    EXPECT_EQ(trianglesOverIds(decoded->second), trianglesOverIds(region))
        << FaceId::fromPacked(id).toString();
    EXPECT_EQ(std::multiset<uint64_t>(decoded->second.vertexIds.begin(), decoded->second.vertexIds.end()),
              std::multiset<uint64_t>(region.vertexIds.begin(), region.vertexIds.end()));
  }
  EXPECT_EQ(lattices, t->regions().size());
}

TEST(RegionMeshopt, LayoutIdsAreAdoptedInTheDecodedOrder) {
  const Shape s = shapes()[1];
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  RegionMesh moved = s.mesh;
  for (size_t v = 0; v < moved.positions.size(); ++v) moved.positions[v] += moved.normals[v] * jitter(rng);
  const QuantizationGrid grid = gridAround(moved);
  RegionHeader layout = headerWith(grid, RegionCodec::kMeshopt);
  layout.documentVersion = layout.layoutVersion = 7;
  auto heldBytes = encodeRegion(layout, s.mesh);
  ASSERT_TRUE(heldBytes.isOk()) << heldBytes.status().toString();
  auto held = decodeRegion(*heldBytes);
  ASSERT_TRUE(held.isOk());
  RegionHeader later = layout;
  later.documentVersion = 9;
  later.idsInline = false;
  auto thin = encodeRegion(later, moved);
  ASSERT_TRUE(thin.isOk());
  auto decoded = decodeRegion(*thin);
  ASSERT_TRUE(decoded.isOk()) << decoded.status().toString();
  EXPECT_TRUE(decoded->second.vertexIds.empty());
  ASSERT_TRUE(adoptLayoutIds(decoded->first, decoded->second, held->second, 7).isOk());
  // Against the input by id: the adopted ids must be the moved vertices'.
  expectWithinBounds(moved, decoded->second, grid);
  EXPECT_EQ(trianglesOverIds(decoded->second), trianglesOverIds(moved));
}

TEST(RegionMeshopt, RefusesTruncationCorruptionAndForeignStreams) {
  const Shape s = shapes()[2];
  auto encoded = encodeRegion(headerWith(s.grid, RegionCodec::kMeshopt), s.mesh);
  ASSERT_TRUE(encoded.isOk());
  const std::string bytes = *encoded;
  for (size_t length = 0; length < bytes.size(); ++length) {
    auto decoded = decodeRegion(std::string_view(bytes).substr(0, length));
    ASSERT_FALSE(decoded.isOk()) << "length " << length;
    EXPECT_EQ(decoded.status().code(), ErrorCode::kParseError);
  }
  std::mt19937 rng(3);
  for (int i = 0; i < 2000; ++i) {
    std::string bad = bytes;
    bad[rng() % bad.size()] ^= static_cast<char>(1 + rng() % 255);
    EXPECT_FALSE(decodeRegion(bad).isOk()) << "corruption " << i;
  }
  // Behind a valid checksum: a vertex stream of another version, then a
  // vertex count the triangles cannot use, then random payload bytes;
  // refused or decoded to a valid region, never a crash.
  const size_t payloadAt = kRegionHeaderBytes;
  std::string version = bytes;
  version[payloadAt + 8] = static_cast<char>(0xa7);
  refreshRegionChecksum(version);
  auto refused = decodeRegion(version);
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("stream versions"), std::string::npos)
      << refused.status().toString();
  std::string count = bytes;
  const uint32_t tooMany = 10;  // 3 triangles use at most 9 vertices
  std::memcpy(&count[payloadAt], &tooMany, 4);
  refreshRegionChecksum(count);
  refused = decodeRegion(count);
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("10 vertices for 3 triangles"), std::string::npos)
      << refused.status().toString();
  for (int i = 0; i < 3000; ++i) {
    std::string mutated = bytes;
    const size_t at = payloadAt + rng() % (bytes.size() - payloadAt - kRegionTrailerBytes);
    mutated[at] = static_cast<char>(rng());
    refreshRegionChecksum(mutated);
    auto decoded = decodeRegion(mutated);
    if (!decoded.isOk()) continue;
    for (const auto& t : decoded->second.triangles)
      for (int c : t) ASSERT_LT(static_cast<size_t>(c), decoded->second.positions.size());
  }
}

// The vertex count raised by one behind a valid checksum: meshoptimizer's
// vertex codec decodes the bow tie's 8-vertex stream as 9 vertices, the
// last used by no triangle, which no encoder writes (found by the
// region_meshopt fuzz target, docs/FUZZING.md; its corpus keeps the input).
TEST(RegionMeshopt, RefusesAVertexNoTriangleUses) {
  const Shape s = shapes()[2];
  auto encoded = encodeRegion(headerWith(s.grid, RegionCodec::kMeshopt), s.mesh);
  ASSERT_TRUE(encoded.isOk()) << encoded.status().toString();
  std::string bytes = *encoded;
  uint32_t count = 0;
  std::memcpy(&count, &bytes[kRegionHeaderBytes], 4);
  ASSERT_EQ(count, 8u);
  ++count;
  std::memcpy(&bytes[kRegionHeaderBytes], &count, 4);
  refreshRegionChecksum(bytes);
  auto refused = decodeRegion(bytes);
  ASSERT_FALSE(refused.isOk());
  EXPECT_EQ(refused.status().code(), ErrorCode::kParseError);
  EXPECT_NE(refused.status().message().find("vertex 8 of 9 is used by no triangle"), std::string::npos)
      << refused.status().toString();
}

TEST(RegionMeshopt, RefusesNormalsFinerThanItsTwoBytes) {
  Shape s = shapes()[2];
  s.grid.normalBits = 17;
  auto bytes = encodeRegion(headerWith(s.grid, RegionCodec::kMeshopt), s.mesh);
  ASSERT_FALSE(bytes.isOk());
  EXPECT_NE(bytes.status().message().find("17 normal bits"), std::string::npos) << bytes.status().toString();
}

}  // namespace
}  // namespace tessera

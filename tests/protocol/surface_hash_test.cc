// The surface hash of docs/PROTOCOL.md 6.5 (core/tessellation/surface_hash.h):
// the document's worked example, whose values were computed by a separate
// Python implementation of the text (not by this code); invariance under
// the rotations a decoder may choose; and the server's form, computed before
// encoding, equals the client's, computed from the decoded payload, on every
// region of real tessellations (ids as bytes and as lattice points, and
// display-only).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <map>

#include "core/document/document.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/region_codec.h"
#include "core/tessellation/region_lattice.h"
#include "core/tessellation/surface_hash.h"
#include "core/tessellation/tessellation.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

// The example of PROTOCOL.md 6.5.
std::array<HashedCorner, 3> exampleTriangle() {
  return {HashedCorner{VertexId(1, 26).packed(), {2.5f, 0.0f, -0.75f}},
          HashedCorner{VertexId(3, 1234).packed(), {0.25f, -1.5f, 3.0f}},
          HashedCorner{VertexId(0, 7).packed(), {-0.0f, 0.125f, 1.0f}}};
}

TEST(SurfaceHash, MatchesTheDocumentsExample) {
  const auto t = exampleTriangle();
  EXPECT_EQ(triangleHash(t), 0xe453ef2728c8a2b3ull);
  // Without ids (a display-only profile), every id is 0.
  const std::array<HashedCorner, 3> noIds{HashedCorner{0, {1.0f, 2.0f, 3.0f}},
                                          HashedCorner{0, {1.0f, 2.0f, 2.0f}},
                                          HashedCorner{0, {0.5f, 2.0f, 3.0f}}};
  EXPECT_EQ(triangleHash(noIds), 0xfe0234f5371dc0e8ull);
  // The two as a region: the sum modulo 2^64.
  RegionMesh region;
  for (const auto& c : t) {
    region.positions.emplace_back(c.position[0], c.position[1], c.position[2]);
    region.vertexIds.push_back(c.id);
  }
  region.normals.assign(3, Vec3(0, 0, 1));
  region.triangles = {{0, 1, 2}};
  RegionMesh plain;
  for (const auto& c : noIds) plain.positions.emplace_back(c.position[0], c.position[1], c.position[2]);
  plain.normals.assign(3, Vec3(0, 0, 1));
  plain.triangles = {{0, 1, 2}};
  EXPECT_EQ(surfaceHash({{1, region}, {2, plain}}), 0xe256241c5fe6639bull);
}

TEST(SurfaceHash, RotationsAgreeAndOrientationCounts) {
  const auto t = exampleTriangle();
  EXPECT_EQ(triangleHash({t[1], t[2], t[0]}), triangleHash(t));
  EXPECT_EQ(triangleHash({t[2], t[0], t[1]}), triangleHash(t));
  EXPECT_EQ(triangleHash({t[0], t[2], t[1]}), 0x92866d435b9a347bull);  // reversed: another triangle
  auto positiveZero = t;
  positiveZero[2].position[0] = 0.0f;
  EXPECT_EQ(triangleHash(positiveZero), triangleHash(t));
  auto moved = t;
  moved[1].position[2] = std::nextafter(3.0f, 4.0f);
  EXPECT_NE(triangleHash(moved), triangleHash(t));
}

// The server hashes a region before encoding it; a client after decoding it.
TEST(SurfaceHash, ServersFormEqualsTheDecodedRegions) {
  auto cube = testing::creasedCube();
  ASSERT_TRUE(cube.isOk()) << cube.status().message();
  auto doc = Document::create(*cube, {.maxLevel = 5});
  ASSERT_TRUE(doc.isOk());
  for (int i = 0; i < 6; ++i) {
    const VertexId v(2, static_cast<uint64_t>(i * 17 % 98));
    ASSERT_TRUE(doc->moveBy(std::span(&v, 1), Vec3(0.01 * i, -0.02, 0.015)).isOk());
  }
  auto grid = documentGrid(*doc);
  ASSERT_TRUE(grid.isOk());
  for (bool withIds : {true, false}) {
    const LodProfile profile{
        .baseLevel = 2, .maxLevel = 5, .angleThresholdDegrees = 10, .vertexIds = withIds};
    auto t = Tessellation::build(*doc, profile);
    ASSERT_TRUE(t.isOk()) << t.status().message();
    std::map<uint64_t, RegionMesh> decodedAsBytes, decodedAsPoints;
    uint64_t serverSum = 0;
    double encodeSeconds = 0, hashSeconds = 0;  // reported, never asserted
    for (const auto& [id, region] : t->regions()) {
      RegionHeader header{
          .regionId = id, .documentVersion = 7, .layoutVersion = 7, .profile = profile, .grid = *grid};
      auto bytes = encodeRegion(header, region);
      auto frame = regionFrame(doc->hierarchy(), doc->counts(), FaceId::fromPacked(id));
      ASSERT_TRUE(bytes.isOk() && frame.isOk());
      header.frame = *frame;
      const auto encodeStart = std::chrono::steady_clock::now();
      auto points = encodeRegion(header, region);
      encodeSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - encodeStart).count();
      ASSERT_TRUE(points.isOk());
      auto a = decodeRegion(*bytes), b = decodeRegion(*points);
      ASSERT_TRUE(a.isOk() && b.isOk());
      const auto hashStart = std::chrono::steady_clock::now();
      const uint64_t server = regionSurfaceHashOnGrid(region, *grid, withIds);
      hashSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - hashStart).count();
      EXPECT_EQ(regionSurfaceHash(a->second), server) << FaceId::fromPacked(id).toString();
      EXPECT_EQ(regionSurfaceHash(b->second), server) << FaceId::fromPacked(id).toString();
      serverSum += server;
      decodedAsBytes[id] = a->second;
      decodedAsPoints[id] = b->second;
    }
    EXPECT_EQ(surfaceHash(decodedAsBytes), serverSum);
    EXPECT_EQ(surfaceHash(decodedAsPoints), serverSum);
    EXPECT_NE(serverSum, 0u);
    std::printf("[ measured ] %zu regions, %lld triangles: encoding %.2f ms, the server's hashing %.2f ms\n",
                t->regions().size(), static_cast<long long>(t->numTriangles()), encodeSeconds * 1e3,
                hashSeconds * 1e3);
  }
}

}  // namespace
}  // namespace tessera

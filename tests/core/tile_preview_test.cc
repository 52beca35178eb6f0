// The first picture's preview (core/view/tile_preview.h) on real meshes: at
// most kPreviewTriangles triangles, each vertex a level-0 limit point where
// the root tiles have it, close to the level-0 surface, and a small
// fraction of the roots' bytes.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/tessellation/document_grid.h"
#include "core/view/tile_catalogue.h"
#include "core/view/tile_encoding.h"
#include "core/view/tile_preview.h"
#include "support/test_meshes.h"
#include "support/tile_gaps.h"

namespace tessera {
namespace {

// The distance from p to the triangle abc (Ericson, "Real-Time Collision
// Detection" 5.1.5, closest point by Voronoi regions).
double distanceToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1 / (va + vb + vc);
  return (p - (a + vb * denom * ab + vc * denom * ac)).norm();
}

TEST(TilePreview, IsAFewKilobytesOfLevelZeroLimitPointsCloseToTheSurface) {
  for (const std::string name : {"fandisk.off", "elephant.off", "knot1.off", "mushroom.off", "hand.off"}) {
    auto mesh = importMesh(testing::cgalMeshPath(name));
    ASSERT_TRUE(mesh.isOk()) << name;
    auto doc = Document::create(*mesh, {.maxLevel = 3});
    ASSERT_TRUE(doc.isOk()) << name;
    auto grid = documentGrid(*doc);
    ASSERT_TRUE(grid.isOk()) << name;
    Vec3 lo = doc->basePoints()[0], hi = lo;
    for (const Vec3& p : doc->basePoints()) lo = testing::min(lo, p), hi = testing::max(hi, p);
    const double radius = 0.5 * (hi - lo).norm();

    TileCatalogue catalogue(*doc);
    std::map<uint64_t, Vec3> limit;  // level-0 vertex id -> its limit point, as the roots show it
    int64_t rootBytes = 0, rootTriangles = 0;
    for (const TileKey& root : catalogue.tree().roots()) {
      auto tile = catalogue.get(root);
      ASSERT_TRUE(tile.isOk());
      const RegionMesh& m = (*tile)->mesh;
      for (size_t v = 0; v < m.positions.size(); ++v) limit.emplace(m.vertexIds[v], m.positions[v]);
      auto encoded = encodeTile(*doc, root, m, *grid, 1);
      ASSERT_TRUE(encoded.isOk());
      rootBytes += static_cast<int64_t>(encoded->bytes->size());
      rootTriangles += static_cast<int64_t>(m.triangles.size());
    }
    // Made from the document's level-0 faces, without the tree, as a server
    // makes it before it has one: the same level-0 surface as the roots'.
    auto fromDocument = surfacePreview(*doc);
    ASSERT_TRUE(fromDocument.isOk()) << fromDocument.status().message();
    EXPECT_EQ(fromDocument->levelZeroTriangles, rootTriangles) << name;
    const RegionMesh* preview = &fromDocument->mesh;
    EXPECT_LE(preview->triangles.size(), kPreviewTriangles) << name;
    EXPECT_GT(preview->triangles.size(), kPreviewTriangles / 4) << name << ": not reduced to a handful";
    for (size_t v = 0; v < preview->positions.size(); ++v) {
      ASSERT_TRUE(limit.count(preview->vertexIds[v])) << name << ": not a level-0 vertex";
      EXPECT_EQ(limit.at(preview->vertexIds[v]), preview->positions[v]) << name;
    }
    // How far the level-0 limit points lie from the preview (one direction
    // only: the preview's vertices are on the level-0 surface).
    double worst = 0, sum = 0;
    for (const auto& [id, p] : limit) {
      double d = INFINITY;
      for (const auto& t : preview->triangles)
        d = std::min(d, distanceToTriangle(p, preview->positions[t[0]], preview->positions[t[1]],
                                           preview->positions[t[2]]));
      worst = std::max(worst, d), sum += d;
    }
    auto encoded = encodeTile(*doc, TileKey::preview(), *preview, *grid, 1);
    ASSERT_TRUE(encoded.isOk());
    const int64_t bytes = static_cast<int64_t>(encoded->bytes->size());
    std::printf(
        "[ measured ] %s: %lld -> %zu triangles, %lld -> %lld bytes with ids (%.1f times fewer); level-0 "
        "points from the preview: mean %.4f, worst %.4f of the radius\n",
        name.c_str(), static_cast<long long>(rootTriangles), preview->triangles.size(),
        static_cast<long long>(rootBytes), static_cast<long long>(bytes),
        static_cast<double>(rootBytes) / bytes, sum / limit.size() / radius, worst / radius);
    EXPECT_LT(bytes, 16 << 10) << name;
    EXPECT_LT(sum / limit.size(), 0.01 * radius) << name;
  }
}

}  // namespace
}  // namespace tessera

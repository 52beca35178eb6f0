// The admission of a document's work on its own
// (server/document/document_admission.h, docs/ARCHITECTURE.md "Bulk work"):
// the triangle estimates from the level counts alone, and the lane a task of
// that size takes.
#include <gtest/gtest.h>

#include <cstdint>

#include "server/document/document_admission.h"

namespace tessera::server {
namespace {

// A triangulated cube's counts (8 vertices, 18 edges, 12 faces) to level 3:
// 12, 48, 192 and 768 faces.
const LevelCounts kCube(8, 18, 12, 3);

wire::LodProfile profile(uint32_t base, uint32_t max, uint64_t budget = 0) {
  wire::LodProfile p;
  p.set_base_level(base);
  p.set_max_level(max);
  p.set_triangle_budget(budget);
  return p;
}

TEST(DocumentAdmission, UniformTrianglesAreTheFacesOfALevel) {
  EXPECT_EQ(uniformTriangles(kCube, 0), 12);
  EXPECT_EQ(uniformTriangles(kCube, 1), 48);
  EXPECT_EQ(uniformTriangles(kCube, 3), 768);
}

TEST(DocumentAdmission, BeyondTheCountsFourTimesPerLevelSaturating) {
  EXPECT_EQ(uniformTriangles(kCube, 4), 768 * 4);
  EXPECT_EQ(uniformTriangles(kCube, 6), 768 * 64);
  const int64_t deep = uniformTriangles(kCube, 64);
  EXPECT_GE(deep, INT64_MAX >> 2) << "it saturates rather than stops short";
  EXPECT_GT(deep, 0) << "it never overflows";
  EXPECT_EQ(uniformTriangles(kCube, UINT32_MAX), deep);
}

TEST(DocumentAdmission, AProfileNeedsItsBaseLevelWhole) {
  EXPECT_EQ(minimumTriangles(kCube, profile(0, 3)), 12);
  EXPECT_EQ(minimumTriangles(kCube, profile(2, 3)), 192);
  EXPECT_EQ(minimumTriangles(kCube, profile(1000, 1000)), uniformTriangles(kCube, 64))
      << "levels are read up to 64";
}

TEST(DocumentAdmission, AProfileReachesItsMaxLevelWithinItsBudget) {
  Limits limits;
  limits.maxTrianglesPerSubscriber = 500;
  EXPECT_EQ(maximumTriangles(kCube, profile(0, 2), limits), 192) << "the max level's faces";
  EXPECT_EQ(maximumTriangles(kCube, profile(0, 3), limits), 500) << "no budget asked: --max-triangles";
  EXPECT_EQ(maximumTriangles(kCube, profile(0, 3, 100), limits), 100) << "its own budget, smaller";
  EXPECT_EQ(maximumTriangles(kCube, profile(0, 3, 5000), limits), 500) << "its own budget, capped";
  EXPECT_EQ(maximumTriangles(kCube, profile(0, 3, UINT64_MAX), limits), 500);
}

TEST(DocumentAdmission, WorkAboveBulkTrianglesTakesTheBulkLane) {
  ServerConfig config;
  config.bulkTriangles = 1000;
  EXPECT_EQ(laneFor(0, config), Lane::kInteractive);
  EXPECT_EQ(laneFor(1000, config), Lane::kInteractive);
  EXPECT_EQ(laneFor(1001, config), Lane::kBulk);
}

}  // namespace
}  // namespace tessera::server

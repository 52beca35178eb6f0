// A requested LOD profile checked before any work
// (server/document/profile_request.h, docs/PROTOCOL.md §9 and §14).
#include <gtest/gtest.h>

#include <string>

#include "server/document/profile_request.h"

namespace tessera::server {
namespace {

wire::LodProfile requested(uint32_t base, uint32_t max, uint64_t budget = 0) {
  wire::LodProfile p;
  p.set_base_level(base);
  p.set_max_level(max);
  p.set_angle_threshold_degrees(10);
  p.set_triangle_budget(budget);
  return p;
}

TEST(ProfileRequest, TheBudgetIsTheSmallerOfTheRequestAndTheCap) {
  Limits limits;
  limits.maxTrianglesPerSubscriber = 1000;
  EXPECT_EQ(budgetOf(requested(0, 2, 0), limits), 1000);
  EXPECT_EQ(budgetOf(requested(0, 2, 300), limits), 300);
  EXPECT_EQ(budgetOf(requested(0, 2, 5000), limits), 1000);
  EXPECT_EQ(budgetOf(requested(0, 2, UINT64_MAX), limits), 1000);
}

TEST(ProfileRequest, MorphTimesRoundToSharedViews) {
  wire::LodProfile a = requested(0, 2), b = requested(0, 2), c = requested(0, 2);
  a.set_morph_t(0.25);
  b.set_morph_t(0.25 + 0.4 / kMorphTimeSteps);  // rounds to the same step
  c.set_morph_t(0.25 + 1.0 / kMorphTimeSteps);  // the next step
  auto ra = checkProfileRequest(a, Limits{}, store::DocumentId{3}, 4, true);
  auto rb = checkProfileRequest(b, Limits{}, store::DocumentId{3}, 4, true);
  auto rc = checkProfileRequest(c, Limits{}, store::DocumentId{3}, 4, true);
  ASSERT_TRUE(ra.isOk() && rb.isOk() && rc.isOk());
  EXPECT_EQ(*ra->morphT, 0.25);
  EXPECT_EQ(ra->key, rb->key);
  EXPECT_NE(ra->key, rc->key);
  auto still = checkProfileRequest(requested(0, 2), Limits{}, store::DocumentId{3}, 4, true);
  ASSERT_TRUE(still.isOk());
  EXPECT_FALSE(still->morphT.has_value());
  EXPECT_NE(still->key, ra->key) << "a still view and a morph view are different views";
}

TEST(ProfileRequest, RefusalsNameTheField) {
  auto tooDeep = checkProfileRequest(requested(0, 5), Limits{}, store::DocumentId{3}, 4, false);
  ASSERT_FALSE(tooDeep.isOk());
  EXPECT_EQ(tooDeep.status().message(), "LOD profile: max level 5 exceeds the document's 4");
  EXPECT_EQ(tooDeep.status().code(), ErrorCode::kInvalidArgument);

  wire::LodProfile morph = requested(0, 2);
  morph.set_morph_t(0.5);
  auto oneKey = checkProfileRequest(morph, Limits{}, store::DocumentId{3}, 4, false);
  ASSERT_FALSE(oneKey.isOk());
  EXPECT_NE(oneKey.status().message().find("document 3 has one key"), std::string::npos);

  morph.set_morph_t(1.5);
  auto outside = checkProfileRequest(morph, Limits{}, store::DocumentId{3}, 4, true);
  ASSERT_FALSE(outside.isOk());
  EXPECT_NE(outside.status().message().find("is not in [0, 1]"), std::string::npos);

  morph.set_morph_t(std::nan(""));
  EXPECT_FALSE(checkProfileRequest(morph, Limits{}, store::DocumentId{3}, 4, true).isOk())
      << "NaN is not a time";

  auto reversed = checkProfileRequest(requested(3, 1), Limits{}, store::DocumentId{3}, 4, false);
  EXPECT_FALSE(reversed.isOk());
}

}  // namespace
}  // namespace tessera::server

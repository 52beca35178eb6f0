// Tag sidecar parsing and application: every error names FILE:LINE and why.
#include "core/io/tag_file.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/mesh/mesh_validation.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

BaseMesh tetra() {
  PolygonSoup soup;
  soup.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  for (const auto& f : std::vector<std::vector<int>>{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}})
    soup.addFace(f);
  return std::move(buildBaseMesh(soup, {}, "tetra")).value();
}

// A tetrahedron plus one far vertex-fan triangle, so that 0 and 4 share no edge.
BaseMesh twoPieces() {
  PolygonSoup soup;
  soup.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1),
                 Vec3(5, 5, 5), Vec3(6, 5, 5), Vec3(5, 6, 5)};
  for (const auto& f : std::vector<std::vector<int>>{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {4, 5, 6}}) {
    soup.addFace(f);
  }
  return std::move(buildBaseMesh(soup, {}, "pieces")).value();
}

std::string parseErrorOf(const std::string& text) {
  auto tags = parseTags(text, "t.tags");
  EXPECT_FALSE(tags.isOk()) << text;
  if (tags.isOk()) return "";
  EXPECT_EQ(tags.status().code(), ErrorCode::kParseError);
  return tags.status().message();
}

TEST(TagFile, ParsesCreasesCornersCommentsAndInf) {
  auto tags =
      parseTags("# header comment\n\ncrease 0 1 2.5  # semi-sharp\ncorner 3 INF\n  crease 1 2 inf\n", "t");
  ASSERT_TRUE(tags.isOk()) << tags.status().toString();
  ASSERT_EQ(tags->size(), 3u);
  EXPECT_EQ((*tags)[0].kind, FeatureTag::Kind::kCrease);
  EXPECT_EQ((*tags)[0].v0, 0);
  EXPECT_EQ((*tags)[0].v1, 1);
  EXPECT_FLOAT_EQ((*tags)[0].sharpness, 2.5f);
  EXPECT_EQ((*tags)[0].line, 3);
  EXPECT_EQ((*tags)[1].kind, FeatureTag::Kind::kCorner);
  EXPECT_EQ((*tags)[1].sharpness, kSharpnessInfinite);
  EXPECT_EQ((*tags)[2].sharpness, kSharpnessInfinite);
  EXPECT_EQ((*tags)[2].line, 5);
}

TEST(TagFile, LargeFiniteSharpnessIsInfinite) {
  auto tags = parseTags("crease 0 1 25\n", "t");
  ASSERT_TRUE(tags.isOk());
  EXPECT_EQ((*tags)[0].sharpness, kSharpnessInfinite);
}

TEST(TagFile, RejectsMalformedLinesWithFileAndLine) {
  EXPECT_EQ(parseErrorOf("crease 0 1 1\nbevel 0 1\n"),
            "t.tags:2: unknown keyword 'bevel' (expected 'crease' or 'corner')");
  EXPECT_EQ(parseErrorOf("crease 0 1\n"),
            "t.tags:1: crease: too few values, expected 'crease I J SHARPNESS'");
  EXPECT_EQ(parseErrorOf("corner 0 1 2\n"),
            "t.tags:1: corner: unexpected trailing '2', expected 'corner I SHARPNESS'");
  EXPECT_EQ(parseErrorOf("\ncrease 0 1 1 junk\n"),
            "t.tags:2: crease: unexpected trailing 'junk', expected 'crease I J SHARPNESS'");
  EXPECT_EQ(parseErrorOf("crease -1 1 1\n"),
            "t.tags:1: crease: bad vertex index '-1' (expected a non-negative integer)");
  EXPECT_EQ(parseErrorOf("crease 0 1.5 1\n"),
            "t.tags:1: crease: bad vertex index '1.5' (expected a non-negative integer)");
  EXPECT_EQ(parseErrorOf("corner 99999999999 1\n"),
            "t.tags:1: corner: bad vertex index '99999999999' (expected a non-negative integer)");
  EXPECT_EQ(parseErrorOf("crease 0 1 -0.5\n"),
            "t.tags:1: crease 0 1: bad sharpness '-0.5' (expected a number >= 0 or 'inf')");
  EXPECT_EQ(parseErrorOf("corner 2 nan\n"),
            "t.tags:1: corner 2: bad sharpness 'nan' (expected a number >= 0 or 'inf')");
  EXPECT_EQ(parseErrorOf("corner 2 1.0x\n"),
            "t.tags:1: corner 2: bad sharpness '1.0x' (expected a number >= 0 or 'inf')");
  EXPECT_EQ(parseErrorOf("crease 3 3 1\n"), "t.tags:1: crease 3 3: names the same vertex twice");
}

TEST(TagFile, AppliesTags) {
  BaseMesh mesh = tetra();
  auto tags = parseTags("crease 1 0 inf\ncrease 1 2 3\ncorner 3 inf\n", "t");
  ASSERT_TRUE(tags.isOk());
  ASSERT_TRUE(applyTags(*tags, "t", mesh).isOk());
  const BaseMesh::TagCounts counts = mesh.tagCounts();
  EXPECT_EQ(counts.infiniteCreases, 1);
  EXPECT_EQ(counts.semiSharpCreases, 1);
  EXPECT_EQ(counts.sharpVertices, 1);
}

TEST(TagFile, CreaseWithoutEdgeIsErrorWithLineAndMeshIsUnchanged) {
  BaseMesh mesh = twoPieces();
  auto tags = parseTags("crease 0 1 inf\n\ncrease 0 4 1\n", "t.tags");
  ASSERT_TRUE(tags.isOk());
  const Status status = applyTags(*tags, "t.tags", mesh);
  ASSERT_FALSE(status.isOk());
  EXPECT_EQ(status.code(), ErrorCode::kNotFound);
  EXPECT_EQ(status.message(), "t.tags:3: crease 0 4: vertices 0 and 4 share no edge");
  EXPECT_EQ(mesh.tagCounts().infiniteCreases, 0);  // nothing applied
}

TEST(TagFile, MissingVertexAndDuplicatesAreErrors) {
  BaseMesh mesh = tetra();
  auto tags = parseTags("corner 7 1\n", "t.tags");
  ASSERT_TRUE(tags.isOk());
  EXPECT_EQ(applyTags(*tags, "t.tags", mesh).message(),
            "t.tags:1: corner 7: vertex 7 does not exist (the mesh has 4 vertices)");
  tags = parseTags("crease 0 1 1\ncorner 2 1\ncrease 1 0 2\n", "t.tags");
  ASSERT_TRUE(tags.isOk());
  EXPECT_EQ(applyTags(*tags, "t.tags", mesh).message(),
            "t.tags:3: crease 1 0: duplicate tag, the same edge is already tagged at t.tags:1");
}

TEST(TagFile, ApplyTagFileReadsFromDisk) {
  const std::string dir = testing::makeTempDir("tessera-tags");
  BaseMesh mesh = tetra();
  {
    std::ofstream(dir + "/good.tags") << "crease 0 1 inf\n";
    std::ofstream(dir + "/bad.tags") << "crease 0 1 inf\ncorner 0 -1\n";
  }
  EXPECT_TRUE(applyTagFile(dir + "/good.tags", mesh).isOk());
  const Status bad = applyTagFile(dir + "/bad.tags", mesh);
  EXPECT_NE(bad.message().find("bad.tags:2: corner 0: bad sharpness '-1'"), std::string::npos)
      << bad.message();
  const Status missing = applyTagFile(dir + "/missing.tags", mesh);
  EXPECT_EQ(missing.code(), ErrorCode::kNotFound);
  EXPECT_NE(missing.message().find("missing.tags"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tessera

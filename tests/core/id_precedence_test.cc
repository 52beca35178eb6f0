// Which error wins when a command's ids break several rules at once
// (docs/PROTOCOL.md 7.2, "Which error wins"): the list's shape, then every
// id's existence in the order given (notFound), then how the ids relate
// (invalidArgument), then the values; whatever the position of the missing
// id in the list.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/document/document.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

Document cube() {
  auto mesh = testing::creasedCube();
  EXPECT_TRUE(mesh.isOk()) << mesh.status().message();
  auto doc = Document::create(*mesh, {.maxLevel = 3});
  EXPECT_TRUE(doc.isOk()) << doc.status().message();
  return std::move(*doc);
}

ErrorCode moveCode(Document& doc, std::vector<VertexId> ids, Vec3 by = Vec3(0, 0, 0.01)) {
  return doc.moveBy(ids, by).status().code();
}

TEST(IdPrecedence, AMissingVertexWinsWhereverItStands) {
  Document doc = cube();
  const VertexId missing(1, doc.counts().vertices(1));  // one past the last
  const VertexId a(1, 5), b(2, 7);
  // Mixed levels before the missing id: still NOT_FOUND.
  EXPECT_EQ(moveCode(doc, {a, b, missing}), ErrorCode::kNotFound);
  EXPECT_EQ(moveCode(doc, {missing, b}), ErrorCode::kNotFound);
  // A duplicate and a missing id.
  EXPECT_EQ(moveCode(doc, {a, a, missing}), ErrorCode::kNotFound);
  // A level above the document's max level.
  EXPECT_EQ(moveCode(doc, {a, VertexId(4, 0)}), ErrorCode::kNotFound);
  // Ids before values: a missing id with a non-finite displacement.
  EXPECT_EQ(moveCode(doc, {missing}, Vec3(NAN, 0, 0)), ErrorCode::kNotFound);
  // Without a missing id, the relations and values give INVALID_ARGUMENT.
  EXPECT_EQ(moveCode(doc, {}), ErrorCode::kInvalidArgument);
  EXPECT_EQ(moveCode(doc, {a, b}), ErrorCode::kInvalidArgument);
  EXPECT_EQ(moveCode(doc, {a, a}), ErrorCode::kInvalidArgument);
  EXPECT_EQ(moveCode(doc, {a}, Vec3(NAN, 0, 0)), ErrorCode::kInvalidArgument);
  // The message names the missing id.
  const Status status = doc.moveBy(std::vector<VertexId>{a, b, missing}, Vec3(0, 0, 0.01)).status();
  EXPECT_NE(status.message().find(missing.toString()), std::string::npos) << status.message();
}

TEST(IdPrecedence, EndVerticesOfAnEdge) {
  Document doc = cube();
  const VertexId missing(1, doc.counts().vertices(1));
  const VertexId a(1, 5), b(2, 7);
  EXPECT_EQ(doc.edgeBetween(a, VertexId(2, doc.counts().vertices(2))).status().code(), ErrorCode::kNotFound);
  EXPECT_EQ(doc.edgeBetween(missing, b).status().code(), ErrorCode::kNotFound);
  EXPECT_EQ(doc.edgeBetween(missing, missing).status().code(), ErrorCode::kNotFound);
  EXPECT_EQ(doc.edgeBetween(a, b).status().code(), ErrorCode::kInvalidArgument);  // two levels
  EXPECT_EQ(doc.edgeBetween(a, a).status().code(), ErrorCode::kInvalidArgument);  // one vertex twice
  EXPECT_EQ(doc.edgeBetween(VertexId(0, 0), VertexId(0, 6)).status().code(),
            ErrorCode::kInvalidArgument);  // not joined
}

TEST(IdPrecedence, ASingleMissingElementWinsOverItsValue) {
  Document doc = cube();
  const EdgeId missingEdge(1, doc.counts().edges(1));
  const VertexId missingVertex(1, doc.counts().vertices(1));
  EXPECT_EQ(doc.setEdgeSharpness(missingEdge, -1.0f).status().code(), ErrorCode::kNotFound);
  EXPECT_EQ(doc.setVertexSharpness(missingVertex, NAN).status().code(), ErrorCode::kNotFound);
  EXPECT_EQ(doc.setEdgeSharpness(EdgeId(1, 0), -1.0f).status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(doc.setVertexSharpness(VertexId(1, 0), NAN).status().code(), ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace tessera

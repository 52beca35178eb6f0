// Journal entries: an EditBatch is one entry of kind kBatch that encodes,
// decodes and replays exactly like its parts one after the other; damaged
// batch entries are refused with a message, never half read.
#include <gtest/gtest.h>

#include "core/document/document.h"
#include "core/document/document_file.h"
#include "core/io/mesh_import.h"
#include "server/journal_entry.h"
#include "support/test_meshes.h"

namespace tessera::server {
namespace {

Document cube() {
  auto mesh = importMesh(testing::sourceTestDataPath("cube.obj"));
  EXPECT_TRUE(mesh.isOk());
  auto doc = Document::create(*mesh, {.maxLevel = 4});
  EXPECT_TRUE(doc.isOk());
  return std::move(*doc);
}

// Makes three changes on `doc` and returns them as journal entries.
std::vector<JournalEntry> threeChanges(Document& doc) {
  std::vector<JournalEntry> parts;
  const VertexId moved[] = {VertexId(1, 3)};
  auto first = doc.moveBy(moved, Vec3(0, 0, 0.1));
  EXPECT_TRUE(first.isOk());
  parts.push_back({.kind = JournalEntry::Kind::kEdit, .edit = doc.edits().back()});
  auto second = doc.setEdgeSharpness(EdgeId(1, 4), 2.0f);
  EXPECT_TRUE(second.isOk());
  parts.push_back({.kind = JournalEntry::Kind::kEdit, .edit = doc.edits().back()});
  EXPECT_TRUE(doc.undo(*first).isOk());
  parts.push_back({.kind = JournalEntry::Kind::kUndo, .target = *first});
  return parts;
}

TEST(JournalEntry, ABatchReplaysAsItsParts) {
  Document live = cube();
  JournalEntry batch{.kind = JournalEntry::Kind::kBatch};
  batch.batch = threeChanges(live);
  const std::string bytes = encodeJournalEntry(batch);
  auto decoded = decodeJournalEntry(bytes, "entry 2");
  ASSERT_TRUE(decoded.isOk()) << decoded.status().toString();
  ASSERT_EQ(decoded->kind, JournalEntry::Kind::kBatch);
  ASSERT_EQ(decoded->batch.size(), 3u);
  EXPECT_EQ(encodeJournalEntry(*decoded), bytes);

  Document replayed = cube();
  ASSERT_TRUE(applyJournalEntry(replayed, *decoded).isOk());
  EXPECT_EQ(serializeDocument(replayed), serializeDocument(live));
}

TEST(JournalEntry, DamagedBatchesAreRefused) {
  Document live = cube();
  JournalEntry batch{.kind = JournalEntry::Kind::kBatch};
  batch.batch = threeChanges(live);
  const std::string bytes = encodeJournalEntry(batch);
  // Truncated anywhere inside: an error, never a shorter batch.
  for (size_t cut = 1; cut < bytes.size(); ++cut) {
    EXPECT_FALSE(decodeJournalEntry(bytes.substr(0, cut), "entry 2").isOk()) << cut;
  }
  // A batch of none, and a batch inside a batch.
  const std::string empty("\x04\x00\x00\x00\x00", 5);
  auto none = decodeJournalEntry(empty, "entry 3");
  ASSERT_FALSE(none.isOk());
  EXPECT_NE(none.status().message().find("entry 3: a batch of 0 entries"), std::string::npos);
  JournalEntry outer{.kind = JournalEntry::Kind::kBatch};
  outer.batch.push_back(batch);
  auto nested = decodeJournalEntry(encodeJournalEntry(outer), "entry 4");
  ASSERT_FALSE(nested.isOk());
  EXPECT_NE(nested.status().message().find("a batch inside a batch"), std::string::npos);
}

}  // namespace
}  // namespace tessera::server

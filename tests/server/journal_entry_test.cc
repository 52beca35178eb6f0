// Journal entries: an EditBatch is one entry of kind kBatch that encodes,
// decodes and replays exactly like its parts one after the other; damaged
// batch entries are refused with a message, never half read.
#include <gtest/gtest.h>

#include "core/document/document.h"
#include "core/document/document_file.h"
#include "core/morph/keyed_document_file.h"
#include "server/document/journal_entry.h"
#include "support/test_meshes.h"

namespace tessera::server {
namespace {

Document cube() {
  auto doc = testing::cubeDocument(4);
  EXPECT_TRUE(doc.isOk()) << doc.status().message();
  return std::move(*doc);
}

// Entries built field by field (designated initializers would leave the
// other members to -Wmissing-field-initializers).
JournalEntry entryOf(JournalEntry::Kind kind) {
  JournalEntry e;
  e.kind = kind;
  return e;
}
JournalEntry editEntry(const Edit& edit) {
  JournalEntry e = entryOf(JournalEntry::Kind::kEdit);
  e.edit = edit;
  return e;
}
JournalEntry targetEntry(JournalEntry::Kind kind, EditId target) {
  JournalEntry e = entryOf(kind);
  e.target = target;
  return e;
}

// Makes three changes on `doc` and returns them as journal entries.
std::vector<JournalEntry> threeChanges(Document& doc) {
  std::vector<JournalEntry> parts;
  const VertexId moved[] = {VertexId(1, 3)};
  auto first = doc.moveBy(moved, Vec3(0, 0, 0.1));
  EXPECT_TRUE(first.isOk());
  parts.push_back(editEntry(doc.edits().back()));
  auto second = doc.setEdgeSharpness(EdgeId(1, 4), 2.0f);
  EXPECT_TRUE(second.isOk());
  parts.push_back(editEntry(doc.edits().back()));
  EXPECT_TRUE(doc.undo(*first).isOk());
  parts.push_back(targetEntry(JournalEntry::Kind::kUndo, *first));
  return parts;
}

TEST(JournalEntry, ABatchReplaysAsItsParts) {
  Document live = cube();
  JournalEntry batch = entryOf(JournalEntry::Kind::kBatch);
  batch.batch = threeChanges(live);
  const std::string bytes = encodeJournalEntry(batch);
  auto decoded = decodeJournalEntry(bytes, "entry 2");
  ASSERT_TRUE(decoded.isOk()) << decoded.status().toString();
  ASSERT_EQ(decoded->kind, JournalEntry::Kind::kBatch);
  ASSERT_EQ(decoded->batch.size(), 3u);
  EXPECT_EQ(encodeJournalEntry(*decoded), bytes);

  KeyedDocument replayed(cube());
  ASSERT_TRUE(applyJournalEntry(replayed, *decoded).isOk());
  EXPECT_EQ(serializeDocument(replayed.key0()), serializeDocument(live));
}

TEST(JournalEntry, DamagedBatchesAreRefused) {
  Document live = cube();
  JournalEntry batch = entryOf(JournalEntry::Kind::kBatch);
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
  JournalEntry outer = entryOf(JournalEntry::Kind::kBatch);
  outer.batch.push_back(batch);
  auto nested = decodeJournalEntry(encodeJournalEntry(outer), "entry 4");
  ASSERT_FALSE(nested.isOk());
  EXPECT_NE(nested.status().message().find("a batch inside a batch"), std::string::npos);
}

// A morph document's second key and the edits on it are
// journal entries too, and replay rebuilds both keys bit for bit.
TEST(JournalEntry, AMorphKeyAndItsEditsReplayExactly) {
  KeyedDocument live(cube());
  std::vector<Vec3> points = live.key0().basePoints();
  for (Vec3& p : points) p = 1.5 * p + Vec3(0.25, 0, 0);
  JournalEntry add = entryOf(JournalEntry::Kind::kAddKey);
  add.keyPoints = points;
  add.images = {std::string("\x89PNG\r\n\x1a\nfrom", 12), std::string("\x89PNG\r\n\x1a\nto", 10)};
  ASSERT_TRUE(applyJournalEntry(live, add).isOk());
  ASSERT_TRUE(live.isMorph());
  // Edits on key 1, as the server journals them: key 1 named in the entry.
  Document& second = **live.editKey(1);
  JournalEntry onKey1 = entryOf(JournalEntry::Kind::kBatch);
  onKey1.batch = threeChanges(second);
  for (JournalEntry& part : onKey1.batch) part.key = 1;

  KeyedDocument replayed(cube());
  for (const JournalEntry* entry : {&add, &onKey1}) {
    const std::string bytes = encodeJournalEntry(*entry);
    auto decoded = decodeJournalEntry(bytes, "entry");
    ASSERT_TRUE(decoded.isOk()) << decoded.status().toString();
    EXPECT_EQ(encodeJournalEntry(*decoded), bytes);
    ASSERT_TRUE(applyJournalEntry(replayed, *decoded).isOk());
  }
  ASSERT_TRUE(replayed.isMorph());
  EXPECT_EQ(serializeKeyedDocument(replayed), serializeKeyedDocument(live));
  EXPECT_EQ(replayed.images().to, live.images().to);
  // Key 0 never saw the edits on key 1.
  EXPECT_TRUE(replayed.key0().edits().empty());
  EXPECT_EQ(replayed.key(1).edits().size(), 2u);
}

TEST(JournalEntry, DamagedMorphEntriesAreRefused) {
  JournalEntry edit = targetEntry(JournalEntry::Kind::kUndo, EditId{3});
  edit.key = 1;
  const std::string bytes = encodeJournalEntry(edit);
  for (size_t cut = 1; cut < bytes.size(); ++cut) {
    EXPECT_FALSE(decodeJournalEntry(bytes.substr(0, cut), "entry 5").isOk()) << cut;
  }
  // Key 2 (a morph document has keys 0 and 1) and a batch on a key.
  std::string key2 = bytes;
  key2[1] = 2;
  auto bad = decodeJournalEntry(key2, "entry 6");
  ASSERT_FALSE(bad.isOk());
  EXPECT_NE(bad.status().message().find("entry 6: an entry on morph key 2"), std::string::npos)
      << bad.status().message();
  std::string batchOnKey = bytes;
  batchOnKey[5] = 4;
  auto batch = decodeJournalEntry(batchOnKey, "entry 7");
  ASSERT_FALSE(batch.isOk());
  EXPECT_NE(batch.status().message().find("a journal entry of kind 4 on a morph key"), std::string::npos);
  // An edit on key 1 of a document with one key.
  KeyedDocument single(cube());
  Status missing = applyJournalEntry(single, edit);
  ASSERT_FALSE(missing.isOk());
  EXPECT_NE(missing.message().find("key 1 does not exist: the document has 1 key"), std::string::npos)
      << missing.message();
  // A second key of another vertex count.
  JournalEntry add = entryOf(JournalEntry::Kind::kAddKey);
  add.keyPoints.assign(3, Vec3(0, 0, 0));
  Status count = applyJournalEntry(single, add);
  ASSERT_FALSE(count.isOk());
  EXPECT_NE(count.message().find("the second key has 3 points, key 0 has 8"), std::string::npos)
      << count.message();
  EXPECT_FALSE(single.isMorph());
}

}  // namespace
}  // namespace tessera::server

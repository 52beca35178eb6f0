// A morph document's keys (docs/INTERPOLATION.md, core/morph/keyed_document.h) and
// their file (keyed_document_file.h): key 1 starts with key 0's edits on its
// own points, the document at t is the morph of the two keys, a document of
// one key is saved exactly as a plain document file, and a morph container
// reads back bit for bit; damaged containers are refused by name.
#include <gtest/gtest.h>

#include "core/document/document_file.h"
#include "core/morph/keyed_document.h"
#include "core/morph/keyed_document_file.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

constexpr int kLevel = 3;

struct Keys {
  KeyedDocument doc;
  std::vector<Vec3> points1;
};

Keys torusKeys() {
  const testing::TestMesh mesh = testing::withJitter(testing::torus(8, 6), 0.05, 7);
  auto key0 = Document::create(mesh.topology, mesh.points, {.maxLevel = kLevel});
  EXPECT_TRUE(key0.isOk());
  const VertexId fine(2, 40);
  EXPECT_TRUE(key0->moveBy(std::span(&fine, 1), Vec3(0, 0.05, 0.02)).isOk());
  KeyedDocument doc(std::move(*key0));
  std::vector<Vec3> points1 = mesh.points;
  for (Vec3& p : points1) p = Vec3(1.5 * p[0], p[1] + 0.2 * p[0] * p[0], p[2]);
  return {std::move(doc), points1};
}

TEST(KeyedDocument, TheSecondKeyStartsWithTheFirstKeysEditsOnItsOwnPoints) {
  Keys k = torusKeys();
  ASSERT_TRUE(k.doc.addKey(k.points1).isOk());
  ASSERT_TRUE(k.doc.isMorph());
  const Document& key1 = k.doc.key(1);
  EXPECT_EQ(key1.basePoints(), k.points1);
  ASSERT_EQ(key1.edits().size(), 1u);
  // The same offsets, in local frames (core/loop/local_frame.h): the edit itself is
  // copied, not its world displacement.
  EXPECT_EQ(std::get<MoveEdit>(key1.edits()[0].change).offsets[0].localOffset,
            std::get<MoveEdit>(k.doc.key0().edits()[0].change).offsets[0].localOffset);
  EXPECT_EQ(key1.nextEditId(), k.doc.key0().nextEditId());
  // At t = 0 and 1 the keys' own surfaces; halfway the base points are the
  // midpoints (the definition of a linear morph of control meshes).
  for (auto [t, key] : {std::pair{0.0, 0}, {1.0, 1}}) {
    auto at = k.doc.at(t);
    ASSERT_TRUE(at.isOk()) << at.status().message();
    auto a = at->surface(kLevel, SurfaceKind::kLimit),
         b = k.doc.key(key).surface(kLevel, SurfaceKind::kLimit);
    ASSERT_TRUE(a.isOk() && b.isOk());
    double worst = 0;
    for (size_t i = 0; i < a->positions.size(); ++i)
      worst = std::max(worst, (a->positions[i] - b->positions[i]).norm());
    EXPECT_LE(worst, 1e-12) << "t = " << t;
  }
  auto half = k.doc.pointsAt(0.5);
  ASSERT_TRUE(half.isOk());
  for (size_t v = 0; v < half->size(); ++v) {
    const Vec3 mid = 0.5 * k.doc.key0().basePoints()[v] + 0.5 * k.points1[v];
    EXPECT_LE(((*half)[v] - mid).norm(), 1e-15) << v;
  }
  // An edit of a key changes the morph (the cached one is dropped); an
  // offset is an edit, so the base points at t stay.
  const Vec3 before = *k.doc.pointAt(3, 0.5);
  auto surfaceBefore = k.doc.at(0.5)->surface(kLevel, SurfaceKind::kLimit);
  const VertexId base(0, 3);
  ASSERT_TRUE((*k.doc.editKey(1))->moveBy(std::span(&base, 1), Vec3(0.2, 0, 0)).isOk());
  auto surfaceAfter = k.doc.at(0.5)->surface(kLevel, SurfaceKind::kLimit);
  ASSERT_TRUE(surfaceBefore.isOk() && surfaceAfter.isOk());
  EXPECT_GT((surfaceAfter->positions[3] - surfaceBefore->positions[3]).norm(), 0.01);
  EXPECT_EQ(*k.doc.pointAt(3, 0.5), before);
}

TEST(KeyedDocument, RefusalsNameWhatIsWrong) {
  Keys k = torusKeys();
  EXPECT_NE(k.doc.at(0.5).status().message().find("the document has one key"), std::string::npos);
  std::vector<Vec3> short1(k.points1.begin(), k.points1.end() - 1);
  EXPECT_NE(k.doc.addKey(short1).message().find("the second key has 47 points, key 0 has 48"),
            std::string::npos)
      << k.doc.addKey(short1).message();
  std::vector<Vec3> nan = k.points1;
  nan[9][1] = std::nan("");
  EXPECT_NE(k.doc.addKey(nan).message().find("the second key's point 9 is not finite"), std::string::npos);
  ASSERT_TRUE(k.doc.addKey(k.points1).isOk());
  EXPECT_NE(k.doc.addKey(k.points1).message().find("already has 2 keys"), std::string::npos);
  EXPECT_NE(k.doc.at(1.5).status().message().find("morph time 1.500000 is not in [0, 1]"), std::string::npos);
  EXPECT_NE(k.doc.editKey(2).status().message().find("key 2 does not exist: the document has 2 keys"),
            std::string::npos);
}

TEST(KeyedDocumentFile, OneKeyIsAPlainDocumentFileAndTwoKeysReadBackExactly) {
  Keys k = torusKeys();
  EXPECT_EQ(serializeKeyedDocument(k.doc), serializeDocument(k.doc.key0()));
  ASSERT_TRUE(
      k.doc.addKey(k.points1, {std::string("\x89PNG\r\n\x1a\nA", 9), std::string("\x89PNG\r\n\x1a\nBB", 10)})
          .isOk());
  const VertexId fine(2, 41);
  ASSERT_TRUE((*k.doc.editKey(1))->moveBy(std::span(&fine, 1), Vec3(0.01, 0, 0)).isOk());
  const std::string bytes = serializeKeyedDocument(k.doc);
  auto back = deserializeKeyedDocument(bytes, "morph.tsd");
  ASSERT_TRUE(back.isOk()) << back.status().message();
  EXPECT_EQ(serializeDocument(back->key0()), serializeDocument(k.doc.key0()));
  EXPECT_EQ(serializeDocument(back->key(1)), serializeDocument(k.doc.key(1)));
  EXPECT_EQ(back->images().to, k.doc.images().to);
  EXPECT_EQ(serializeKeyedDocument(*back), bytes);
  // Truncated anywhere: an error naming the source, never a document.
  for (size_t cut = 0; cut < bytes.size(); cut += std::max<size_t>(1, bytes.size() / 300)) {
    auto cutShort = deserializeKeyedDocument(bytes.substr(0, cut), "morph.tsd");
    ASSERT_FALSE(cutShort.isOk()) << cut;
    EXPECT_NE(cutShort.status().message().find("morph.tsd"), std::string::npos)
        << cutShort.status().message();
  }
  // Another key count, and trailing bytes.
  std::string three = bytes;
  three[12] = 3;
  EXPECT_NE(deserializeKeyedDocument(three, "m").status().message().find("a morph container of 3 keys"),
            std::string::npos);
  EXPECT_NE(deserializeKeyedDocument(bytes + "x", "m").status().message().find("trailing bytes"),
            std::string::npos);
}

}  // namespace
}  // namespace tessera

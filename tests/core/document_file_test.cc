// The document file format: exact round trips, and clear rejection of
// foreign, truncated, corrupted and crafted files (never a crash).
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <random>

#include <zlib.h>

#include "core/document/document_file.h"
#include "support/polygon_meshes.h"
#include "support/procedural_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

// Catmull-Clark on quads, triangles and a pentagon, with each edit kind
// it takes.
Document editedPolygonDocument() {
  const auto mesh = testing::withRandomPolyTags(testing::mixedPrism(5, false), 0.3, 0.2, 3);
  auto doc =
      Document::create(mesh.topology, mesh.points, {.maxLevel = 4, .scheme = DocumentScheme::kCatmullClark});
  if (!doc.isOk()) throw std::runtime_error(doc.status().toString());
  auto a = doc->moveToLimit(std::vector<VertexId>{VertexId(2, 40)}, Vec3(0.3, 0.1, 0.4));
  auto b = doc->moveBy(std::vector<VertexId>{VertexId(1, 7)}, Vec3(1e-3, 2e-3, -0.1));
  auto c = doc->setEdgeSharpness(EdgeId(1, 5), 1.5f);
  auto d = doc->setVertexSharpness(VertexId(3, 100), kSharpnessInfinite);
  if (!a.isOk() || !b.isOk() || !c.isOk() || !d.isOk()) throw std::runtime_error("edit failed");
  return std::move(doc).value();
}

Document editedDocument() {
  auto mesh = testing::withRandomTags(testing::withJitter(testing::torus(8, 6), 0.02, 8), 0.1, 0.05, 8);
  auto doc = Document::create(mesh.topology, mesh.points,
                              {.loop = {.creaseMethod = CreaseMethod::kChaikin}, .maxLevel = 5});
  if (!doc.isOk()) throw std::runtime_error(doc.status().toString());
  auto a = doc->moveToLimit(std::vector<VertexId>{VertexId(2, 40)}, Vec3(0.3, 0.1, 0.4));
  auto b = doc->moveBy(std::vector<VertexId>{VertexId(3, 7), VertexId(3, 300)}, Vec3(1e-3, 2e-3, -0.1 / 3.0));
  auto c = doc->setEdgeSharpness(EdgeId(1, 5), 1.5f);
  auto d = doc->setVertexSharpness(VertexId(4, 900), kSharpnessInfinite);
  // Format 2: an interpolating vertex with a tension, and one ended.
  auto e = doc->setInterpolation(VertexId(1, 30), true, 2.5);
  auto f = doc->setInterpolation(VertexId(2, 200), true, 0.75);
  auto g = doc->setInterpolation(VertexId(2, 200), false);
  if (!a.isOk() || !b.isOk() || !c.isOk() || !d.isOk()) throw std::runtime_error("edit failed");
  if (!e.isOk() || !f.isOk() || !g.isOk())
    throw std::runtime_error("interpolation failed: " + e.status().toString() + f.status().toString());
  if (!doc->undo(*c).isOk()) throw std::runtime_error("undo failed");
  return std::move(doc).value();
}

// Rewrites the trailing checksum so that mutations reach the payload parser.
void fixChecksum(std::string& bytes) {
  if (bytes.size() < 28) return;
  const uint32_t crc = static_cast<uint32_t>(
      ::crc32(0L, reinterpret_cast<const Bytef*>(bytes.data() + 24), static_cast<uInt>(bytes.size() - 28)));
  std::memcpy(bytes.data() + bytes.size() - 4, &crc, 4);
}

TEST(DocumentFile, RoundTripIsExact) {
  const Document doc = editedDocument();
  const std::string bytes = serializeDocument(doc);
  auto back = deserializeDocument(bytes, "mem");
  ASSERT_TRUE(back.isOk()) << back.status().toString();
  EXPECT_EQ(serializeDocument(*back), bytes);
  EXPECT_EQ(back->nextEditId(), doc.nextEditId());
  ASSERT_EQ(back->edits().size(), doc.edits().size());
  for (int level : {0, 3, 5}) {
    auto a = doc.evaluate(level);
    auto b = back->evaluate(level);
    ASSERT_TRUE(a.isOk() && b.isOk());
    EXPECT_EQ((*a)->points[level], (*b)->points[level]) << "level " << level;  // bit for bit
  }
  const std::string path = testing::makeTempDir("tessera-doc") + "/doc.tsd";
  ASSERT_TRUE(saveDocument(doc, path).isOk());
  auto loaded = loadDocument(path);
  ASSERT_TRUE(loaded.isOk()) << loaded.status().toString();
  EXPECT_EQ(serializeDocument(*loaded), bytes);
}

TEST(DocumentFile, RejectsForeignTruncatedAndCorruptedFiles) {
  const std::string bytes = serializeDocument(editedDocument());
  struct Case {
    std::string data;
    std::string message;
  };
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x40;
  std::string newer = bytes;
  newer[8] = 4;
  std::vector<Case> cases = {
      {"", "not a Tessera document"},
      {"solid cube\nendsolid\n", "not a Tessera document"},
      {bytes.substr(0, 12), "truncated at byte"},
      {bytes.substr(0, bytes.size() - 1), "truncated or padded"},
      {bytes + "x", "truncated or padded"},
      {flipped, "corrupted (payload checksum mismatch)"},
      {newer, "format version 4 is not supported"},
  };
  for (const auto& c : cases) {
    auto doc = deserializeDocument(c.data, "doc.tsd");
    ASSERT_FALSE(doc.isOk()) << c.message;
    EXPECT_NE(doc.status().message().find("doc.tsd"), std::string::npos) << doc.status().message();
    EXPECT_NE(doc.status().message().find(c.message), std::string::npos) << doc.status().message();
  }
  EXPECT_EQ(loadDocument("/nonexistent/doc.tsd").status().code(), ErrorCode::kNotFound);
}

// A file written in format 1 (before interpolating vertices; the creased
// cube with four edits, the last undone, written by fuzz_make_corpus at 7d758c3)
// still loads, and saves as format 2 with the same payload: only the
// version in the header changes.
TEST(DocumentFile, FormatOneFilesStillLoad) {
  auto loaded = loadDocument(testing::sourceTestDataPath("documents/creased_cube_format1.tsd"));
  ASSERT_TRUE(loaded.isOk()) << loaded.status().toString();
  ASSERT_EQ(loaded->edits().size(), 4u);  // a move, an offset, a crease and a corner (undone)
  EXPECT_FALSE(loaded->edits()[3].active);
  std::ifstream in(testing::sourceTestDataPath("documents/creased_cube_format1.tsd"), std::ios::binary);
  std::string v1((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(v1[8], 1);
  std::string expected = v1;
  expected[8] = 2;
  EXPECT_EQ(serializeDocument(*loaded), expected);
}

// Mutations with a valid checksum reach the payload parser and the document
// validation: each must yield a valid document or a clear error.
void expectMutationsAreSafe(const std::string& bytes) {
  std::mt19937 rng(12);
  int rejected = 0;
  for (int i = 0; i < 400; ++i) {
    std::string m = bytes;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < flips; ++k) m[24 + rng() % (m.size() - 28)] = static_cast<char>(rng());
    fixChecksum(m);
    auto doc = deserializeDocument(m, "fuzz.tsd");
    if (!doc.isOk()) {
      ++rejected;
      EXPECT_FALSE(doc.status().message().empty());
    }
  }
  EXPECT_GT(rejected, 0);
}

// Both schemes: a Loop document (format 2) and a Catmull-Clark one (format
// 3, faces of any size).
TEST(DocumentFile, MutatedPayloadsNeverCrash) {
  for (const std::string& bytes :
       {serializeDocument(editedDocument()), serializeDocument(editedPolygonDocument())})
    expectMutationsAreSafe(bytes);
}

}  // namespace
}  // namespace tessera

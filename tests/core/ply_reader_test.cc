// A PLY header that declares 'face' (or 'vertex') twice is refused: the
// reader's roles are property indices within the one face element, and a
// second one had its values read under them (a float taken as a vertex
// index: NaN cast to int, found by fuzz_import_ply under UBSan,
// tests/fuzz/run_long.sh, 2026-11-24).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/io/mesh_import.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(PlyReader, SecondFaceElementIsRefused) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 1\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n0.5\n3 0 1 2\n";
  auto mesh = importMeshFromBytes(ply, ".ply", "twice.ply");
  ASSERT_FALSE(mesh.isOk());
  EXPECT_NE(mesh.status().message().find("twice.ply: header: element 'face' is declared twice"),
            std::string::npos)
      << mesh.status().message();
}

TEST(PlyReader, TheFuzzersInputIsRefusedByName) {
  const std::string bytes = readBytes(testing::sourceTestDataPath("bad/fuzz_ply_nan_face_index.ply"));
  ASSERT_FALSE(bytes.empty());
  auto mesh = importMeshFromBytes(bytes, ".ply", "nan.ply");
  ASSERT_FALSE(mesh.isOk());
  EXPECT_NE(mesh.status().message().find("nan.ply: header: element 'face' is declared twice"),
            std::string::npos)
      << mesh.status().message();
}

// fuzz_import_ply's slow input (session 9): a binary PLY whose header
// declares 555,555,555 instances of an element without properties before
// the real vertex and face elements. Each instance takes no bytes, so
// nothing bounded the loop over them: it ran 139 s of CPU before the fix.
// Now such an element is skipped and the file is read as what it holds.
TEST(PlyReader, AnElementWithoutPropertiesIsSkippedAtOnce) {
  const std::string bytes =
      readBytes(testing::sourceTestDataPath("bad/fuzz_ply_empty_element_555555555.ply"));
  ASSERT_FALSE(bytes.empty());
  auto mesh = importMeshFromBytes(bytes, ".ply", "empty.ply");
  if (!mesh.isOk()) {
    EXPECT_NE(mesh.status().message().find("empty.ply"), std::string::npos) << mesh.status().message();
    EXPECT_EQ(mesh.status().message().find("veRtex"), std::string::npos)
        << "the empty element is not what is wrong: " << mesh.status().message();
  }
}

}  // namespace
}  // namespace tessera

// importMesh(): every supported format reads the same tetrahedron, and every
// bad input gives an error naming the file, the element and the reason.
#include "core/io/mesh_import.h"

#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "support/test_meshes.h"

namespace tessera {
namespace {

using ::tessera::testing::makeTempDir;
using ::tessera::testing::sourceTestDataPath;

const std::vector<std::array<int, 3>> kTetraFaces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};

void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Expects failure with `code`, and every fragment in the message.
void expectImportError(const std::string& relative, ErrorCode code, const std::vector<std::string>& fragments,
                       const ImportOptions& options = {}) {
  SCOPED_TRACE(relative);
  const std::string path = sourceTestDataPath(relative);
  auto mesh = importMesh(path, options);
  ASSERT_FALSE(mesh.isOk()) << "imported a bad file";
  EXPECT_EQ(mesh.status().code(), code) << mesh.status().toString();
  const std::string& message = mesh.status().message();
  EXPECT_NE(message.find(std::filesystem::path(path).filename().string()), std::string::npos) << message;
  for (const std::string& fragment : fragments) {
    EXPECT_NE(message.find(fragment), std::string::npos) << "missing '" << fragment << "' in: " << message;
  }
}

class ImportGoodTetra : public ::testing::TestWithParam<std::string> {};

TEST_P(ImportGoodTetra, ReadsVerticesAndFacesInFileOrder) {
  auto mesh = importMesh(sourceTestDataPath(GetParam()));
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  EXPECT_EQ(mesh->numVertices(), 4);
  EXPECT_EQ(mesh->faceVertexIndices(), kTetraFaces);
  const std::vector<Vec3> points = mesh->positions();
  EXPECT_EQ(points[1], Vec3(1, 0, 0));
  EXPECT_EQ(points[3], Vec3(0, 0, 1));
  EXPECT_EQ(mesh->tagCounts().infiniteCreases + mesh->tagCounts().sharpVertices, 0);
}

INSTANTIATE_TEST_SUITE_P(IndexedFormats, ImportGoodTetra,
                         ::testing::Values("good/tetra.obj", "good/tetra.off", "good/tetra.ply",
                                           "good/tetra_binary.ply"));

// STL has no indices and the glTF file splits every corner: both number
// vertices by first appearance, so P0, P2, P1, P3 for this tetrahedron.
class ImportGoodTetraFirstAppearance : public ::testing::TestWithParam<std::string> {};

TEST_P(ImportGoodTetraFirstAppearance, NumbersVerticesByFirstAppearance) {
  auto mesh = importMesh(sourceTestDataPath(GetParam()));
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  EXPECT_EQ(mesh->numVertices(), 4);
  const std::vector<std::array<int, 3>> faces = {{0, 1, 2}, {0, 2, 3}, {2, 1, 3}, {0, 3, 1}};
  EXPECT_EQ(mesh->faceVertexIndices(), faces);
  EXPECT_EQ(mesh->positions()[1], Vec3(0, 1, 0));
  EXPECT_EQ(mesh->positions()[2], Vec3(1, 0, 0));
}

INSTANTIATE_TEST_SUITE_P(UnindexedFormats, ImportGoodTetraFirstAppearance,
                         ::testing::Values("good/tetra.stl", "good/tetra_binary.stl", "good/tetra.glb"));

TEST(MeshImport, ObjAcceptsVtVnFaceSyntaxAndRelativeIndices) {
  auto mesh = importMesh(sourceTestDataPath("good/tetra_vtvn.obj"));
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  EXPECT_EQ(mesh->faceVertexIndices(), kTetraFaces);
}

TEST(MeshImport, ExtensionIsCaseInsensitive) {
  const std::string dir = makeTempDir("tessera-import");
  std::filesystem::copy_file(sourceTestDataPath("good/tetra.obj"), dir + "/TETRA.OBJ");
  auto mesh = importMesh(dir + "/TETRA.OBJ");
  EXPECT_TRUE(mesh.isOk()) << mesh.status().toString();
  std::filesystem::remove_all(dir);
}

TEST(MeshImport, GltfWeldsSplitVerticesAndAppliesExtrasTags) {
  auto mesh = importMesh(sourceTestDataPath("good/tetra_split.gltf"));
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  // 12 split vertices weld to 4, numbered by first appearance: file vertices
  // 0, 2, 1 (face 0) become 0, 1, 2, so the soup order is P0, P2, P1, P3.
  EXPECT_EQ(mesh->numVertices(), 4);
  EXPECT_EQ(mesh->numFaces(), 4);
  EXPECT_EQ(mesh->positions()[1], Vec3(0, 1, 0));
  const BaseMesh::TagCounts tags = mesh->tagCounts();
  EXPECT_EQ(tags.infiniteCreases, 1);
  EXPECT_EQ(tags.semiSharpCreases, 1);
  EXPECT_EQ(tags.sharpVertices, 1);
}

TEST(MeshImport, TriangulateSplitsQuads) {
  expectImportError("bad/quad.obj", ErrorCode::kUnsupported,
                    {"face 0 (vertices 0, 3, 2, 1)", "--triangulate"});
  auto mesh = importMesh(sourceTestDataPath("good/cube_quads.obj"), ImportOptions{.triangulate = true});
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  EXPECT_EQ(mesh->numFaces(), 12);
  // Face 0 is the quad 0 3 2 1: its two triangles use its corners only, in
  // its orientation (either diagonal of a square is Delaunay).
  const auto faces = mesh->faceVertexIndices();
  const std::vector<std::array<int, 3>> first = {faces[0], faces[1]};
  const std::vector<std::array<int, 3>> diagonal02 = {{0, 3, 2}, {0, 2, 1}};
  const std::vector<std::array<int, 3>> diagonal31 = {{0, 3, 1}, {3, 2, 1}};
  EXPECT_TRUE(first == diagonal02 || first == diagonal31) << ::testing::PrintToString(first);
}

TEST(MeshImportErrors, MissingFileAndUnsupportedExtension) {
  auto missing = importMesh("/nonexistent/dir/cube.obj");
  ASSERT_FALSE(missing.isOk());
  EXPECT_EQ(missing.status().code(), ErrorCode::kNotFound);
  EXPECT_NE(missing.status().message().find("cube.obj: file not found"), std::string::npos);

  auto unknown = importMesh(sourceTestDataPath("good/tetra.obj") + ".3ds");
  ASSERT_FALSE(unknown.isOk());
  EXPECT_EQ(unknown.status().code(), ErrorCode::kUnsupported);
  EXPECT_NE(unknown.status().message().find("'.3ds'"), std::string::npos);
  EXPECT_NE(unknown.status().message().find(".obj, .off, .ply, .stl, .gltf, .glb"), std::string::npos);
}

TEST(MeshImportErrors, NonFiniteCoordinates) {
  expectImportError("bad/nan.obj", ErrorCode::kInvalidMesh, {":3:", "vertex 2", "NaN"});
  expectImportError("bad/inf.off", ErrorCode::kInvalidMesh, {"vertex 3", "infinite"});
  expectImportError("bad/nan_binary.ply", ErrorCode::kInvalidMesh, {"vertex 1", "NaN"});
}

TEST(MeshImportErrors, BadIndices) {
  expectImportError("bad/out_of_range.obj", ErrorCode::kInvalidMesh,
                    {"face 2 (vertices 1, 2, 8)", "vertex index 8 is out of range", "4 vertices"});
  expectImportError("bad/out_of_range.off", ErrorCode::kInvalidMesh,
                    {"face 2", "vertex index 7 is out of range"});
  expectImportError("bad/negative_index.off", ErrorCode::kInvalidMesh, {"face 1", "vertex index -1"});
  expectImportError("bad/zero_index.obj", ErrorCode::kParseError,
                    {":6:", "face 1", "bad vertex reference '0'"});
  expectImportError("bad/bad_token.obj", ErrorCode::kParseError, {":7:", "face 2", "'4x'"});
  expectImportError("bad/short_vertex.obj", ErrorCode::kParseError,
                    {":2:", "vertex 1", "expected 3 coordinates"});
}

TEST(MeshImportErrors, DegenerateAndDuplicateFaces) {
  expectImportError("bad/repeated_vertex.obj", ErrorCode::kInvalidMesh,
                    {"face 1 (vertices 1, 1, 3)", "degenerate, repeats vertex 1"});
  expectImportError("bad/repeated_vertex.ply", ErrorCode::kInvalidMesh,
                    {"face 1 (vertices 0, 0, 3)", "degenerate, repeats vertex 0"});
  expectImportError("bad/zero_area.obj", ErrorCode::kInvalidMesh, {"face 2 (vertices 0, 2, 1)", "zero area"});
  expectImportError("bad/duplicate_face.obj", ErrorCode::kInvalidMesh,
                    {"face 4 (vertices 1, 0, 2)", "duplicates face 0 (vertices 0, 2, 1)"});
  expectImportError("bad/degenerate_facet.stl", ErrorCode::kInvalidMesh,
                    {":22:", "facet 2", "degenerate, corners 0 and 1 are the same point"});
}

TEST(MeshImportErrors, NonManifold) {
  expectImportError("bad/non_manifold_edge.obj", ErrorCode::kInvalidMesh,
                    {"edge 0-1", "non-manifold, used by 3 faces", "face 0", "face 1", "face 2"});
  expectImportError(
      "bad/inconsistent_orientation.obj", ErrorCode::kInvalidMesh,
      {"edge 0-2", "inconsistent orientation", "face 0 (vertices 0, 2, 1)", "face 3 (vertices 0, 2, 3)"});
  expectImportError("bad/non_manifold_vertex.obj", ErrorCode::kInvalidMesh,
                    {"vertex 0", "more than one fan"});
  expectImportError("bad/isolated_vertex.obj", ErrorCode::kInvalidMesh, {"vertex 4", "not used by any face"});
}

TEST(MeshImportErrors, EmptyMeshes) {
  expectImportError("bad/empty.obj", ErrorCode::kInvalidMesh, {"no vertices"});
  expectImportError("bad/no_faces.obj", ErrorCode::kInvalidMesh, {"no faces"});
}

TEST(MeshImportErrors, TruncatedFiles) {
  expectImportError("bad/truncated.off", ErrorCode::kParseError,
                    {":8:", "face 1", "expected 3 vertex indices"});
  expectImportError("bad/truncated.ply", ErrorCode::kParseError, {"truncated"});
  expectImportError("bad/truncated_header.ply", ErrorCode::kParseError, {"header", "end_header"});
  expectImportError("bad/truncated.stl", ErrorCode::kParseError, {"truncated", "endsolid"});
  expectImportError("bad/truncated_binary.stl", ErrorCode::kParseError, {"binary STL", "declares 4 facets"});
  expectImportError("bad/truncated.glb", ErrorCode::kParseError, {"malformed glTF"});
}

// Found by the fuzz smoke: a JSON chunk of 615 bytes (not a multiple of 4)
// and a BIN chunk that runs 3 bytes past the end; tinygltf 2.7 read 168
// bytes beyond the buffer (AddressSanitizer). Refused before it gets there.
TEST(MeshImportErrors, AGlbChunkOffItsAlignmentOrPastTheEndIsRefused) {
  expectImportError(
      "bad/fuzz_glb_chunk_past_the_end.glb", ErrorCode::kParseError,
      {"malformed glTF", "GLB container", "chunk 0 at byte 12", "615 bytes, not a multiple of 4"});
}

TEST(MeshImportErrors, TruncatedObjStopsAtTheBrokenLine) {
  const std::string dir = makeTempDir("tessera-import");
  const std::string text = readBytes(sourceTestDataPath("good/tetra.obj"));
  writeFile(dir + "/cut.obj", text.substr(0, text.size() - 4));  // "f 1 4 3" -> "f 1"
  auto mesh = importMesh(dir + "/cut.obj");
  ASSERT_FALSE(mesh.isOk());
  EXPECT_NE(mesh.status().message().find("cut.obj:10: face 3: has 1 vertices"), std::string::npos)
      << mesh.status().message();
  std::filesystem::remove_all(dir);
}

TEST(MeshImportErrors, Gltf) {
  expectImportError("bad/lines_mode.gltf", ErrorCode::kUnsupported,
                    {"meshes[0].primitives[0]", "mode 1", "only TRIANGLES"});
  expectImportError("bad/gltf_tag_out_of_range.gltf", ErrorCode::kNotFound,
                    {"meshes[0].extras.tessera.creases[1]", "vertex index"});
  expectImportError("bad/gltf_tag_negative.gltf", ErrorCode::kInvalidArgument,
                    {"meshes[0].extras.tessera.creases[0]", "sharpness"});
  // fuzz_import_gltf (session 10): a 37-digit crease index was converted to
  // int64 before its range was checked, undefined behaviour (UBSan). The
  // same input is in the fuzz seeds, which CI replays under UBSan.
  expectImportError("bad/fuzz_gltf_huge_crease_index.gltf", ErrorCode::kNotFound,
                    {"meshes[0].extras.tessera.creases[1]", "vertex index must be an integer in [0, 12)"});
}

TEST(MeshImportErrors, RandomBytesWithEveryExtension) {
  const std::string dir = makeTempDir("tessera-import");
  std::mt19937 rng(1234);
  std::string bytes(2048, '\0');
  for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
  for (const std::string& ext : supportedImportExtensions()) {
    SCOPED_TRACE(ext);
    const std::string path = dir + "/garbage" + ext;
    writeFile(path, bytes);
    auto mesh = importMesh(path);
    ASSERT_FALSE(mesh.isOk());
    EXPECT_NE(mesh.status().message().find("garbage" + ext), std::string::npos) << mesh.status().message();
  }
  std::filesystem::remove_all(dir);
}

TEST(MeshImport, RealCgalMeshesImport) {
  // 3torus.off has quads.
  for (const char* name : {"fandisk.off", "elephant.off", "3torus.off"}) {
    auto mesh = importMesh(::tessera::testing::cgalMeshPath(name), ImportOptions{.triangulate = true});
    EXPECT_TRUE(mesh.isOk()) << name << ": " << mesh.status().toString();
  }
}

}  // namespace
}  // namespace tessera

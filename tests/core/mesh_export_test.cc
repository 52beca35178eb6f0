// Round trips for exportMesh: OBJ and PLY read back with OpenMesh IO, GLB with
// tinygltf, Draco GLB decoded with draco::Decoder; then the input errors.
// The Khronos glTF-Validator run lives in tests/validator.cmake.
//
// OpenMesh requires MeshIO.hh before any mesh kernel header.
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <array>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/mesh_export.h"
#include "support/test_meshes.h"
#include "tools/sample_surfaces.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using ReadMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

class ExportTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::makeTempDir("tessera-export"); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (fs::path(dir_) / name).string(); }

  std::string dir_;
};

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Reads `path` with OpenMesh, asking for vertex normals when `withNormals`.
ReadMesh readWithOpenMesh(const std::string& path, bool withNormals) {
  ReadMesh mesh;
  mesh.request_vertex_normals();
  OpenMesh::IO::Options options =
      withNormals ? OpenMesh::IO::Options::VertexNormal : OpenMesh::IO::Options::Default;
  EXPECT_TRUE(OpenMesh::IO::read_mesh(mesh, path, options)) << path;
  EXPECT_EQ(options.check(OpenMesh::IO::Options::VertexNormal), withNormals) << path;
  return mesh;
}

// Faces compared up to rotation (a reader may start a face at any corner),
// never up to reflection: orientation must survive.
std::array<int, 3> canonicalFace(std::array<int, 3> f) {
  std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
  return f;
}

void expectSameSurface(const SurfaceMesh& surface, const ReadMesh& mesh, double tolerance, bool withNormals) {
  ASSERT_EQ(mesh.n_vertices(), surface.positions.size());
  ASSERT_EQ(mesh.n_faces(), surface.triangles.size());
  double maxPositionError = 0.0;
  double maxNormalError = 0.0;
  for (std::size_t i = 0; i < surface.positions.size(); ++i) {
    const auto vh = mesh.vertex_handle(static_cast<unsigned>(i));
    maxPositionError = std::max(maxPositionError, (mesh.point(vh) - surface.positions[i]).norm());
    if (withNormals) maxNormalError = std::max(maxNormalError, (mesh.normal(vh) - surface.normals[i]).norm());
  }
  EXPECT_LE(maxPositionError, tolerance);
  EXPECT_LE(maxNormalError, tolerance);
  for (std::size_t f = 0; f < surface.triangles.size(); ++f) {
    std::array<int, 3> read{};
    int c = 0;
    for (auto vh : mesh.fv_range(mesh.face_handle(static_cast<unsigned>(f)))) read[c++] = vh.idx();
    ASSERT_EQ(canonicalFace(read), canonicalFace(surface.triangles[f])) << "face " << f;
  }
}

TEST_F(ExportTest, ObjRoundTripIsLosslessWithNormals) {
  const SurfaceMesh surface = testing::makeTorusSurface(24, 12);
  ASSERT_TRUE(exportMesh(surface, path("torus.obj")).isOk());
  const std::string text = readFile(path("torus.obj"));
  EXPECT_NE(text.find("\nvn "), std::string::npos);
  EXPECT_NE(text.find("\nf 1//1 "), std::string::npos);
  // OpenMesh's OBJ reader parses into float, hence its tolerance ...
  expectSameSurface(surface, readWithOpenMesh(path("torus.obj"), true), 1e-6, true);
  // ... while the text itself holds every double exactly.
  std::istringstream lines(text);
  std::string line;
  std::size_t v = 0;
  while (std::getline(lines, line)) {
    if (line.rfind("v ", 0) != 0) continue;
    const char* cursor = line.data() + 2;
    const char* end = line.data() + line.size();
    for (int k = 0; k < 3; ++k) {
      double value = 0.0;
      const auto result = std::from_chars(cursor, end, value);
      ASSERT_EQ(result.ec, std::errc()) << line;
      ASSERT_EQ(value, surface.positions[v][k]) << "position " << v;
      cursor = result.ptr + 1;
    }
    ++v;
  }
  EXPECT_EQ(v, surface.positions.size());
}

TEST_F(ExportTest, ObjWithoutNormalsWritesPlainFaces) {
  SurfaceMesh surface = testing::makeTorusSurface(8, 6);
  surface.normals.clear();
  ASSERT_TRUE(exportMesh(surface, path("torus.obj")).isOk());
  const std::string text = readFile(path("torus.obj"));
  EXPECT_EQ(text.find("vn "), std::string::npos);
  EXPECT_EQ(text.find("//"), std::string::npos);
  expectSameSurface(surface, readWithOpenMesh(path("torus.obj"), false), 1e-6, false);
}

TEST_F(ExportTest, PlyRoundTripIsBinaryFloat32) {
  const SurfaceMesh surface = testing::makeTorusSurface(24, 12);
  ASSERT_TRUE(exportMesh(surface, path("torus.ply")).isOk());
  const std::string bytes = readFile(path("torus.ply"));
  EXPECT_EQ(bytes.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  // float32 storage: coordinates below 4 are within 2^-22 of the input.
  expectSameSurface(surface, readWithOpenMesh(path("torus.ply"), true), 1e-6, true);
}

TEST_F(ExportTest, ExtensionIsCaseInsensitive) {
  const SurfaceMesh surface = testing::makeTorusSurface(8, 6);
  ASSERT_TRUE(exportMesh(surface, path("UPPER.OBJ")).isOk());
  ASSERT_TRUE(exportMesh(surface, path("Mixed.Ply")).isOk());
  ASSERT_TRUE(exportMesh(surface, path("scene.GLB")).isOk());
  EXPECT_EQ(readFile(path("scene.GLB")).substr(0, 4), "glTF");
}

// ---- GLB ---------------------------------------------------------------------

tinygltf::Model loadGlb(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err;
  std::string warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, path)) << err;
  EXPECT_TRUE(err.empty()) << err;
  return model;
}

template <typename T>
std::vector<T> accessorData(const tinygltf::Model& model, int accessorIndex) {
  const tinygltf::Accessor& accessor = model.accessors.at(accessorIndex);
  const tinygltf::BufferView& view = model.bufferViews.at(accessor.bufferView);
  const std::size_t components = accessor.type == TINYGLTF_TYPE_VEC3 ? 3 : 1;
  std::vector<T> values(accessor.count * components);
  EXPECT_LE(accessor.byteOffset + values.size() * sizeof(T), view.byteLength);
  std::memcpy(values.data(),
              model.buffers.at(view.buffer).data.data() + view.byteOffset + accessor.byteOffset,
              values.size() * sizeof(T));
  return values;
}

void checkPlainGlb(const SurfaceMesh& surface, const std::string& file, int expectedIndexType) {
  const tinygltf::Model model = loadGlb(file);
  EXPECT_EQ(model.asset.version, "2.0");
  EXPECT_EQ(model.asset.generator, "Tessera");
  EXPECT_TRUE(model.extensionsUsed.empty());
  ASSERT_EQ(model.scenes.size(), 1u);
  ASSERT_EQ(model.nodes.size(), 1u);
  EXPECT_EQ(model.nodes[0].mesh, 0);
  ASSERT_EQ(model.meshes.size(), 1u);
  ASSERT_EQ(model.meshes[0].primitives.size(), 1u);
  const tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
  EXPECT_EQ(primitive.mode, TINYGLTF_MODE_TRIANGLES);
  for (const tinygltf::BufferView& view : model.bufferViews) EXPECT_EQ(view.byteOffset % 4, 0u);

  const int positionIndex = primitive.attributes.at("POSITION");
  const tinygltf::Accessor& positions = model.accessors[positionIndex];
  EXPECT_EQ(positions.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  EXPECT_EQ(positions.type, TINYGLTF_TYPE_VEC3);
  ASSERT_EQ(positions.count, surface.positions.size());
  EXPECT_EQ(model.bufferViews[positions.bufferView].target, TINYGLTF_TARGET_ARRAY_BUFFER);
  const std::vector<float> xyz = accessorData<float>(model, positionIndex);
  std::array<float, 3> lo{FLT_MAX, FLT_MAX, FLT_MAX};
  std::array<float, 3> hi{-FLT_MAX, -FLT_MAX, -FLT_MAX};
  for (std::size_t i = 0; i < surface.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(xyz[3 * i + k], static_cast<float>(surface.positions[i][k]));
      lo[k] = std::min(lo[k], xyz[3 * i + k]);
      hi[k] = std::max(hi[k], xyz[3 * i + k]);
    }
  }
  ASSERT_EQ(positions.minValues.size(), 3u);
  ASSERT_EQ(positions.maxValues.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    // Exact: the bounds must be those of the stored float32 values.
    EXPECT_EQ(positions.minValues[k], static_cast<double>(lo[k]));
    EXPECT_EQ(positions.maxValues[k], static_cast<double>(hi[k]));
  }

  const int normalIndex = primitive.attributes.at("NORMAL");
  const tinygltf::Accessor& normals = model.accessors[normalIndex];
  EXPECT_EQ(normals.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  ASSERT_EQ(normals.count, surface.positions.size());
  const std::vector<float> n = accessorData<float>(model, normalIndex);
  for (std::size_t i = 0; i < normals.count; ++i) {
    const double length = std::sqrt(double(n[3 * i]) * n[3 * i] + double(n[3 * i + 1]) * n[3 * i + 1] +
                                    double(n[3 * i + 2]) * n[3 * i + 2]);
    EXPECT_NEAR(length, 1.0, 1e-6) << "normal " << i;
  }

  const tinygltf::Accessor& indices = model.accessors[primitive.indices];
  EXPECT_EQ(indices.type, TINYGLTF_TYPE_SCALAR);
  EXPECT_EQ(indices.componentType, expectedIndexType);
  ASSERT_EQ(indices.count, surface.triangles.size() * 3);
  EXPECT_EQ(model.bufferViews[indices.bufferView].target, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  std::vector<std::uint32_t> read;
  if (expectedIndexType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
    for (std::uint16_t v : accessorData<std::uint16_t>(model, primitive.indices)) read.push_back(v);
  } else {
    read = accessorData<std::uint32_t>(model, primitive.indices);
  }
  for (std::size_t f = 0; f < surface.triangles.size(); ++f) {
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(read[3 * f + c], std::uint32_t(surface.triangles[f][c])) << "face " << f;
  }
}

TEST_F(ExportTest, GlbRoundTripWithShortIndices) {
  const SurfaceMesh surface = testing::makeTorusSurface(100, 50);
  ASSERT_TRUE(exportMesh(surface, path("torus.glb")).isOk());
  checkPlainGlb(surface, path("torus.glb"), TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
}

TEST_F(ExportTest, GlbUsesIntIndicesBeyond65535Vertices) {
  // 65,536 vertices: index 65535 would be the forbidden restart value of u16.
  const SurfaceMesh surface = testing::makeTorusSurface(256, 256);
  ASSERT_TRUE(exportMesh(surface, path("big.glb")).isOk());
  checkPlainGlb(surface, path("big.glb"), TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
}

TEST_F(ExportTest, GlbNormalisesNormals) {
  SurfaceMesh surface = testing::makeTorusSurface(8, 6);
  for (Vec3& n : surface.normals) n *= 3.5;
  ASSERT_TRUE(exportMesh(surface, path("scaled.glb")).isOk());
  for (Vec3& n : surface.normals) n /= 3.5;
  checkPlainGlb(surface, path("scaled.glb"), TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
}

// ---- errors ------------------------------------------------------------------

void expectError(const Status& status, ErrorCode code, const std::vector<std::string>& mentions) {
  ASSERT_FALSE(status.isOk());
  EXPECT_EQ(status.code(), code) << status.toString();
  for (const std::string& m : mentions)
    EXPECT_NE(status.message().find(m), std::string::npos) << status.toString();
}

TEST_F(ExportTest, RejectsUnknownExtensionListingSupportedOnes) {
  const SurfaceMesh surface = testing::makeTorusSurface(8, 6);
  expectError(exportMesh(surface, path("mesh.3ds")), ErrorCode::kUnsupported,
              {"mesh.3ds", ".3ds", ".obj", ".off", ".ply", ".stl", ".glb"});
  expectError(exportMesh(surface, path("mesh")), ErrorCode::kUnsupported, {"no extension", ".glb"});
  expectError(exportMesh(surface, path("mesh.gltf")), ErrorCode::kUnsupported, {".gltf"});
  EXPECT_FALSE(fs::exists(path("mesh.3ds")));
}

TEST_F(ExportTest, RejectsDracoForNonGlb) {
  ExportOptions options;
  options.draco = true;
  expectError(exportMesh(testing::makeTorusSurface(8, 6), path("mesh.obj"), options), ErrorCode::kUnsupported,
              {"Draco", ".glb"});
}

TEST_F(ExportTest, RejectsDracoOptionsOutOfRange) {
  const SurfaceMesh surface = testing::makeTorusSurface(8, 6);
  ExportOptions options;
  options.draco = true;
  options.dracoPositionBits = 0;
  expectError(exportMesh(surface, path("a.glb"), options), ErrorCode::kInvalidArgument,
              {"dracoPositionBits"});
  options = {};
  options.draco = true;
  options.dracoNormalBits = 31;
  expectError(exportMesh(surface, path("a.glb"), options), ErrorCode::kInvalidArgument, {"dracoNormalBits"});
  options = {};
  options.draco = true;
  options.dracoCompressionLevel = 11;
  expectError(exportMesh(surface, path("a.glb"), options), ErrorCode::kInvalidArgument,
              {"dracoCompressionLevel"});
  EXPECT_FALSE(fs::exists(path("a.glb")));
}

TEST_F(ExportTest, RejectsOutOfRangeIndexNamingTheTriangle) {
  SurfaceMesh surface = testing::makeTorusSurface(8, 6);
  surface.triangles[5][1] = 999;
  for (const char* name : {"bad.obj", "bad.ply", "bad.glb"}) {
    expectError(exportMesh(surface, path(name)), ErrorCode::kInvalidMesh, {name, "triangle 5", "999"});
    EXPECT_FALSE(fs::exists(path(name)));
  }
  surface.triangles[5][1] = -1;
  expectError(exportMesh(surface, path("bad.glb")), ErrorCode::kInvalidMesh, {"triangle 5", "-1"});
}

TEST_F(ExportTest, RejectsNonFiniteValuesNamingTheElement) {
  SurfaceMesh surface = testing::makeTorusSurface(8, 6);
  surface.positions[3][1] = std::numeric_limits<double>::quiet_NaN();
  expectError(exportMesh(surface, path("nan.glb")), ErrorCode::kInvalidMesh, {"position 3", "finite"});
  surface = testing::makeTorusSurface(8, 6);
  surface.normals[7][2] = std::numeric_limits<double>::infinity();
  expectError(exportMesh(surface, path("inf.ply")), ErrorCode::kInvalidMesh, {"normal 7", "finite"});
  surface = testing::makeTorusSurface(8, 6);
  surface.normals[4] = Vec3(0, 0, 0);
  expectError(exportMesh(surface, path("zero.glb")), ErrorCode::kInvalidMesh, {"normal 4", "zero"});
}

TEST_F(ExportTest, RejectsMismatchedNormalCount) {
  SurfaceMesh surface = testing::makeTorusSurface(8, 6);
  surface.normals.pop_back();
  expectError(exportMesh(surface, path("n.obj")), ErrorCode::kInvalidMesh, {"47 normals", "48 positions"});
}

TEST_F(ExportTest, RejectsEmptySurface) {
  expectError(exportMesh(SurfaceMesh{}, path("empty.glb")), ErrorCode::kInvalidMesh, {"no triangles"});
}

TEST_F(ExportTest, ReportsUnwritablePath) {
  const SurfaceMesh surface = testing::makeTorusSurface(8, 6);
  for (const char* name : {"x.obj", "x.ply", "x.glb"}) {
    const std::string target = path("missing-dir/" + std::string(name));
    expectError(exportMesh(surface, target), ErrorCode::kIoError, {target});
  }
  ExportOptions draco;
  draco.draco = true;
  expectError(exportMesh(surface, path("missing-dir/d.glb"), draco), ErrorCode::kIoError,
              {"missing-dir/d.glb"});
}

}  // namespace
}  // namespace tessera

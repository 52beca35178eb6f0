// Import as users have it (docs/FORMATS.md): every reader keeps the file's
// precision; --drop-unused renumbers vertices and tags; --crease-angle
// creases the edges its definition names, and the vertex rules follow;
// Tessera reads its own Draco exports back.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <gtest/gtest.h>

#include "core/io/mesh_export.h"
#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"
#include "core/loop/loop_refiner.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

std::string writeFile(const std::string& dir, const std::string& name, const std::string& bytes) {
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::string readFileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// ---------------------------------------------------------------- precision

// A 6-triangle fan of radius 0.05 around (1000, 1000, 1000), in a tilted
// plane, with coordinates that need every digit of a double.
std::vector<Vec3> farFan() {
  const Vec3 centre(1000.000000123456789, 999.99999987654321, 1000.0000000314159);
  const Vec3 u = Vec3(1, 0.3, -0.2).normalized();
  const Vec3 v = (Vec3(0.1, 0.2, 1) % u).normalized();
  std::vector<Vec3> points = {centre};
  for (int k = 0; k < 6; ++k) {
    const double a = 2 * M_PI * k / 6 + 0.1;
    points.push_back(centre + 0.05 * (std::cos(a) * u + std::sin(a) * v));
  }
  return points;
}

std::string g17(double x) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

// The definition: strtod of each coordinate token on the given lines.
std::vector<Vec3> strtodPoints(const std::string& text, int firstLine, int count, int skipTokens) {
  std::istringstream in(text);
  std::string line;
  std::vector<Vec3> points;
  for (int n = 0; std::getline(in, line); ++n) {
    if (n < firstLine || n >= firstLine + count) continue;
    std::istringstream tokens(line);
    std::string token;
    for (int k = 0; k < skipTokens; ++k) tokens >> token;
    double xyz[3];
    for (double& c : xyz) {
      tokens >> token;
      c = std::strtod(token.c_str(), nullptr);
    }
    points.emplace_back(xyz[0], xyz[1], xyz[2]);
  }
  return points;
}

void expectBitExact(const std::vector<Vec3>& got, const std::vector<Vec3>& want, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < want.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(std::memcmp(&got[i].v[k], &want[i].v[k], sizeof(double)), 0)
          << what << ": vertex " << i << " coordinate " << k << ": read " << g17(got[i][k]) << ", file "
          << g17(want[i][k]);
    }
  }
}

TEST(ImportPrecision, TextFormatsKeepEveryDigitOfADouble) {
  const std::vector<Vec3> fan = farFan();
  // The case is the right one: float would move these coordinates.
  int floatDiffers = 0;
  for (const Vec3& p : fan) {
    for (int k = 0; k < 3; ++k) floatDiffers += static_cast<double>(static_cast<float>(p[k])) != p[k];
  }
  ASSERT_EQ(floatDiffers, 21);

  std::string vertices, obj, off = "OFF\n7 6 0\n", ply;
  for (const Vec3& p : fan) vertices += g17(p[0]) + " " + g17(p[1]) + " " + g17(p[2]) + "\n";
  std::istringstream lines(vertices);
  for (std::string line; std::getline(lines, line);) obj += "v " + line + "\n";
  off += vertices;
  ply =
      "ply\nformat ascii 1.0\nelement vertex 7\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 6\nproperty list uchar int vertex_indices\nend_header\n" +
      vertices;
  for (int k = 0; k < 6; ++k) {
    const int a = 1 + k, b = 1 + (k + 1) % 6;
    obj += "f 1 " + std::to_string(a + 1) + " " + std::to_string(b + 1) + "\n";
    off += "3 0 " + std::to_string(a) + " " + std::to_string(b) + "\n";
    ply += "3 0 " + std::to_string(a) + " " + std::to_string(b) + "\n";
  }
  const std::string dir = testing::makeTempDir("tessera-precision");
  struct Case {
    std::string name, text;
    int firstLine, skip;
  };
  for (const Case& c : {Case{"fan.obj", obj, 0, 1}, Case{"fan.off", off, 2, 0}, Case{"fan.ply", ply, 9, 0}}) {
    const std::string path = writeFile(dir, c.name, c.text);
    auto mesh = importMesh(path);
    ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
    expectBitExact(mesh->positions(), strtodPoints(readFileText(path), c.firstLine, 7, c.skip), c.name);
  }
  std::filesystem::remove_all(dir);
}

// Binary PLY doubles, either byte order: the stored bits, unchanged.
TEST(ImportPrecision, BinaryPlyDoublesAreKeptBitForBit) {
  const std::vector<Vec3> fan = farFan();
  for (const bool big : {false, true}) {
    std::string ply = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex 7\nproperty double x\nproperty double y\nproperty double z\n"
                      "element face 6\nproperty list uchar int vertex_indices\nend_header\n";
    const auto put = [&ply, big](const void* value, size_t size) {
      const auto* bytes = static_cast<const char*>(value);
      for (size_t k = 0; k < size; ++k) ply += bytes[big ? size - 1 - k : k];
    };
    for (const Vec3& p : fan) {
      for (int k = 0; k < 3; ++k) put(&p.v[k], 8);
    }
    for (int k = 0; k < 6; ++k) {
      const unsigned char three = 3;
      const int32_t corners[3] = {0, 1 + k, 1 + (k + 1) % 6};
      put(&three, 1);
      for (int32_t c : corners) put(&c, 4);
    }
    auto mesh = importMeshFromBytes(ply, ".ply", big ? "big.ply" : "little.ply");
    ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
    expectBitExact(mesh->positions(), fan, big ? "big-endian PLY" : "little-endian PLY");
  }
}

// STL holds float: an ASCII STL's decimal text is rounded to float, as a
// binary STL would store it (the format's precision, documented).
TEST(ImportPrecision, StlIsFloatByFormat) {
  const std::vector<Vec3> fan = farFan();
  std::string stl = "solid fan\n";
  for (int k = 0; k < 6; ++k) {
    stl += "facet normal 0 0 0\nouter loop\n";
    for (int c : {0, 1 + k, 1 + (k + 1) % 6}) {
      stl += "vertex " + g17(fan[c][0]) + " " + g17(fan[c][1]) + " " + g17(fan[c][2]) + "\n";
    }
    stl += "endloop\nendfacet\n";
  }
  stl += "endsolid fan\n";
  auto mesh = importMeshFromBytes(stl, ".stl", "fan.stl");
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  std::vector<Vec3> asFloat;
  for (const Vec3& p : fan) {
    asFloat.emplace_back(static_cast<float>(std::strtod(g17(p[0]).c_str(), nullptr)),
                         static_cast<float>(std::strtod(g17(p[1]).c_str(), nullptr)),
                         static_cast<float>(std::strtod(g17(p[2]).c_str(), nullptr)));
  }
  expectBitExact(mesh->positions(), asFloat, "fan.stl");  // first appearance: centre, then the ring in order
}

// ------------------------------------------------------------- drop-unused

// A tetrahedron whose file has an unused vertex 2 between the used ones.
const char* kTetraWithUnused =
    "v 0 0 0\nv 1 0 0\nv 7 7 7\nv 0 1 0\nv 0 0 1\n"
    "f 1 4 2\nf 1 2 5\nf 2 4 5\nf 1 5 4\n";

TEST(ImportDropUnused, RefusedWithoutTheOptionNamingIt) {
  auto refused = importMeshFromBytes(kTetraWithUnused, ".obj", "unused.obj");
  ASSERT_FALSE(refused.isOk());
  EXPECT_EQ(refused.status().code(), ErrorCode::kInvalidMesh);
  EXPECT_NE(refused.status().message().find("unused.obj: vertex 2 (7, 7, 7): not used by any face"),
            std::string::npos)
      << refused.status().message();
  EXPECT_NE(refused.status().message().find("--drop-unused"), std::string::npos)
      << refused.status().message();
}

TEST(ImportDropUnused, DropsRenumbersAndRemapsTagsByTheFilesNumbers) {
  const ImportOptions options{.dropUnused = true};
  auto imported = importMeshFromBytesWithReport(kTetraWithUnused, ".obj", "unused.obj", options);
  ASSERT_TRUE(imported.isOk()) << imported.status().toString();
  const ImportReport& report = imported->report;
  EXPECT_EQ(report.renumbering.dropped, 1);
  EXPECT_EQ(report.renumbering.newIndex, (std::vector<int>{0, 1, -1, 2, 3}));
  EXPECT_EQ(describeImport(report, options), "dropped 1 unused vertex (--drop-unused)");
  BaseMesh& mesh = imported->mesh;
  EXPECT_EQ(mesh.positions(),
            (std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}));

  // Tags name the file's vertices: "crease 3 4" is the edge (0,1,0)-(0,0,1),
  // "corner 1" the vertex (1,0,0).
  const std::string dir = testing::makeTempDir("tessera-drop-unused");
  const std::string tags = writeFile(dir, "t.tags", "crease 3 4 inf\ncorner 1 2.5\n");
  ASSERT_TRUE(applyTagFile(tags, mesh, report.renumbering).isOk());
  const TriMesh& m = mesh.mesh();
  int creases = 0;
  for (auto e : m.edges()) {
    if (!isInfinite(mesh.edgeSharpness(e))) continue;
    ++creases;
    const Vec3 a(m.point(m.from_vertex_handle(m.halfedge_handle(e, 0))));
    const Vec3 b(m.point(m.to_vertex_handle(m.halfedge_handle(e, 0))));
    EXPECT_TRUE((a == Vec3(0, 1, 0) && b == Vec3(0, 0, 1)) || (a == Vec3(0, 0, 1) && b == Vec3(0, 1, 0)));
  }
  EXPECT_EQ(creases, 1);
  for (auto v : m.vertices()) {
    EXPECT_EQ(mesh.vertexSharpness(v), Vec3(m.point(v)) == Vec3(1, 0, 0) ? 2.5f : 0.0f)
        << "vertex " << v.idx();
  }
  // A tag on the dropped vertex, or beyond the file's vertices: named.
  BaseMesh copy = mesh;
  const Status dropped = applyTagFile(writeFile(dir, "d.tags", "corner 2 1\n"), copy, report.renumbering);
  EXPECT_NE(dropped.message().find("d.tags:1: corner 2: vertex 2 was dropped"), std::string::npos)
      << dropped.message();
  const Status missing = applyTagFile(writeFile(dir, "m.tags", "corner 5 1\n"), copy, report.renumbering);
  EXPECT_NE(missing.message().find("vertex 5 does not exist (the file has 5 vertices)"), std::string::npos)
      << missing.message();
  std::filesystem::remove_all(dir);
}

TEST(ImportDropUnused, AMeshWithEveryVertexUsedIsUnchanged) {
  auto imported = importMeshWithReport(testing::sourceTestDataPath("good/tetra.off"), {.dropUnused = true});
  ASSERT_TRUE(imported.isOk()) << imported.status().toString();
  EXPECT_TRUE(imported->report.renumbering.isIdentity());
  EXPECT_EQ(describeImport(imported->report, {.dropUnused = true}), "");
}

// ------------------------------------------------------------ crease angle

std::vector<VertexRule> rulesAtLevel0(const BaseMesh& mesh) {
  auto refiner = LoopRefiner::create(mesh, LoopOptions{}, LoopRefiner::Uniform{.levels = 1});
  EXPECT_TRUE(refiner.isOk()) << refiner.status().toString();
  const Level& level = refiner->level(0);
  return std::vector<VertexRule>(level.vertexRules.begin(), level.vertexRules.begin() + level.numVertices);
}

int infiniteCreases(const BaseMesh& mesh) {
  return mesh.tagCounts().infiniteCreases;
}

TEST(ImportCreaseAngle, CubeHasTwelveSharpEdgesAt30DegreesAndNoneAt100) {
  const std::string cube = testing::sourceTestDataPath("good/cube_quads.obj");
  auto at30 = importMeshWithReport(cube, {.triangulate = true, .creaseAngle = 30});
  ASSERT_TRUE(at30.isOk()) << at30.status().toString();
  EXPECT_EQ(at30->report.edgesCreasedByAngle, 12);
  EXPECT_EQ(infiniteCreases(at30->mesh), 12);
  // The creased edges are the cube's edges (endpoints differ in one
  // coordinate), never the triangulation's face diagonals.
  const TriMesh& m = at30->mesh.mesh();
  for (auto e : m.edges()) {
    const Vec3 d = Vec3(m.point(m.to_vertex_handle(m.halfedge_handle(e, 0)))) -
                   Vec3(m.point(m.from_vertex_handle(m.halfedge_handle(e, 0))));
    const int axes = (d[0] != 0) + (d[1] != 0) + (d[2] != 0);
    EXPECT_EQ(isInfinite(at30->mesh.edgeSharpness(e)), axes == 1) << "edge " << e.idx();
  }
  // Three sharp edges meet at each corner: the corner rule.
  for (VertexRule rule : rulesAtLevel0(at30->mesh)) EXPECT_EQ(rule, VertexRule::kCorner);

  auto at100 = importMeshWithReport(cube, {.triangulate = true, .creaseAngle = 100});
  ASSERT_TRUE(at100.isOk()) << at100.status().toString();
  EXPECT_EQ(at100->report.edgesCreasedByAngle, 0);
  EXPECT_EQ(infiniteCreases(at100->mesh), 0);
  for (VertexRule rule : rulesAtLevel0(at100->mesh)) EXPECT_EQ(rule, VertexRule::kSmooth);
  EXPECT_EQ(describeImport(at100->report, {.creaseAngle = 100}),
            "creased 0 edges sharper than 100 degrees (--crease-angle)");
}

// A closed 16-sided prism with polygon caps: neighbouring sides meet at
// 360/16 = 22.5 degrees, sides and caps at 90.
std::string prismObj(int sides) {
  std::string obj;
  for (int z = 0; z < 2; ++z) {
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * M_PI * k / sides;
      obj += "v " + g17(std::cos(a)) + " " + g17(std::sin(a)) + " " + std::to_string(3 * z) + "\n";
    }
  }
  for (int k = 0; k < sides; ++k) {
    const int a = k + 1, b = (k + 1) % sides + 1;
    obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(b + sides) + " " +
           std::to_string(a + sides) + "\n";
  }
  std::string bottom = "f", top = "f";
  for (int k = 0; k < sides; ++k) {
    bottom += " " + std::to_string(sides - k);  // clockwise seen from above: faces down
    top += " " + std::to_string(sides + k + 1);
  }
  return obj + bottom + "\n" + top + "\n";
}

TEST(ImportCreaseAngle, PrismRimsAreCreasesAndSidesFollowTheAngle) {
  const std::string obj = prismObj(16);
  auto at30 =
      importMeshFromBytesWithReport(obj, ".obj", "prism.obj", {.triangulate = true, .creaseAngle = 30});
  ASSERT_TRUE(at30.isOk()) << at30.status().toString();
  EXPECT_EQ(at30->report.edgesCreasedByAngle, 32);  // the two rims
  // Every vertex is on a rim, on two sharp edges: the crease rule.
  for (VertexRule rule : rulesAtLevel0(at30->mesh)) EXPECT_EQ(rule, VertexRule::kCrease);

  auto at20 =
      importMeshFromBytesWithReport(obj, ".obj", "prism.obj", {.triangulate = true, .creaseAngle = 20});
  ASSERT_TRUE(at20.isOk()) << at20.status().toString();
  EXPECT_EQ(at20->report.edgesCreasedByAngle, 48);  // rims and the 16 side edges
  for (VertexRule rule : rulesAtLevel0(at20->mesh)) EXPECT_EQ(rule, VertexRule::kCorner);
}

TEST(ImportCreaseAngle, TriangulationDiagonalsAreNeverCreased) {
  // One quad folded along its diagonal 1-3 by more than 30 degrees: the
  // diagonal is not an edge of the file, and the file has only boundary edges.
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0.9\nv 0 1 0\nf 1 2 3 4\n";
  auto mesh =
      importMeshFromBytesWithReport(quad, ".obj", "fold.obj", {.triangulate = true, .creaseAngle = 30});
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  const auto faces = mesh->mesh.faceVertexIndices();
  const std::vector<Vec3> p = mesh->mesh.positions();
  const Vec3 n0 = (p[faces[0][1]] - p[faces[0][0]]) % (p[faces[0][2]] - p[faces[0][0]]);
  const Vec3 n1 = (p[faces[1][1]] - p[faces[1][0]]) % (p[faces[1][2]] - p[faces[1][0]]);
  ASSERT_GT(std::atan2((n0 % n1).norm(), n0 | n1), 30 * M_PI / 180);  // the case is the right one
  EXPECT_EQ(mesh->report.edgesCreasedByAngle, 0);
  EXPECT_EQ(infiniteCreases(mesh->mesh), 0);
}

TEST(ImportCreaseAngle, ExplicitTagsWinOverTheAngle) {
  // glTF extras tags are applied after the angle: the semi-sharp tag stays.
  auto mesh = importMeshWithReport(testing::sourceTestDataPath("good/tetra_split.gltf"), {.creaseAngle = 10});
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
  EXPECT_EQ(mesh->report.edgesCreasedByAngle, 6);  // this tetrahedron's edges: 90 and 125 degrees
  EXPECT_EQ(mesh->mesh.tagCounts().semiSharpCreases, 1);
  EXPECT_EQ(mesh->mesh.tagCounts().infiniteCreases, 5);
}

// ------------------------------------------------------------------- Draco

// Tessera reads its own Draco export back: same counts, every position
// within Draco's quantization (one grid step of the largest extent over
// 2^bits - 1, the bound ExportOptions documents).
TEST(ImportDraco, ReadsItsOwnDracoExportWithinTheQuantization) {
  auto fandisk = importMesh(testing::cgalMeshPath("fandisk.off"));
  ASSERT_TRUE(fandisk.isOk()) << fandisk.status().toString();
  SurfaceMesh surface;
  surface.positions = fandisk->positions();
  surface.triangles = fandisk->faceVertexIndices();
  const std::string dir = testing::makeTempDir("tessera-draco-back");
  for (int bits : {16, 11}) {
    ExportOptions options;
    options.draco = true;
    options.dracoPositionBits = bits;
    const std::string path = dir + "/fandisk" + std::to_string(bits) + ".glb";
    ASSERT_TRUE(exportMesh(surface, path, options).isOk());
    auto back = importMesh(path);
    ASSERT_TRUE(back.isOk()) << back.status().toString();
    ASSERT_EQ(back->numVertices(), fandisk->numVertices());
    ASSERT_EQ(back->numFaces(), fandisk->numFaces());
    const BoundingBox box = fandisk->boundingBox();
    const double bound = (box.max - box.min).max() / (std::ldexp(1.0, bits) - 1.0);
    double worst = 0;
    for (const Vec3& q : back->positions()) {
      double best = 1e300;
      for (const Vec3& p : surface.positions) {
        const Vec3 d = p - q;
        best = std::min(best, std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])}));
      }
      worst = std::max(worst, best);
    }
    std::cout << "[ draco    ] fandisk " << bits << "-bit: worst coordinate error " << worst << " (bound "
              << bound << ")\n";
    EXPECT_LE(worst, bound) << bits << " bits";
    EXPECT_GT(worst, 0) << "quantized positions cannot all be exact";
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tessera

// The real `tessera` binary with the import options of docs/FORMATS.md
// (--drop-unused, --crease-angle, polygons) and every output format read
// back (OBJ, OFF, PLY, STL, GLB).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "cli/cli_run.h"
#include "core/io/mesh_import.h"

namespace tessera {
namespace {

std::string cube() {
  return testing::sourceTestDataPath("cube.obj");
}
std::string cubeQuads() {
  return testing::sourceTestDataPath("good/cube_quads.obj");
}

std::string write(const std::string& dir, const std::string& name, const std::string& text) {
  std::ofstream(dir + "/" + name, std::ios::binary) << text;
  return dir + "/" + name;
}

std::vector<std::array<double, 3>> sortedPositions(const BaseMesh& mesh, bool asFloat) {
  std::vector<std::array<double, 3>> p;
  for (const Vec3& v : mesh.positions()) {
    p.push_back(asFloat ? std::array<double, 3>{float(v[0]), float(v[1]), float(v[2])}
                        : std::array<double, 3>{v[0], v[1], v[2]});
  }
  std::sort(p.begin(), p.end());
  return p;
}

// Every output format reads back as the same mesh: OBJ and OFF exactly (the
// shortest round-trip text of each double), PLY, STL and GLB as float32.
TEST(CliExport, EveryFormatReadsBack) {
  const std::string dir = testing::makeTempDir("tessera-every-format");
  for (const char* ext : {".obj", ".off", ".ply", ".stl", ".glb"}) {
    CliRun r = runCli("refine " + cube() + " --level 2 -o " + dir + "/cube" + ext);
    ASSERT_EQ(r.exitCode, 0) << ext << ": " << r.err;
    EXPECT_NE(r.out.find("98 vertices, 192 triangles"), std::string::npos) << r.out;
  }
  auto obj = importMesh(dir + "/cube.obj");
  ASSERT_TRUE(obj.isOk()) << obj.status().toString();
  for (const char* ext : {".off", ".ply", ".stl", ".glb"}) {
    SCOPED_TRACE(ext);
    auto back = importMesh(dir + "/cube" + ext);
    ASSERT_TRUE(back.isOk()) << back.status().toString();
    EXPECT_EQ(back->numVertices(), 98);
    EXPECT_EQ(back->numFaces(), 192);
    const bool text = std::string(ext) == ".off";
    EXPECT_EQ(sortedPositions(*back, !text), sortedPositions(*obj, !text));
  }
  // OFF keeps the face order and corners of OBJ.
  auto off = importMesh(dir + "/cube.off");
  ASSERT_TRUE(off.isOk());
  EXPECT_EQ(off->faceVertexIndices(), obj->faceVertexIndices());
  EXPECT_EQ(off->positions(), obj->positions());
  std::filesystem::remove_all(dir);
}

TEST(CliImport, DropUnusedSaysHowManyAndRemapsTags) {
  const std::string dir = testing::makeTempDir("tessera-drop-unused");
  const std::string mesh = write(dir, "unused.obj",
                                 "v 0 0 0\nv 1 0 0\nv 7 7 7\nv 0 1 0\nv 0 0 1\n"
                                 "f 1 4 2\nf 1 2 5\nf 2 4 5\nf 1 5 4\n");
  const std::string tags = write(dir, "unused.tags", "crease 3 4 inf\n");
  CliRun refused = runCli("info " + mesh);
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_NE(refused.err.find("vertex 2 (7, 7, 7): not used by any face"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--drop-unused"), std::string::npos) << refused.err;

  CliRun info = runCli("info " + mesh + " --drop-unused --tags " + tags);
  ASSERT_EQ(info.exitCode, 0) << info.err;
  EXPECT_NE(info.err.find("tessera info: " + mesh + ": dropped 1 unused vertex (--drop-unused)"),
            std::string::npos)
      << info.err;
  EXPECT_NE(info.out.find("vertices        4\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("creases         1 infinite"), std::string::npos) << info.out;

  CliRun doc = runCli("doc new " + mesh + " --drop-unused -o " + dir + "/unused.tsd");
  ASSERT_EQ(doc.exitCode, 0) << doc.err;
  EXPECT_NE(doc.err.find("tessera doc new: " + mesh + ": dropped 1 unused vertex"), std::string::npos)
      << doc.err;

  const std::string onDropped = write(dir, "dropped.tags", "corner 2 inf\n");
  CliRun bad =
      runCli("refine " + mesh + " --drop-unused --tags " + onDropped + " --level 1 -o " + dir + "/x.obj");
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("dropped.tags:1: corner 2: vertex 2 was dropped"), std::string::npos) << bad.err;
  std::filesystem::remove_all(dir);
}

TEST(CliImport, CreaseAngleCreasesTheCubesEdges) {
  const std::string dir = testing::makeTempDir("tessera-crease-angle");
  CliRun info = runCli("info " + cubeQuads() + " --triangulate --crease-angle 30");
  ASSERT_EQ(info.exitCode, 0) << info.err;
  EXPECT_NE(info.out.find("creases         12 infinite, 0 semi-sharp\n"), std::string::npos) << info.out;
  EXPECT_NE(info.err.find("creased 12 edges sharper than 30 degrees (--crease-angle)"), std::string::npos)
      << info.err;
  CliRun flat = runCli("info " + cubeQuads() + " --triangulate --crease-angle=100");
  ASSERT_EQ(flat.exitCode, 0) << flat.err;
  EXPECT_NE(flat.out.find("creases         0 infinite"), std::string::npos) << flat.out;
  // The creased cube refines to a cube: its corners stay put at the limit.
  CliRun limit = runCli("refine " + cubeQuads() + " --triangulate --crease-angle 30 --level 3 --limit -o " +
                        dir + "/cube.obj");
  ASSERT_EQ(limit.exitCode, 0) << limit.err;
  auto refined = importMesh(dir + "/cube.obj");
  ASSERT_TRUE(refined.isOk()) << refined.status().toString();
  const BoundingBox box = refined->boundingBox();
  auto base = importMesh(cubeQuads(), {.triangulate = true});
  ASSERT_TRUE(base.isOk());
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(box.min[k], base->boundingBox().min[k], 1e-12);
    EXPECT_NEAR(box.max[k], base->boundingBox().max[k], 1e-12);
  }
  for (const char* bad : {"200", "-1", "nan", "ten"}) {
    CliRun r = runCli("info " + cube() + " --crease-angle " + bad);
    EXPECT_EQ(r.exitCode, 2) << bad;
    EXPECT_NE(r.err.find("--crease-angle: expects degrees from 0 to 180, got '" + std::string(bad) + "'"),
              std::string::npos)
        << r.err;
  }
  std::filesystem::remove_all(dir);
}

TEST(CliImport, ConcavePolygonsAndDracoInputRefine) {
  const std::string dir = testing::makeTempDir("tessera-polygons");
  // A concave pentagon fanned from corner 0 would overlap itself.
  const std::string arrow =
      write(dir, "arrow.obj", "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 2 1 0\nv 0 4 0\nf 1 2 3 4 5\n");
  CliRun refined = runCli("refine " + arrow + " --triangulate --level 1 -o " + dir + "/arrow.ply");
  ASSERT_EQ(refined.exitCode, 0) << refined.err;
  const std::string star =
      write(dir, "star.obj",
            "v 1 0 0\nv 0.309 0.951 0\nv -0.809 0.588 0\nv -0.809 -0.588 0\nv 0.309 -0.951 0\n"
            "f 1 3 5 2 4\n");
  CliRun refused = runCli("refine " + star + " --triangulate --level 1 -o " + dir + "/star.ply");
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_NE(
      refused.err.find(star + ": face 0 (vertices 0, 2, 4, 1, 3): cannot be triangulated: self-intersecting"),
      std::string::npos)
      << refused.err;
  // Tessera reads its own Draco export as input to refine.
  ASSERT_EQ(runCli("refine " + cube() + " --level 1 --draco -o " + dir + "/d.glb").exitCode, 0);
  CliRun again = runCli("refine " + dir + "/d.glb --level 1 -o " + dir + "/again.obj");
  ASSERT_EQ(again.exitCode, 0) << again.err;
  EXPECT_NE(again.out.find("98 vertices, 192 triangles"), std::string::npos) << again.out;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tessera

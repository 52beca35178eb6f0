// `tessera refine --scheme`: the real binary on polygon and triangle input,
// the counts each scheme must produce, and the refusals (exit 2, naming the
// option) where a scheme has no creases or no limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "cli/cli_run.h"
#include "core/util/vec3.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

std::string writeQuadCube(const std::string& dir) {
  const std::string path = dir + "/quad-cube.obj";
  std::ofstream(path)
      << "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
         "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  return path;
}

TEST(CliScheme, CatmullClarkRefinesQuadsAsQuads) {
  const std::string dir = testing::makeTempDir("cli-scheme");
  const std::string cube = writeQuadCube(dir);
  // Level 1: 8 + 6 + 12 vertices, 24 quads, written as quads.
  CliRun run = runCli("refine " + cube + " --scheme catmull-clark --level 1 -o " + dir + "/cc1.obj");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("26 vertices, 24 polygons (level 1)"), std::string::npos) << run.out;
  const std::string obj = readAll(dir + "/cc1.obj");
  size_t quads = 0, faces = 0;
  for (size_t at = obj.find("\nf "); at != std::string::npos; at = obj.find("\nf ", at + 1)) {
    const std::string line = obj.substr(at + 1, obj.find('\n', at + 1) - at - 1);
    ++faces;
    quads += std::count(line.begin(), line.end(), ' ') == 4;
  }
  EXPECT_EQ(faces, 24u);
  EXPECT_EQ(quads, 24u);
  // STL and GLB take triangles: two per quad.
  run = runCli("refine " + cube + " --scheme catmull-clark --level 1 -o " + dir + "/cc1.stl");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("26 vertices, 48 triangles (level 1)"), std::string::npos) << run.out;
  // The corner (1, 1, 1) moves to 5/9 of itself (the shortest round-trip decimal).
  EXPECT_NE(readAll(dir + "/cc1.obj").find("v 0.5555555555555556 0.5555555555555556 0.5555555555555556"),
            std::string::npos);
  run = runCli("refine " + cube + " --scheme=catmull-clark --level 2 --limit -o " + dir + "/cc2.ply");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("98 vertices, 96 polygons (level 2, limit surface)"), std::string::npos) << run.out;
}

// Tags in the OBJ itself (OpenSubdiv's `t` dialect, docs/FORMATS.md): the
// cage's options apply unless the command line says otherwise, which is
// refused naming both; the refined cage is written with its tags.
TEST(CliScheme, AnObjsOwnTagsAndOptionsAreReadAndTheRefinedCageKeepsThem) {
  const std::string dir = testing::makeTempDir("cli-scheme");
  const std::string tagged = dir + "/tagged.obj";
  std::ofstream(tagged) << readAll(writeQuadCube(dir))
                        << "t crease 2/1/0 0 1 2\nt corner 1/1/0 6 inf\nt interpolateboundary 1/0/0 1\n";
  CliRun run = runCli("refine " + tagged + " --scheme catmull-clark --level 1 -o " + dir + "/cage.obj");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::string cage = readAll(dir + "/cage.obj");
  EXPECT_NE(cage.find("t interpolateboundary 1/0/0 1\n"), std::string::npos) << cage;
  EXPECT_NE(cage.find("t creasemethod 0/0/1 normal\n"), std::string::npos) << cage;
  // The crease's two halves at level 1, sharpness 2 - 1 = 1; the corner
  // stays infinitely sharp (10, OpenSubdiv's infinite sharpness).
  size_t creases = 0;
  for (size_t at = cage.find("t crease 2/1/0 "); at != std::string::npos;
       at = cage.find("t crease 2/1/0 ", at + 1))
    creases += cage.compare(cage.find('\n', at) - 2, 2, " 1") == 0;
  EXPECT_EQ(creases, 2u) << cage;
  EXPECT_NE(cage.find("t corner 1/1/0 6 10\n"), std::string::npos) << cage;
  run = runCli("refine " + tagged + " --scheme catmull-clark --level 1 --boundary edge-only -o " + dir +
               "/x.obj");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("--boundary edge-only: " + tagged + " says edge-and-corner (t interpolateboundary)"),
            std::string::npos)
      << run.err;
}

TEST(CliScheme, EveryOtherSchemeWritesItsCounts) {
  const std::string dir = testing::makeTempDir("cli-scheme");
  const std::string cube = writeQuadCube(dir);
  // Bilinear: as Catmull-Clark's topology. Doo-Sabin: one face per face,
  // edge and vertex (6 quads, 12 quads, 8 triangles: 26 polygons, or
  // 6*2 + 12*2 + 8 = 44 triangles).
  CliRun run = runCli("refine " + cube + " --scheme bilinear --level 1 -o " + dir + "/b.obj");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("26 vertices, 24 polygons"), std::string::npos) << run.out;
  run = runCli("refine " + cube + " --scheme doo-sabin --level 1 -o " + dir + "/d.off");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("24 vertices, 26 polygons"), std::string::npos) << run.out;
  {
    std::istringstream off(readAll(dir + "/d.off"));
    std::string magic;
    int vertices = 0, faces = 0, edges = 0;
    off >> magic >> vertices >> faces >> edges;
    ASSERT_EQ(faces, 26);
    double coordinate = 0;
    for (int k = 0; k < 3 * vertices; ++k) off >> coordinate;
    std::map<int, int> bySize;
    for (int f = 0; f < faces; ++f) {
      int n = 0, v = 0;
      off >> n;
      for (int k = 0; k < n; ++k) off >> v;
      ++bySize[n];
    }
    EXPECT_EQ(bySize, (std::map<int, int>{{3, 8}, {4, 18}}));
  }
  run = runCli("refine " + cube + " --scheme doo-sabin --level 1 -o " + dir + "/d.glb");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("24 vertices, 44 triangles"), std::string::npos) << run.out;
  // Triangle schemes on the triangulated cube (12 triangles, 18 edges).
  const std::string triangles = testing::sourceTestDataPath("cube.obj");
  run = runCli("refine " + triangles + " --scheme butterfly --level 1 -o " + dir + "/bf.obj");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("26 vertices, 48 triangles"), std::string::npos) << run.out;
  run = runCli("refine " + triangles + " --scheme sqrt3 --level 2 --limit -o " + dir + "/s3.obj");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  // Each step: a vertex per face, three triangles per triangle.
  EXPECT_NE(run.out.find("56 vertices, 108 triangles (level 2, limit surface)"), std::string::npos)
      << run.out;
}

TEST(CliScheme, RefusalsNameTheOption) {
  const std::string dir = testing::makeTempDir("cli-scheme");
  const std::string cube = writeQuadCube(dir);
  const std::string triangles = testing::sourceTestDataPath("cube.obj");
  struct Case {
    std::string args, expected;
  };
  const Case cases[] = {
      {"refine " + cube + " --scheme kobbelt --level 1 -o " + dir + "/x.obj", "--scheme"},
      {"refine " + triangles + " --scheme butterfly --limit --level 1 -o " + dir + "/x.obj", "--limit"},
      {"refine " + cube + " --scheme doo-sabin --tags " + testing::sourceTestDataPath("cube.tags") +
           " --level 1 -o " + dir + "/x.obj",
       "--tags"},
      {"refine " + cube + " --scheme bilinear --crease-method chaikin --level 1 -o " + dir + "/x.obj",
       "--crease-method"},
      {"refine " + cube + " --scheme catmull-clark --triangulate --level 1 -o " + dir + "/x.obj",
       "--triangulate"},
  };
  for (const Case& c : cases) {
    const CliRun run = runCli(c.args);
    EXPECT_EQ(run.exitCode, 2) << c.args << "\n" << run.err;
    EXPECT_NE(run.err.find(c.expected), std::string::npos) << run.err;
  }
  // Not usage errors: a polygon level has no Catmull-Clark limit masks;
  // sqrt3 refuses a boundary. Both exit 1 with the file named.
  std::ofstream(dir + "/open.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
  CliRun run = runCli("refine " + dir + "/open.obj --scheme sqrt3 --level 1 -o " + dir + "/x.obj");
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_NE(run.err.find("boundary"), std::string::npos) << run.err;
  std::ofstream(dir + "/tri.obj")
      << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
  run = runCli("refine " + dir + "/tri.obj --scheme catmull-clark --level 0 --limit -o " + dir + "/x.obj");
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_NE(run.err.find("tri.obj"), std::string::npos) << run.err;
}

// `tessera doc new` on quads: a Catmull-Clark document by default (said on
// stderr), kept in the file; --scheme loop refuses a quad by name; edits by
// script and exports keep the quads; the adaptive export triangulates.
TEST(CliScheme, DocNewMakesACatmullClarkDocumentOfQuads) {
  const std::string dir = testing::makeTempDir("cli-scheme");
  const std::string cube = writeQuadCube(dir);
  CliRun run = runCli("doc new " + cube + " --max-level 3 -o " + dir + "/cc.tsd");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.err.find(cube + ": 6 of 6 faces are not triangles: a catmull-clark document"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.out.find("8 vertices, 6 faces, catmull-clark, max level 3"), std::string::npos) << run.out;
  run = runCli("doc info " + dir + "/cc.tsd");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("scheme          catmull-clark, uniform creases, edge-only boundary"),
            std::string::npos)
      << run.out;

  run = runCli("doc new " + cube + " --scheme loop -o " + dir + "/loop.tsd");
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.err.find("only triangles"), std::string::npos) << run.err;
  run = runCli("doc new " + cube + " --triangulate -o " + dir + "/tri.tsd");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("12 faces, loop"), std::string::npos) << run.out;
  run = runCli("doc new " + cube + " --scheme catmull-clark --drop-unused -o " + dir + "/x.tsd");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("--drop-unused: not available for a catmull-clark document"), std::string::npos)
      << run.err;

  std::ofstream(dir + "/edits.txt") << "move v1:7 to 0.6 0.6 0.7\ncrease e0:0 2\noffset v2:30 by 0 0 0.05\n";
  run = runCli("doc edit " + dir + "/cc.tsd --script " + dir + "/edits.txt");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  run = runCli("doc export " + dir + "/cc.tsd --level 2 -o " + dir + "/cc2.obj");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("98 vertices, 96 polygons (level 2)"), std::string::npos) << run.out;
  run = runCli("doc export " + dir + "/cc.tsd --level 1 --limit -o " + dir + "/limit1.obj");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  // v1:7 (the child of the cube's eighth corner keeps its index): its
  // limit went where it was dragged.
  std::istringstream limit(readAll(dir + "/limit1.obj"));
  std::vector<Vec3> positions;
  for (std::string line; std::getline(limit, line);) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream xyz(line.substr(2));
    Vec3 p;
    xyz >> p[0] >> p[1] >> p[2];
    positions.push_back(p);
  }
  ASSERT_GT(positions.size(), 7u);
  EXPECT_LE((positions[7] - Vec3(0.6, 0.6, 0.7)).norm(), 1e-9);
  // The adaptive tessellation, capped at the document's level 3: at this
  // threshold every leaf is a quad of level 3 (64 per base face, two
  // triangles each), and the six base faces make one region group.
  run = runCli("doc export " + dir + "/cc.tsd --adaptive --max-level 4 --angle 5 -o " + dir + "/a.glb");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("768 triangles in 1 regions"), std::string::npos) << run.out;
}

// `doc view` on a Catmull-Clark document: the quad split's tiles, a near
// camera finer than a far one (docs/VIEWS.md "Catmull-Clark documents").
TEST(CliScheme, DocViewShowsTheQuadSplitsTiles) {
  const std::string dir = testing::makeTempDir("cli-scheme");
  const std::string cube = writeQuadCube(dir);
  ASSERT_EQ(runCli("doc new " + cube + " --max-level 6 -o " + dir + "/cc.tsd").exitCode, 0);
  CliRun far = runCli("doc view " + dir + "/cc.tsd --eye 0 0 40 --target 0 0 0 --size 390x844");
  ASSERT_EQ(far.exitCode, 0) << far.err;
  // Six quads, two triangles each.
  EXPECT_NE(far.out.find("first picture: the level-0 tiles, 12 triangles"), std::string::npos) << far.out;
  CliRun near = runCli("doc view " + dir + "/cc.tsd --eye 0.2 0.3 1.3 --target 0 0 1 --size 1920x1080");
  ASSERT_EQ(near.exitCode, 0) << near.err;
  auto finest = [](const std::string& out) {
    const size_t at = out.find("the whole document at level ");
    return at == std::string::npos ? -1 : std::stoi(out.substr(at + 28));
  };
  EXPECT_GT(finest(near.out), finest(far.out)) << far.out << near.out;
  EXPECT_GE(finest(near.out), 5) << near.out;
}

}  // namespace
}  // namespace tessera

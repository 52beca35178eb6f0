// The real `tessera` binary, run as a user would: exit codes, outputs and
// error messages (never a signal).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli/cli_run.h"
#include "core/io/mesh_import.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

std::string cube() {
  return testing::sourceTestDataPath("cube.obj");
}
std::string cubeTags() {
  return testing::sourceTestDataPath("cube.tags");
}

TEST(Cli, HelpForEveryCommand) {
  for (const char* args : {"--help", "info --help", "refine --help", "doc --help", "doc new --help",
                           "doc view --help", "remote --help", "remote edit --help", "-h"}) {
    CliRun r = runCli(args);
    EXPECT_EQ(r.exitCode, 0) << args;
    EXPECT_NE(r.out.find("Usage: tessera"), std::string::npos) << args;
    EXPECT_TRUE(r.err.empty()) << args << ": " << r.err;
  }
  CliRun none = runCli("");
  EXPECT_EQ(none.exitCode, 2);
  CliRun unknown = runCli("frobnicate");
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_NE(unknown.err.find("unknown command 'frobnicate'"), std::string::npos);
}

TEST(Cli, InfoDescribesTheCube) {
  CliRun r = runCli("info " + cube() + " --tags " + cubeTags());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("vertices        8\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("faces           12\n"), std::string::npos);
  EXPECT_NE(r.out.find("edges           18\n"), std::string::npos);
  EXPECT_NE(r.out.find("valence         4:4 5:4 \n"), std::string::npos);
  EXPECT_NE(r.out.find("genus           0\n"), std::string::npos);
  EXPECT_NE(r.out.find("boundary loops  0\n"), std::string::npos);
  EXPECT_NE(r.out.find("creases         4 infinite, 8 semi-sharp\n"), std::string::npos);
  EXPECT_NE(r.out.find("sharp vertices  1\n"), std::string::npos);
  EXPECT_NE(r.out.find("bbox diagonal   1.73205081\n"), std::string::npos);
}

TEST(Cli, InfoFindsGenusOfARealMesh) {
  // 3torus.off is made of quads: --triangulate fans them.
  CliRun r = runCli("info " + testing::cgalMeshPath("3torus.off") + " --triangulate");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("genus           3\n"), std::string::npos) << r.out;
}

TEST(Cli, RefineWritesEveryFormat) {
  const std::string dir = testing::makeTempDir("tessera-refine");
  for (const char* ext : {".obj", ".ply", ".glb"}) {
    const std::string out = dir + "/cube" + ext;
    CliRun r = runCli("refine " + cube() + " --tags " + cubeTags() + " --level 2 -o " + out);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(out));
    EXPECT_NE(r.out.find("98 vertices, 192 triangles"), std::string::npos) << r.out;
  }
  CliRun draco = runCli("refine " + cube() + " --level 3 --limit --draco -o " + dir + "/limit.glb");
  ASSERT_EQ(draco.exitCode, 0) << draco.err;
  // Control points at level 2 re-import as the same closed mesh.
  auto back = importMesh(dir + "/cube.obj");
  ASSERT_TRUE(back.isOk()) << back.status().toString();
  EXPECT_EQ(back->numVertices(), 98);
  EXPECT_EQ(back->numFaces(), 192);
}

TEST(Cli, LimitKeepsTheTaggedCornerInPlace) {
  const std::string out = testing::makeTempDir("tessera-limit") + "/limit.obj";
  CliRun r = runCli("refine " + cube() + " --tags " + cubeTags() + " --level 3 --limit -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  auto back = importMesh(out);
  ASSERT_TRUE(back.isOk()) << back.status().toString();
  // Vertex 6 is tagged an infinitely sharp corner: its limit is its position.
  const Vec3 corner = back->mesh().point(back->mesh().vertex_handle(6));
  EXPECT_NEAR(corner[0], 1.0, 1e-12);
  EXPECT_NEAR(corner[1], 1.0, 1e-12);
  EXPECT_NEAR(corner[2], 1.0, 1e-12);
}

TEST(Cli, ErrorsExitCleanlyWithMessages) {
  struct Case {
    std::string args;
    int exitCode;
    std::string message;
  };
  const std::string dir = testing::makeTempDir("tessera-errors");
  const std::string badTags = dir + "/bad.tags";
  std::ofstream(badTags) << "crease 0 1 inf\ncrease 0 6 2\n";
  std::vector<Case> cases = {
      {"refine " + cube() + " --level 2", 2, "tessera refine: --output is required"},
      {"refine " + cube() + " -o " + dir + "/x.obj", 2, "tessera refine: --level is required"},
      {"refine " + cube() + " --level two -o " + dir + "/x.obj", 2,
       "--level: expects a whole number from 0 to 1000, got 'two'"},
      {"refine " + cube() + " --level=-1 -o " + dir + "/x.obj", 2, "--level: expects a whole number"},
      {"refine " + cube() + " --level 1 --bogus -o " + dir + "/x.obj", 2, "not expected: --bogus"},
      {"refine " + cube() + " --level 1 --crease-method cubic -o " + dir + "/x.obj", 2,
       "--crease-method: expects uniform or chaikin, got 'cubic'"},
      {"refine " + cube() + " --level 1 --boundary none -o " + dir + "/x.obj", 2,
       "--boundary: expects edge-only or edge-and-corner, got 'none'"},
      {"refine " + dir + "/missing.obj --level 1 -o " + dir + "/x.obj", 1, "missing.obj"},
      {"refine " + cube() + " --level 1 -o " + dir + "/x.3ds", 1, "x.3ds"},
      {"refine " + cube() + " --level 1 --draco -o " + dir + "/x.obj", 1, "x.obj"},
      {"refine " + cube() + " --level 40 -o " + dir + "/x.obj", 1, "would exceed"},
      {"refine " + cube() + " --tags " + badTags + " --level 1 -o " + dir + "/x.obj", 1, "bad.tags:2"},
      {"info " + cube() + " " + cube(), 2, "not expected: " + cube()},
      {"info", 2, "tessera info: IN is required"},
      {"doc frobnicate x", 2, "unknown command 'frobnicate'"},
      {"doc", 2, "tessera doc: A subcommand is required"},
      {"doc export x.tsd --adaptive --level 2 -o " + dir + "/a.glb", 2, "--level excludes --adaptive"},
      {"doc export x.tsd --base-level 2 -o " + dir + "/a.glb", 2, "--base-level requires --adaptive"},
      {"remote --port 70000 list", 2, "--port: Value 70000 not in range"},
      {"remote grant 1 superuser TOKEN", 2, "ROLE: expects viewer, editor or admin, got 'superuser'"},
  };
  for (const auto& c : cases) {
    CliRun r = runCli(c.args);
    EXPECT_FALSE(r.signalled) << c.args;
    EXPECT_EQ(r.exitCode, c.exitCode) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\nstderr: " << r.err;
  }
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

TEST(CliDoc, NewEditInfoExport) {
  const std::string dir = testing::makeTempDir("tessera-doc-cli");
  const std::string doc = dir + "/cube.tsd";
  CliRun made = runCli("doc new " + cube() + " --tags " + cubeTags() + " --max-level 4 -o " + doc);
  ASSERT_EQ(made.exitCode, 0) << made.err;
  const std::string script = dir + "/edits.txt";
  std::ofstream(script) << "# a session\nmove v1:20 to 0.5 0.5 1.3\noffset v3:200 v3:201 by 0 0 0.05\n"
                           "crease e2:30 inf\ncorner v2:5 inf\nundo 4\n";
  CliRun edited = runCli("doc edit " + doc + " --script " + script);
  ASSERT_EQ(edited.exitCode, 0) << edited.err;
  EXPECT_NE(edited.out.find("applied 5 commands; 4 edits"), std::string::npos) << edited.out;
  CliRun info = runCli("doc info " + doc);
  ASSERT_EQ(info.exitCode, 0) << info.err;
  EXPECT_NE(info.out.find("edits           4 (3 active, 1 undone)"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("edit2    move   v3:200 v3:201"), std::string::npos) << info.out;
  // Infinite sharpness reads as what it is (it is stored as the sentinel 10).
  EXPECT_NE(info.out.find("edit3    crease e2:30 inf\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("edit4    corner (undone) v2:5 inf\n"), std::string::npos) << info.out;
  EXPECT_EQ(info.out.find(" 10\n"), std::string::npos) << info.out;
  for (const char* ext : {".obj", ".glb"}) {
    CliRun exported = runCli("doc export " + doc + " --level 3 --limit -o " + dir + "/out" + ext);
    ASSERT_EQ(exported.exitCode, 0) << exported.err;
    EXPECT_TRUE(std::filesystem::exists(dir + "/out" + ext));
  }
}

// The i-th "v x y z" line of an OBJ file.
Vec3 objVertex(const std::string& path, size_t index) {
  std::istringstream in(readAll(path));
  std::string line;
  size_t seen = 0;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) != 0) continue;
    if (seen++ == index) {
      std::istringstream xyz(line.substr(2));
      Vec3 p;
      xyz >> p[0] >> p[1] >> p[2];
      return p;
    }
  }
  ADD_FAILURE() << path << " has no vertex " << index;
  return Vec3(0, 0, 0);
}

// Interpolating vertices (docs/INTERPOLATION.md) from the command line: after
// `interpolate`, the limit surface (exported at level 4, vertex order following
// the numbering) passes through the vertex's level-1 control point (the level-1 control export).
TEST(CliDoc, InterpolateMakesTheLimitPassThroughTheControlPoint) {
  const std::string dir = testing::makeTempDir("tessera-doc-interp");
  const std::string doc = dir + "/cube.tsd";
  ASSERT_EQ(runCli("doc new " + cube() + " --max-level 4 -o " + doc).exitCode, 0);
  std::ofstream(dir + "/plain.txt") << "offset v1:3 by 0.1 0.2 -0.1\n";
  ASSERT_EQ(runCli("doc edit " + doc + " --script " + dir + "/plain.txt").exitCode, 0);
  ASSERT_EQ(runCli("doc export " + doc + " --level 1 -o " + dir + "/control.obj").exitCode, 0);
  ASSERT_EQ(runCli("doc export " + doc + " --level 4 --limit -o " + dir + "/before.obj").exitCode, 0);
  const Vec3 control = objVertex(dir + "/control.obj", 3);
  const double before = (objVertex(dir + "/before.obj", 3) - control).norm();
  EXPECT_GT(before, 1e-3) << "plain Loop does not interpolate";
  std::ofstream(dir + "/tag.txt") << "interpolate v1:3 2.5\n";
  CliRun tagged = runCli("doc edit " + doc + " --script " + dir + "/tag.txt");
  ASSERT_EQ(tagged.exitCode, 0) << tagged.err;
  ASSERT_EQ(runCli("doc export " + doc + " --level 4 --limit -o " + dir + "/after.obj").exitCode, 0);
  // OBJ numbers are written as shortest round-trip text: exact doubles.
  EXPECT_LE((objVertex(dir + "/after.obj", 3) - control).norm(), 1e-12);
  CliRun info = runCli("doc info " + doc);
  EXPECT_NE(info.out.find("edit2    interp v1:3 tension 2.5\n"), std::string::npos) << info.out;
  std::ofstream(dir + "/off.txt") << "interpolate v1:3 off\n";
  ASSERT_EQ(runCli("doc edit " + doc + " --script " + dir + "/off.txt").exitCode, 0);
  ASSERT_EQ(runCli("doc export " + doc + " --level 4 --limit -o " + dir + "/off.obj").exitCode, 0);
  EXPECT_EQ(readAll(dir + "/off.obj"), readAll(dir + "/before.obj"));
}

TEST(CliDoc, ABadScriptLeavesTheDocumentUntouched) {
  const std::string dir = testing::makeTempDir("tessera-doc-bad");
  const std::string doc = dir + "/cube.tsd";
  ASSERT_EQ(runCli("doc new " + cube() + " -o " + doc).exitCode, 0);
  const std::string before = readAll(doc);
  struct Case {
    std::string script;
    std::string message;
  };
  std::vector<Case> cases = {
      {"offset v1:3 by 0 0 1\nmove v9:1 to 1 2 3\n", "bad.txt:2: v9:1: level 9 is above the maximum level 6"},
      {"offset v1:3 by 0 0 nan\n", "bad.txt:1: bad number 'nan'"},
      {"crease e1:4 -2\n", "bad.txt:1: e1:4: sharpness must be >= 0"},
      {"undo 7\n", "bad.txt:1: edit7: no such edit"},
      {"twist v1:1\n", "bad.txt:1: unknown command 'twist'"},
      {"move v1:1 v1:1000000 to 0 0 0\n", "bad.txt:1: v1:1000000: level 1 has"},
      {"interpolate v1:3 0\n", "bad.txt:1: v1:3: tension must be in [0.001, 1000]"},
      {"interpolate v6:3\n", "bad.txt:1: v6:3: an interpolating vertex shapes the next level"},
      {"interpolate v1:3 off 2\n", "bad.txt:1: nothing may follow 'off'"},
      {"interpolate v1:3 1 tangent 1 0\n", "bad.txt:1: expected 'tangent X Y Z' after the tension"},
      {"interpolate v1:3 1 tangent 1 0 0\n",
       "bad.txt:1: v1:3: a tangent applies only to boundary and crease"},
  };
  for (const auto& c : cases) {
    std::ofstream(dir + "/bad.txt") << c.script;
    CliRun r = runCli("doc edit " + doc + " --script " + dir + "/bad.txt");
    EXPECT_EQ(r.exitCode, 1) << c.script;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_EQ(readAll(doc), before) << c.script;
  }
  std::ofstream(dir + "/junk.tsd") << "not a document";
  CliRun junk = runCli("doc info " + dir + "/junk.tsd");
  EXPECT_EQ(junk.exitCode, 1);
  EXPECT_NE(junk.err.find("not a Tessera document"), std::string::npos) << junk.err;
  CliRun badProfile =
      runCli("doc export " + doc + " --adaptive --base-level 4 --max-level 2 -o " + dir + "/a.glb");
  EXPECT_EQ(badProfile.exitCode, 2);
  EXPECT_NE(badProfile.err.find("max level 2 is below the base level 4"), std::string::npos)
      << badProfile.err;
  EXPECT_EQ(readAll(doc), before);
  CliRun badAngle = runCli("doc export " + doc + " --adaptive --angle nan -o " + dir + "/a.glb");
  EXPECT_EQ(badAngle.exitCode, 2);
  EXPECT_NE(badAngle.err.find("angle threshold"), std::string::npos) << badAngle.err;
}

// The adaptive export writes a crack-free tessellation that reads back with
// the triangle count it reported, fewer than the uniform level it reaches.
TEST(CliDoc, ExportsTheAdaptiveTessellation) {
  const std::string dir = testing::makeTempDir("tessera-doc-adaptive");
  const std::string doc = dir + "/cube.tsd";
  ASSERT_EQ(runCli("doc new " + cube() + " --tags " + cubeTags() + " -o " + doc).exitCode, 0);
  std::ofstream(dir + "/edit.txt") << "offset v4:3 by 0 0 0.05\n";
  ASSERT_EQ(runCli("doc edit " + doc + " --script " + dir + "/edit.txt").exitCode, 0);
  CliRun r = runCli("doc export " + doc + " --adaptive --base-level 1 --max-level 4 --angle 20 -o " + dir +
                    "/a.ply");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // The profile for people: no "angle20.000000" cache key.
  EXPECT_NE(r.out.find("(adaptive: base level 1, max level 4, angle 20\u00b0"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(".000000"), std::string::npos) << r.out;
  CliRun info = runCli("info " + dir + "/a.ply");
  ASSERT_EQ(info.exitCode, 0) << info.err;
  const size_t at = r.out.find(" triangles in ");
  ASSERT_NE(at, std::string::npos);
  const std::string count = r.out.substr(r.out.rfind(' ', at - 1) + 1, at - r.out.rfind(' ', at - 1) - 1);
  EXPECT_NE(info.out.find(count), std::string::npos) << info.out;
  EXPECT_LT(std::stoll(count), 12 * 256);
}

// `doc view` prints what a camera would be sent, by level; a near camera
// gets finer tiles than a far one; bad views are refused by name.
TEST(CliDoc, ViewPrintsTheTilesACameraNeeds) {
  const std::string dir = testing::makeTempDir("tessera-doc-view");
  const std::string doc = dir + "/cube.tsd";
  ASSERT_EQ(runCli("doc new " + cube() + " --tags " + cubeTags() + " --max-level 5 -o " + doc).exitCode, 0);
  CliRun far = runCli("doc view " + doc + " --eye 0 0 40 --target 0 0 0 --size 390x844");
  ASSERT_EQ(far.exitCode, 0) << far.err;
  EXPECT_NE(far.out.find("view 390x844 px, tolerance 1 px;"), std::string::npos) << far.out;
  EXPECT_NE(far.out.find("level  tiles (hidden)"), std::string::npos) << far.out;
  // The cube is small: its first picture is its level-0 tiles. Fandisk's
  // 12,946 level-0 triangles get the surface's preview (docs/VIEWS.md).
  EXPECT_NE(far.out.find("first picture: the level-0 tiles, 12 triangles"), std::string::npos) << far.out;
  const std::string fandisk = dir + "/fandisk.tsd";
  ASSERT_EQ(
      runCli("doc new " + testing::cgalMeshPath("fandisk.off") + " --max-level 2 -o " + fandisk).exitCode, 0);
  CliRun large = runCli("doc view " + fandisk + " --eye 0 0 3 --target 0 0 0");
  ASSERT_EQ(large.exitCode, 0) << large.err;
  EXPECT_NE(large.out.find("first picture: the surface's preview, 2,048 triangles"), std::string::npos)
      << large.out;
  EXPECT_NE(large.out.find("(the level-0 tiles: 12,946,"), std::string::npos) << large.out;
  CliRun near = runCli("doc view " + doc + " --eye 0 0 1.6 --target 0 0 0 --size 1920x1080 --tolerance 0.5");
  ASSERT_EQ(near.exitCode, 0) << near.err;
  auto finest = [](const std::string& out) {
    const size_t at = out.find("the whole document at level ");
    return at == std::string::npos ? -1 : std::stoi(out.substr(at + 28));
  };
  EXPECT_GT(finest(near.out), finest(far.out)) << far.out << near.out;
  for (const std::string& bad : {std::string("--size 0x844"), std::string("--tolerance 0"),
                                 std::string("--tolerance 1e9"), std::string("--size phone")}) {
    CliRun r = runCli("doc view " + doc + " --eye 0 0 4 --target 0 0 0 " + bad);
    EXPECT_EQ(r.exitCode, 2) << bad;
    EXPECT_TRUE(r.err.find("viewport") != std::string::npos || r.err.find("tolerance") != std::string::npos ||
                r.err.find("--size") != std::string::npos)
        << bad << ": " << r.err;
  }
  CliRun same = runCli("doc view " + doc + " --eye 0 0 4 --target 0 0 4");
  EXPECT_EQ(same.exitCode, 2);
  EXPECT_NE(same.err.find("forward is zero"), std::string::npos) << same.err;
}

}  // namespace
}  // namespace tessera

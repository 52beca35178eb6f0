// The real `tessera` binary, run as a user would: exit codes, outputs and
// error messages (never a signal).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/io/mesh_import.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

struct CliRun {
  int exitCode = -1;
  bool signalled = false;
  std::string out, err;
};

std::string readAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

CliRun runCli(const std::string& args) {
  static const std::string dir = testing::makeTempDir("tessera-cli");
  const std::string out = dir + "/stdout", err = dir + "/stderr";
  const std::string command = std::string(TESSERA_CLI_PATH) + " " + args + " >" + out + " 2>" + err;
  int status = std::system(command.c_str());
  CliRun run;
  run.signalled = WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) > 128);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = readAll(out);
  run.err = readAll(err);
  return run;
}

std::string cube() { return testing::sourceTestDataPath("cube.obj"); }
std::string cubeTags() { return testing::sourceTestDataPath("cube.tags"); }

TEST(Cli, HelpForEveryCommand) {
  for (const char* args : {"--help", "info --help", "refine --help"}) {
    CliRun r = runCli(args);
    EXPECT_EQ(r.exitCode, 0) << args;
    EXPECT_NE(r.out.find("usage: tessera"), std::string::npos) << args;
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
      {"refine " + cube() + " --level 2", 2, "-o OUT is required"},
      {"refine " + cube() + " -o " + dir + "/x.obj", 2, "--level is required"},
      {"refine " + cube() + " --level two -o " + dir + "/x.obj", 2, "--level expects a whole number"},
      {"refine " + cube() + " --level 1 --bogus -o " + dir + "/x.obj", 2, "unknown option --bogus"},
      {"refine " + cube() + " --level 1 --crease-method cubic -o " + dir + "/x.obj", 2, "uniform or chaikin"},
      {"refine " + dir + "/missing.obj --level 1 -o " + dir + "/x.obj", 1, "missing.obj"},
      {"refine " + cube() + " --level 1 -o " + dir + "/x.stl", 1, "x.stl"},
      {"refine " + cube() + " --level 1 --draco -o " + dir + "/x.obj", 1, "x.obj"},
      {"refine " + cube() + " --level 40 -o " + dir + "/x.obj", 1, "would exceed"},
      {"refine " + cube() + " --tags " + badTags + " --level 1 -o " + dir + "/x.obj", 1, "bad.tags:2"},
      {"info " + cube() + " " + cube(), 2, "expected one input mesh"},
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

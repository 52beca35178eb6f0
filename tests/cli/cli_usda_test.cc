// The real `tessera` binary on .usda files (docs/FORMATS.md "USD"): a cage
// written by `refine` or `doc export` and refined again by Tessera gives the
// points the command gives at the finer level directly; the file's
// subdivisionScheme chooses where --scheme does not and a contradiction is
// refused; --usd-prim picks a Mesh prim; a limit surface is no cage.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "cli/cli_run.h"
#include "core/io/mesh_import.h"
#include "core/util/file_io.h"

namespace tessera {
namespace {

std::string write(const std::string& dir, const std::string& name, const std::string& text) {
  std::ofstream(dir + "/" + name, std::ios::binary) << text;
  return dir + "/" + name;
}

// The points of a mesh file.
std::vector<Vec3> pointsOf(const std::string& path) {
  auto text = readFile(path);
  EXPECT_TRUE(text.isOk());
  const std::string ext = std::filesystem::path(path).extension().string();
  auto soup = importPolygonSoup(*text, ext, path);
  EXPECT_TRUE(soup.isOk()) << soup.status().toString();
  return soup.isOk() ? soup->points : std::vector<Vec3>{};
}

// The cage's numbering of the finer level is its own, so the points are
// compared as sets: each of `a`'s is a different one of `b`'s, within 1e-12.
void expectSamePoints(const std::string& a, const std::string& b) {
  const auto pa = pointsOf(a), pb = pointsOf(b);
  ASSERT_EQ(pa.size(), pb.size());
  std::set<size_t> matched;
  double worst = 0;
  for (const Vec3& p : pa) {
    size_t best = 0;
    double distance = HUGE_VAL;
    for (size_t k = 0; k < pb.size(); ++k)
      if ((pb[k] - p).norm() < distance) distance = (pb[k] - p).norm(), best = k;
    worst = std::max(worst, distance);
    matched.insert(best);
  }
  EXPECT_LE(worst, 1e-12) << a << " vs " << b;
  EXPECT_EQ(matched.size(), pa.size());
}

const std::string kQuads =
    "#usda 1.0\ndef Xform \"World\" {\n"
    "  def Mesh \"Box\" {\n"
    "    int[] faceVertexCounts = [4, 4, 4, 4, 4, 4]\n"
    "    int[] faceVertexIndices = [0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7]\n"
    "    point3f[] points = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1), (-1, -1, 1), (1, -1, 1), "
    "(1, 1, 1), (-1, 1, 1.5)]\n"
    "    int[] creaseIndices = [4, 5, 6]\n    int[] creaseLengths = [3]\n"
    "    float[] creaseSharpnesses = [2.5]\n"
    "    int[] cornerIndices = [0]\n    float[] cornerSharpnesses = [10]\n"
    "  }\n"
    "  def Mesh \"Other\" {\n"
    "    uniform token subdivisionScheme = \"loop\"\n"
    "    int[] faceVertexCounts = [3, 3, 3, 3]\n    int[] faceVertexIndices = [0, 2, 1, 0, 1, 3, 1, 2, 3, 2, "
    "0, 3]\n"
    "    point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]\n"
    "  }\n}\n";

TEST(CliUsda, ARefinedCageRefinesToTheFinerLevel) {
  const std::string dir = testing::makeTempDir("cli-usda");
  const std::string in = write(dir, "box.usda", kQuads);
  // The file's Box is catmullClark by USD's fallback: refine takes it.
  CliRun run = runCli("refine " + in + " --usd-prim Box --level 1 -o " + dir + "/cage1.usda");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  run = runCli("refine " + dir + "/cage1.usda --level 1 -o " + dir + "/from_cage.obj");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  run = runCli("refine " + in + " --usd-prim /World/Box --level 2 -o " + dir + "/direct.obj");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  expectSamePoints(dir + "/from_cage.obj", dir + "/direct.obj");

  // Loop: the tetrahedron with the cube's tags, its level-1 cage refined once.
  const std::string cube = testing::sourceTestDataPath("cube.obj");
  const std::string tags = testing::sourceTestDataPath("cube.tags");
  run = runCli("refine " + cube + " --tags " + tags + " --level 1 -o " + dir + "/loop1.usda");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(readAll(dir + "/loop1.usda").find("uniform token subdivisionScheme = \"loop\""),
            std::string::npos);
  run = runCli("refine " + dir + "/loop1.usda --level 1 -o " + dir + "/loop_from_cage.obj");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  run = runCli("refine " + cube + " --tags " + tags + " --level 2 -o " + dir + "/loop_direct.obj");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  expectSamePoints(dir + "/loop_from_cage.obj", dir + "/loop_direct.obj");
  std::filesystem::remove_all(dir);
}

TEST(CliUsda, DocumentsTakeTheFilesSchemeAndExportTheirCage) {
  const std::string dir = testing::makeTempDir("cli-usda-doc");
  const std::string in = write(dir, "box.usda", kQuads);
  CliRun run = runCli("doc new " + in + " -o " + dir + "/box.tdoc");
  ASSERT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("2 Mesh prims (/World/Box, /World/Other): name one (--usd-prim PATH)"),
            std::string::npos)
      << run.err;
  run = runCli("doc new " + in + " --usd-prim Other -o " + dir + "/tetra.tdoc");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("loop"), std::string::npos) << run.out;
  run = runCli("doc new " + in + " --usd-prim Other --scheme catmull-clark -o " + dir + "/t2.tdoc");
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("--scheme catmull-clark: " + in +
                         " says loop (subdivisionScheme); give the same, or none"),
            std::string::npos)
      << run.err;
  run = runCli("doc new " + in + " --usd-prim Box --max-level 3 -o " + dir + "/box.tdoc");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("catmull-clark"), std::string::npos) << run.out;
  run = runCli("doc export " + dir + "/box.tdoc --level 1 -o " + dir + "/box1.usda");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::string cage = readAll(dir + "/box1.usda");
  EXPECT_NE(cage.find("uniform token subdivisionScheme = \"catmullClark\""), std::string::npos) << cage;
  EXPECT_NE(cage.find("float[] creaseSharpnesses = [1.5, 1.5, 1.5, 1.5]"), std::string::npos) << cage;
  run = runCli("doc export " + dir + "/box.tdoc --level 1 --limit -o " + dir + "/limit.usda");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::string limit = readAll(dir + "/limit.usda");
  EXPECT_NE(limit.find("uniform token subdivisionScheme = \"none\""), std::string::npos);
  EXPECT_NE(limit.find("interpolation = \"vertex\""), std::string::npos);
  EXPECT_EQ(limit.find("crease"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tessera

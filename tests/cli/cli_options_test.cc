// The command line's conventions: --version, --opt=value,
// per-subcommand help, an output that would overwrite the input refused,
// numbers for people, and Draco-compressed GLB input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli/cli_run.h"
#include "client/cli/human_format.h"
#include "core/io/mesh_import.h"
#include "core/mesh/surface_mesh.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

std::string cube() {
  return testing::sourceTestDataPath("cube.obj");
}

TEST(CliOptions, VersionAndEqualsForm) {
  CliRun version = runCli("--version");
  EXPECT_EQ(version.exitCode, 0);
  EXPECT_EQ(version.out, "tessera 0.1.0\n");
  const std::string dir = testing::makeTempDir("tessera-equals");
  CliRun equals =
      runCli("refine " + cube() + " --level=2 --output=" + dir + "/x.obj --crease-method=chaikin");
  ASSERT_EQ(equals.exitCode, 0) << equals.err;
  EXPECT_NE(equals.out.find("98 vertices, 192 triangles (level 2)"), std::string::npos) << equals.out;
  CliRun spaced = runCli("refine " + cube() + " --level 2 -o " + dir + "/y.obj");
  EXPECT_EQ(readAll(dir + "/x.obj"), readAll(dir + "/y.obj"));
}

// `tessera doc new --help` is doc new's help alone, not the whole of doc.
TEST(CliOptions, HelpOfOneSubcommandOnly) {
  CliRun r = runCli("doc new --help");
  ASSERT_EQ(r.exitCode, 0);
  EXPECT_NE(r.out.find("Usage: tessera doc new [OPTIONS] IN"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--triangulate"), std::string::npos) << r.out;
  for (const char* other : {"--script", "--adaptive", "--level ", "export", "remote"}) {
    EXPECT_EQ(r.out.find(other), std::string::npos) << other << " in\n" << r.out;
  }
  CliRun edit = runCli("remote edit --help");
  ASSERT_EQ(edit.exitCode, 0);
  EXPECT_NE(edit.out.find("Usage: tessera remote edit"), std::string::npos) << edit.out;
  EXPECT_EQ(edit.out.find("--doc-name"), std::string::npos) << edit.out;  // remote create's
}

// Every command that takes -o refuses the input itself as the output, by any
// path to it, and leaves the input as it was.
TEST(CliOptions, OutputOverTheInputIsRefused) {
  const std::string dir = testing::makeTempDir("tessera-same");
  fs::copy_file(cube(), dir + "/cube.obj");
  const std::string original = readAll(dir + "/cube.obj");
  ASSERT_EQ(runCli("doc new " + cube() + " -o " + dir + "/cube.tsd").exitCode, 0);
  const std::string document = readAll(dir + "/cube.tsd");
  fs::create_directory(dir + "/sub");
  const std::vector<std::string> commands = {
      "refine " + dir + "/cube.obj --level 1 -o " + dir + "/cube.obj",
      "refine " + dir + "/cube.obj --level 1 -o " + dir + "/sub/../cube.obj",
      "doc new " + dir + "/cube.obj -o " + dir + "/./cube.obj",
      "doc export " + dir + "/cube.tsd --level 1 -o " + dir + "/cube.tsd",
      "doc export " + dir + "/cube.tsd --adaptive -o " + dir + "/sub/../cube.tsd",
  };
  for (const std::string& args : commands) {
    CliRun r = runCli(args);
    EXPECT_EQ(r.exitCode, 2) << args;
    EXPECT_NE(r.err.find("is the input"), std::string::npos) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("would destroy the input"), std::string::npos) << r.err;
  }
  EXPECT_EQ(readAll(dir + "/cube.obj"), original);
  EXPECT_EQ(readAll(dir + "/cube.tsd"), document);
  // A symbolic link to the input is the input too.
  fs::create_symlink(dir + "/cube.obj", dir + "/link.obj");
  CliRun link = runCli("refine " + dir + "/cube.obj --level 1 -o " + dir + "/link.obj");
  EXPECT_EQ(link.exitCode, 2) << link.err;
  EXPECT_EQ(readAll(dir + "/cube.obj"), original);
}

// Counts for people: thousands separators, never an exponent.
TEST(CliOptions, CountsPrintWithThousandsSeparators) {
  const std::string dir = testing::makeTempDir("tessera-counts");
  CliRun r = runCli("refine " + cube() + " --level 5 -o " + dir + "/fine.ply");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("6,146 vertices, 12,288 triangles (level 5)"), std::string::npos) << r.out;
  CliRun info = runCli("info " + dir + "/fine.ply");
  ASSERT_EQ(info.exitCode, 0) << info.err;
  EXPECT_NE(info.out.find("faces           12,288\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("edges           18,432\n"), std::string::npos) << info.out;
}

TEST(HumanFormat, NumbersForPeople) {
  using namespace cli;
  EXPECT_EQ(formatCount(0), "0");
  EXPECT_EQ(formatCount(999), "999");
  EXPECT_EQ(formatCount(1000), "1,000");
  EXPECT_EQ(formatCount(5042010), "5,042,010");
  EXPECT_EQ(formatBytes(512), "512 B");
  EXPECT_EQ(formatBytes(5042010), "4.81 MiB");
  EXPECT_EQ(formatBytes(3.0 * 1024 * 1024 * 1024), "3.00 GiB");
  EXPECT_EQ(formatDecimal(12345.678, 2), "12,345.68");
  EXPECT_EQ(formatDecimal(-1234.5, 1), "-1,234.5");
  EXPECT_EQ(formatSharpness(10.0), "inf");
  EXPECT_EQ(formatSharpness(2.5), "2.5");
  EXPECT_EQ(formatSharpness(0), "0");
  EXPECT_EQ(formatDuration(12.34), "12.3 s");
  EXPECT_EQ(formatDuration(245), "4 min 05 s");
  EXPECT_EQ(formatDuration(3 * 3600 + 12 * 60), "3 h 12 min");
  EXPECT_EQ(formatStat("bytes_sent", 5042010), "4.81 MiB");
  EXPECT_EQ(formatStat("bytes_per_second", 2048), "2.00 KiB/s");
  EXPECT_EQ(formatStat("edits", 5042010), "5,042,010");
  EXPECT_EQ(formatStat("edits_per_second", 0.04), "0.04/s");
  EXPECT_EQ(formatStat("edit_to_durable_ms", 1.5), "1.500 ms");
  EXPECT_EQ(formatStat("uptime_seconds", 245), "4 min 05 s");
  EXPECT_EQ(formatStat("store_average_batch", 2.5), "2.50");
}

// A Draco-compressed GLB (as `refine --draco` writes it) reads back as the
// same mesh as the plain GLB: same counts, positions within quantization.
TEST(CliOptions, DracoGlbIsInputLikeAnyGlb) {
  const std::string dir = testing::makeTempDir("tessera-draco-in");
  ASSERT_EQ(runCli("refine " + cube() + " --level 2 -o " + dir + "/plain.glb").exitCode, 0);
  CliRun made = runCli("refine " + cube() + " --level 2 --draco -o " + dir + "/draco.glb");
  ASSERT_EQ(made.exitCode, 0) << made.err;
  CliRun info = runCli("info " + dir + "/draco.glb");
  ASSERT_EQ(info.exitCode, 0) << info.err;
  EXPECT_NE(info.out.find("vertices        98\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("faces           192\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("genus           0\n"), std::string::npos) << info.out;
  auto plain = importMesh(dir + "/plain.glb");
  auto draco = importMesh(dir + "/draco.glb");
  ASSERT_TRUE(plain.isOk()) << plain.status().toString();
  ASSERT_TRUE(draco.isOk()) << draco.status().toString();
  ASSERT_EQ(draco->numVertices(), plain->numVertices());
  ASSERT_EQ(draco->numFaces(), plain->numFaces());
  // Draco may reorder points: compare the sorted positions. The default
  // quantization is 14 bits over a unit-sized box.
  auto sorted = [](const BaseMesh& m) {
    std::vector<std::array<double, 3>> p;
    for (const Vec3& v : m.positions()) p.push_back({v[0], v[1], v[2]});
    std::sort(p.begin(), p.end());
    return p;
  };
  const auto a = sorted(*plain), b = sorted(*draco);
  for (size_t i = 0; i < a.size(); ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[i][k], b[i][k], 1e-3) << i;
  }
  CliRun made2 = runCli("doc new " + dir + "/draco.glb -o " + dir + "/draco.tsd");
  EXPECT_EQ(made2.exitCode, 0) << made2.err;
  // A damaged payload is a clear error naming the file, never a crash.
  std::string bytes = readAll(dir + "/draco.glb");
  const size_t bin = bytes.rfind("BIN");
  ASSERT_NE(bin, std::string::npos);
  for (size_t i = bin + 8; i < bin + 40 && i < bytes.size(); ++i) bytes[i] = static_cast<char>(0xA5);
  std::ofstream(dir + "/broken.glb", std::ios::binary) << bytes;
  CliRun broken = runCli("info " + dir + "/broken.glb");
  EXPECT_EQ(broken.exitCode, 1);
  EXPECT_FALSE(broken.signalled);
  EXPECT_NE(broken.err.find("broken.glb"), std::string::npos) << broken.err;
  EXPECT_NE(broken.err.find("Draco"), std::string::npos) << broken.err;
}

// The same import from bytes names what the caller says, never a path.
TEST(ImportFromBytes, NamesTheCallersFileAndTouchesNoFile) {
  const std::string quads = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  auto refused = importMeshFromBytes(quads, "obj", "user/quad.obj");
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("user/quad.obj"), std::string::npos)
      << refused.status().message();
  auto fanned = importMeshFromBytes(quads, ".OBJ", "user/quad.obj", {.triangulate = true});
  ASSERT_TRUE(fanned.isOk()) << fanned.status().toString();
  EXPECT_EQ(fanned->numFaces(), 2);
  // Every format from memory reads as from its file.
  for (const char* name : {"good/tetra.obj", "good/tetra.off", "good/tetra_binary.ply",
                           "good/tetra_binary.stl", "good/tetra.glb"}) {
    const std::string path = testing::sourceTestDataPath(name);
    auto fromFile = importMesh(path);
    auto fromBytes = importMeshFromBytes(readAll(path), fs::path(path).extension().string(), name);
    ASSERT_TRUE(fromFile.isOk() && fromBytes.isOk()) << name << ": " << fromBytes.status().toString();
    EXPECT_EQ(fromBytes->positions(), fromFile->positions()) << name;
    EXPECT_EQ(fromBytes->numFaces(), fromFile->numFaces()) << name;
  }
  // A .gltf naming a buffer file beside it: refused, nothing read.
  const std::string gltf = R"({"asset":{"version":"2.0"},"buffers":[{"uri":"tetra.bin","byteLength":48}],)"
                           R"("bufferViews":[{"buffer":0,"byteLength":48}],)"
                           R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"}],)"
                           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}]})";
  auto external = importMeshFromBytes(gltf, ".gltf", "scene.gltf");
  ASSERT_FALSE(external.isOk());
  EXPECT_NE(external.status().message().find("scene.gltf"), std::string::npos) << external.status().message();
  EXPECT_NE(external.status().message().find("tetra.bin"), std::string::npos) << external.status().message();
}

}  // namespace
}  // namespace tessera

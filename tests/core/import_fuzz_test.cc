// A bounded, deterministic mutation fuzzer over importMesh(): valid small
// files are mutated (byte flips, truncations, insertions, chunk duplication)
// with fixed seeds. Every result must be either a mesh or a non-empty error
// naming the file -- never a crash, hang or sanitizer report.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

#include <gtest/gtest.h>

#include "core/io/mesh_import.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

constexpr int kMutationsPerFormat = 300;

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string mutate(std::string data, std::mt19937& rng) {
  auto pick = [&](size_t n) { return n == 0 ? size_t{0} : static_cast<size_t>(rng() % n); };
  const int edits = 1 + static_cast<int>(rng() % 4);
  // Characters that matter to the text formats, to reach past the first check.
  static const std::string kInteresting = "0123456789-./ \n#eEfvnaiINF";
  for (int e = 0; e < edits; ++e) {
    switch (rng() % 6) {
      case 0:  // flip a bit
        if (!data.empty()) data[pick(data.size())] ^= static_cast<char>(1u << (rng() % 8));
        break;
      case 1:  // truncate
        data.resize(pick(data.size() + 1));
        break;
      case 2:  // insert a random byte
        data.insert(data.begin() + static_cast<long>(pick(data.size() + 1)), static_cast<char>(rng() & 0xff));
        break;
      case 3:  // overwrite with an interesting character
        if (!data.empty()) data[pick(data.size())] = kInteresting[pick(kInteresting.size())];
        break;
      case 4: {  // duplicate a chunk
        const size_t at = pick(data.size() + 1);
        const size_t len = std::min<size_t>(pick(64) + 1, data.size() - std::min(at, data.size()));
        data.insert(at, data.substr(std::min(at, data.size()), len));
        break;
      }
      default:  // delete a chunk
        if (!data.empty()) {
          const size_t at = pick(data.size());
          data.erase(at, pick(16) + 1);
        }
        break;
    }
  }
  return data;
}

class ImportFuzz : public ::testing::TestWithParam<std::string> {};

TEST_P(ImportFuzz, MutatedFilesNeverCrash) {
  const std::string source = testing::sourceTestDataPath(GetParam());
  const std::string original = readBytes(source);
  ASSERT_FALSE(original.empty());
  const std::string dir = testing::makeTempDir("tessera-fuzz");
  const std::string path = dir + "/fuzz" + std::filesystem::path(source).extension().string();
  std::mt19937 rng(static_cast<unsigned>(std::hash<std::string>()(GetParam()) & 0xffffffffu));
  // TESSERA_FUZZ_DUMP=/tmp/prefix- writes every mutated input to disk.
  const char* dumpPrefix = std::getenv("TESSERA_FUZZ_DUMP");
  int accepted = 0;
  const auto start = std::chrono::steady_clock::now();
  // TESSERA_FUZZ_MUTATIONS / TESSERA_FUZZ_SEED widen a local run; CI uses the defaults.
  const int mutations = std::getenv("TESSERA_FUZZ_MUTATIONS")
                            ? std::atoi(std::getenv("TESSERA_FUZZ_MUTATIONS"))
                            : kMutationsPerFormat;
  if (std::getenv("TESSERA_FUZZ_SEED"))
    rng.seed(static_cast<unsigned>(std::atoi(std::getenv("TESSERA_FUZZ_SEED"))));
  for (int i = 0; i < mutations; ++i) {
    const std::string data = mutate(original, rng);
    if (dumpPrefix != nullptr) {  // debugging aid: keep each input, name the one that hangs
      std::ofstream(std::string(dumpPrefix) + std::to_string(i), std::ios::binary) << data;
      std::cerr << "mutation " << i << "\n";
    }
    {
      std::ofstream out(path, std::ios::binary | std::ios::trunc);
      out << data;
    }
    auto mesh = importMesh(path, ImportOptions{.triangulate = (i % 2) == 0});
    if (mesh.isOk()) {
      ++accepted;
      EXPECT_GT(mesh->numFaces(), 0);
    } else {
      EXPECT_FALSE(mesh.status().message().empty()) << "mutation " << i;
      EXPECT_NE(mesh.status().message().find("fuzz."), std::string::npos)
          << "mutation " << i << ": " << mesh.status().message();
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("accepted", accepted);
  EXPECT_LT(seconds, 10.0 * mutations / kMutationsPerFormat) << "fuzzing " << GetParam() << " took too long";
  std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(AllFormats, ImportFuzz,
                         ::testing::Values("good/tetra.obj", "good/tetra_vtvn.obj", "good/tetra.off",
                                           "good/tetra.ply", "good/tetra_binary.ply", "good/tetra.stl",
                                           "good/tetra_binary.stl", "good/tetra_split.gltf",
                                           "good/tetra.glb"));

}  // namespace
}  // namespace tessera

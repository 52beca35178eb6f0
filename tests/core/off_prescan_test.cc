// Regression for fuzz_import_off's out-of-memory (issue 13 §4): an OFF face
// with a 40-digit "colour" made OpenMesh's reader allocate vertex handles
// without bound (1.6 GB in one vector) for the face after it.
#include <gtest/gtest.h>

#include <string>

#include "core/io/format_prescan.h"
#include "core/io/mesh_import.h"

namespace tessera {
namespace {

const std::string kFuzzInput = "OFF\n4 4 0\n0 0 0\n1 0 80\n\n 0 2 1\n3 0  3\n3 1 2 0  60000000000000000000000000000000000000000000001\n3  0 1 3\n3 91 2 3\n3 0 3 2\n";

TEST(OffPrescan, FaceColoursNeverReachOpenMesh) {
  PrescanCounts counts;
  std::string normalised;
  ASSERT_TRUE(prescanOff(kFuzzInput, "oom.off", counts, normalised).isOk());
  EXPECT_EQ(normalised.find("600000"), std::string::npos) << normalised;
  EXPECT_NE(normalised.find("\n3 1 2 0\n"), std::string::npos) << normalised;
  // The import itself ends promptly with a mesh or a clear error.
  auto mesh = importMeshFromBytes(kFuzzInput, ".off", "oom.off");
  if (!mesh.isOk()) EXPECT_NE(mesh.status().message().find("oom.off"), std::string::npos) << mesh.status().message();
}

}  // namespace
}  // namespace tessera

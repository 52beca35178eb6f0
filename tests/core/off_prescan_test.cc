// Regression for fuzz_import_off's out-of-memory (docs/FUZZING.md): an OFF face
// with a 40-digit "colour" made OpenMesh's reader allocate vertex handles
// without bound (1.6 GB in one vector) for the face after it. OFF no longer
// goes through OpenMesh (text_mesh_readers.h); the input must still end
// promptly with the error its real fault deserves.
#include <gtest/gtest.h>

#include <string>

#include "core/io/mesh_import.h"

namespace tessera {
namespace {

const std::string kFuzzInput =
    "OFF\n4 4 0\n0 0 0\n1 0 80\n\n 0 2 1\n3 0  3\n3 1 2 0  "
    "60000000000000000000000000000000000000000000001\n3  0 1 3\n3 91 2 3\n3 0 3 2\n";

TEST(OffPrescan, FaceColoursNeverReachOpenMesh) {
  // The colour is a number and is ignored; face 2 names vertex 91 of 4.
  auto mesh = importMeshFromBytes(kFuzzInput, ".off", "oom.off");
  ASSERT_FALSE(mesh.isOk());
  EXPECT_NE(
      mesh.status().message().find("oom.off: face 2 (vertices 91, 2, 3): vertex index 91 is out of range"),
      std::string::npos)
      << mesh.status().message();
}

}  // namespace
}  // namespace tessera

// Procedural and on-disk meshes shared by the test suites.
#pragma once

#include <string>

#include "core/document/document.h"
#include "core/mesh/base_mesh.h"
#include "core/util/status.h"

namespace tessera::testing {

// Path of a real mesh extracted from Debian's libcgal-demo (e.g. "fandisk.off").
std::string cgalMeshPath(const std::string& name);
// Path of a file under tests/data.
std::string sourceTestDataPath(const std::string& relative);
// A fresh temporary directory for one test, in $TMPDIR (or /tmp), removed
// with everything in it when the test process exits normally, unless a test
// failed (failed_test_dirs.cc keeps them and names them) or
// TESSERA_KEEP_TEST_DIRS=1 asks to keep them all.
std::string makeTempDir(const std::string& prefix);
// Keeps every directory makeTempDir made so far, naming each on stderr with
// `why`.
void keepTempDirs(const std::string& why);
// Removes the directories makeTempDir made and nobody kept (it runs at exit).
void removeTempDirs();
// tests/data/cube.obj with the creases and corners of cube.tags.
Expected<BaseMesh> creasedCube();
// A document of tests/data/cube.obj, untagged, held to `maxLevel`.
Expected<Document> cubeDocument(int maxLevel);

}  // namespace tessera::testing

// The input mesh of a benchmark program: `--mesh PATH` (taken out of argv
// before Google Benchmark parses it), fandisk from the test data otherwise.
#pragma once

#include <cstdio>
#include <cstring>
#include <string>

#include "core/io/mesh_import.h"

namespace tessera::bench {

inline Expected<BaseMesh> benchMesh(int& argc, char** argv, const char* program) {
  std::string path = std::string(TESSERA_TESTDATA_DIR) + "/cgal/fandisk.off";
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--mesh") == 0) {
      path = argv[i + 1];
      for (int j = i; j + 2 <= argc; ++j) argv[j] = argv[j + 2];
      argc -= 2;
      break;
    }
  }
  auto mesh = importMesh(path);
  if (!mesh.isOk()) {
    std::fprintf(stderr, "%s: %s\n", program, mesh.status().toString().c_str());
  } else {
    std::printf("mesh %s: %d vertices, %d triangles\n", path.c_str(), mesh->numVertices(), mesh->numFaces());
  }
  return mesh;
}

}  // namespace tessera::bench

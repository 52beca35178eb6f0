// Writes the GLB files that ctest's gltf_validator_export hands to the Khronos
// glTF-Validator (tests/validator.cmake): a plain and a Draco-compressed
// export of a closed torus with normals, and the level-3 Loop limit surface
// of a creased cube, the path `tessera refine --limit` takes.
//
// Usage: write_sample_glbs OUT_DIR   (prints the paths it wrote)
#include <filesystem>
#include <iostream>

#include "core/io/mesh_export.h"
#include "core/loop/loop_refiner.h"
#include "tools/sample_surfaces.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " OUT_DIR\n";
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  const tessera::SurfaceMesh surface = tessera::testing::makeTorusSurface(100, 50);

  // A cube with an infinitely sharp rim, semi-sharp sides and a corner.
  tessera::BaseTopology cube;
  cube.numVertices = 8;
  cube.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                    {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  cube.creases = {{4, 5, tessera::kSharpnessInfinite},
                  {5, 6, tessera::kSharpnessInfinite},
                  {0, 4, 2.5f},
                  {1, 5, 2.5f},
                  {2, 6, 2.5f},
                  {3, 7, 2.5f}};
  cube.vertexSharpness = {0, 0, 0, 0, 0, 0, tessera::kSharpnessInfinite, 0};
  const std::vector<tessera::Vec3> cubePoints = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                                 {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  auto refiner = tessera::LoopRefiner::create(cube, {}, {.levels = 3});
  if (!refiner.isOk()) {
    std::cerr << refiner.status().toString() << "\n";
    return 1;
  }
  auto limit = refiner->limitSurface(refiner->refinePoints(cubePoints));
  if (!limit.isOk()) {
    std::cerr << limit.status().toString() << "\n";
    return 1;
  }

  tessera::ExportOptions draco;
  draco.draco = true;
  struct Output {
    std::filesystem::path path;
    const tessera::SurfaceMesh* surface;
    tessera::ExportOptions options;
  };
  const Output outputs[] = {
      {dir / "torus.glb", &surface, tessera::ExportOptions{}},
      {dir / "torus-draco.glb", &surface, draco},
      {dir / "cube-limit.glb", &limit.value(), tessera::ExportOptions{}},
      {dir / "cube-limit-draco.glb", &limit.value(), draco},
  };
  for (const auto& [path, mesh, options] : outputs) {
    const tessera::Status status = tessera::exportMesh(*mesh, path.string(), options);
    if (!status.isOk()) {
      std::cerr << status.toString() << "\n";
      return 1;
    }
    std::cout << path.string() << " (" << std::filesystem::file_size(path) << " bytes)\n";
  }
  return 0;
}

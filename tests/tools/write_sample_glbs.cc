// Writes the GLB files that ctest's gltf_validator_export hands to the Khronos
// glTF-Validator (tests/validator.cmake): one plain and one Draco-compressed
// export of a closed torus with normals.
//
// Usage: write_sample_glbs OUT_DIR   (prints the paths it wrote)
#include <filesystem>
#include <iostream>

#include "core/io/mesh_export.h"
#include "tools/sample_surfaces.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " OUT_DIR\n";
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  const tessera::SurfaceMesh surface = tessera::testing::makeTorusSurface(100, 50);

  tessera::ExportOptions draco;
  draco.draco = true;
  const std::pair<std::filesystem::path, tessera::ExportOptions> outputs[] = {
      {dir / "torus.glb", tessera::ExportOptions{}},
      {dir / "torus-draco.glb", draco},
  };
  for (const auto& [path, options] : outputs) {
    const tessera::Status status = tessera::exportMesh(surface, path.string(), options);
    if (!status.isOk()) {
      std::cerr << status.toString() << "\n";
      return 1;
    }
    std::cout << path.string() << " (" << std::filesystem::file_size(path) << " bytes)\n";
  }
  return 0;
}

// Export of a refined or limit surface to OBJ, PLY or glTF 2.0 GLB (tinygltf),
// optionally Draco-compressed via KHR_draco_mesh_compression (GLB only).
// The format follows the extension of the output path.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera {

struct SurfaceMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // empty, or one unit normal per position
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise
};

struct ExportOptions {
  bool draco = false;             // GLB only: KHR_draco_mesh_compression
  int dracoPositionBits = 16;     // quantization of positions
  int dracoNormalBits = 12;       // quantization of normals
  int dracoCompressionLevel = 7;  // 0 (fastest) .. 10 (smallest)
};

Status exportMesh(const SurfaceMesh& surface, const std::string& path, const ExportOptions& options = {});

}  // namespace tessera

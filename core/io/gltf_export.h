// glTF 2.0 binary (GLB) writing through tinygltf, plain or with
// KHR_draco_mesh_compression (internal to core/io; the public entry point is
// exportMesh in mesh_export.h).
//
// Input:  a SurfaceMesh already validated by exportMesh (non-empty, indices in
//         range, finite values, normals empty or one non-zero per position).
// Output: one GLB file holding a scene with one node, one mesh, one triangle
//         primitive; no material, so viewers use the glTF default material.
#pragma once

#include <string>

#include "core/io/mesh_export.h"
#include "core/util/status.h"

namespace tessera::io_detail {

Status writeGlb(const SurfaceMesh& surface, const std::string& path, const ExportOptions& options);

}  // namespace tessera::io_detail

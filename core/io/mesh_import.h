// Mesh import: OBJ, OFF, PLY, STL through OpenMesh IO, and glTF/GLB through
// tinygltf. The reader chosen follows the file extension; every error names
// the file. Readers produce a PolygonSoup that buildBaseMesh() validates.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/base_mesh.h"
#include "core/mesh/polygon_soup.h"
#include "core/util/status.h"

namespace tessera {

struct ImportOptions {
  bool triangulate = false;  // fan polygons instead of rejecting them
};

// Reads, validates and returns the base mesh. glTF input may carry feature
// tags in `extras` (see docs/FORMATS.md); they are applied to the mesh.
Expected<BaseMesh> importMesh(const std::string& path, const ImportOptions& options = {});

// The same import from bytes in memory, for meshes that arrive over the
// network (CreateDocument) and for fuzzing. `extension` chooses the reader
// (".obj" or "obj", any case); `displayName` names the input in every error
// ("cube.obj:12: ..."). Never touches the filesystem: a .gltf whose buffers
// are external files is refused (a GLB, or data: URIs, carry their own).
Expected<BaseMesh> importMeshFromBytes(std::string_view bytes, const std::string& extension,
                                       const std::string& displayName, const ImportOptions& options = {});

// Extensions importMesh() accepts, lower case with the dot: ".obj", ...
const std::vector<std::string>& supportedImportExtensions();

}  // namespace tessera

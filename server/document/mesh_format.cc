#include "server/document/mesh_format.h"

namespace tessera::server {

const char* meshExtensionOf(wire::MeshFormat format) {
  switch (format) {
    case wire::MESH_FORMAT_OBJ:
      return ".obj";
    case wire::MESH_FORMAT_OFF:
      return ".off";
    case wire::MESH_FORMAT_PLY:
      return ".ply";
    case wire::MESH_FORMAT_STL:
      return ".stl";
    case wire::MESH_FORMAT_GLB:
      return ".glb";
    case wire::MESH_FORMAT_USDA:
      return ".usda";
    default:
      return nullptr;
  }
}

}  // namespace tessera::server

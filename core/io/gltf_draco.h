// KHR_draco_mesh_compression on import (internal to core/io; used by
// gltf_import.cc). The exporter writes such GLBs (`--draco`), and Debian's
// tinygltf 2.7 is built without Draco: it refuses the file outright because
// a compressed primitive's indices accessor has no bufferView (the extension
// allows that). So:
//  1. dropDracoIndices() removes "indices" from every compressed primitive
//     in the JSON before tinygltf parses it (nothing else changes; the GLB's
//     binary chunk is kept byte for byte);
//  2. decodeDracoPrimitive() decodes the primitive's bufferView with Draco
//     into positions and triangles, which replace the accessors.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/util/status.h"

namespace tessera::io_detail {

inline constexpr const char* kDracoExtension = "KHR_draco_mesh_compression";

// `data`: a whole .glb or .gltf. Unchanged unless it uses the extension;
// errors name `name` (a malformed GLB container or JSON).
Expected<std::string> dropDracoIndices(const std::string& data, const std::string& name);

struct DracoPrimitive {
  std::vector<std::array<float, 3>> positions;  // in Draco's decoded point order
  std::vector<uint32_t> indices;                // three per triangle
};

// Decodes a compressed primitive. `positionId`: the Draco unique id of
// POSITION from the extension's "attributes". Errors name `where`.
Expected<DracoPrimitive> decodeDracoPrimitive(const unsigned char* data, size_t size, int positionId,
                                              const std::string& where);

}  // namespace tessera::io_detail

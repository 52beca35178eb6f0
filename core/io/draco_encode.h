// Draco encoding of a SurfaceMesh for KHR_draco_mesh_compression (internal to
// core/io; the public entry point is exportMesh in mesh_export.h).
//
// Input:  a validated SurfaceMesh (indices in range, finite values, normals
//         empty or one per position) and the Draco fields of ExportOptions.
// Output: the encoded bytes plus what the glTF accessors must declare.
//         Draco may reorder, split or merge points, and the extension spec
//         requires the accessors to "match the decompressed data", so every
//         count and bound below is measured on a decode of the bytes produced,
//         never on the input.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/io/mesh_export.h"
#include "core/util/status.h"

namespace tessera::io_detail {

struct DracoEncodedMesh {
  std::vector<std::uint8_t> bytes;
  int positionUniqueId = -1;           // Draco attribute unique id of POSITION
  int normalUniqueId = -1;             // of NORMAL, -1 when the surface has no normals
  std::size_t pointCount = 0;          // decoded vertex count (accessor count)
  std::size_t faceCount = 0;           // decoded triangle count
  std::array<float, 3> positionMin{};  // of the decoded, dequantized positions
  std::array<float, 3> positionMax{};
};

// Rejects quantization bits or a compression level outside what Draco accepts.
Status validateDracoOptions(const ExportOptions& options);

Expected<DracoEncodedMesh> encodeDraco(const SurfaceMesh& surface, const ExportOptions& options);

}  // namespace tessera::io_detail

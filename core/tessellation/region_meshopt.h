// The meshoptimizer side of the region codec (region_codec.h): a RegionMesh
// to and from the payload of a "TSRM" region, the second codec beside Draco
// (region_draco.h) for clients that decode with meshoptimizer (its npm
// decoder in the browser). Internal to core/tessellation; region_codec.cc
// writes and checks everything around the payload (header, frame,
// checksum), the same as for Draco.
//
// The payload (docs/REGION_ENCODING.md, "meshopt regions"), little-endian:
//   offset  size  field
//        0     4  vertex count V (at most 3 per triangle)
//        4     4  size n of the encoded vertex buffer
//        8     n  meshopt_encodeVertexBuffer of V vertices of S bytes:
//                   3 x u32  position as a lattice index of the grid, the
//                            value Draco's quantizer gives (so both codecs
//                            decode to the same float32 positions)
//                   2 x u16  normal, octahedral on normalBits (at most 16),
//                            each at most 2^normalBits - 2
//                   ids:     nothing (no ids), u64 packed VertexId, or
//                            2 x u16 lattice point (u, v) (region_lattice.h)
//                 S = 16, 24 or 20
//    8 + n   ...  meshopt_encodeIndexBuffer of 3 x triangles u32 indices
//
// The encoder orders triangles for the vertex cache and vertices by first
// use (meshopt_optimizeVertexCache, meshopt_optimizeVertexFetchRemap),
// moving every vertex's position, normal and id together, so a decoded
// vertex keeps its own id. The order is a function of the triangles over
// the vertices as given, so two encodings of one layout decode in the same
// order and adoptLayoutIds holds for this codec too.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/tessellation/quantization_grid.h"
#include "core/tessellation/region_codec.h"
#include "core/tessellation/region_draco.h"
#include "core/tessellation/region_lattice.h"
#include "core/util/status.h"

namespace tessera::region_detail {

// The octahedral normal takes two u16: grids with finer normals are refused
// by the meshopt codec (gridFor gives kDefaultNormalBits, 10).
inline constexpr int kMaxMeshoptNormalBits = 16;

// The payload of a mesh that passed encodeRegion's checks. `lattice` is set
// exactly when coding is kLattice. Errors: normal bits above
// kMaxMeshoptNormalBits (invalidArgument), a vertex outside the lattice's
// face (invalidMesh); both prefixed by `where`.
Expected<std::string> encodeMeshoptPayload(const RegionMesh& mesh, IdCoding coding,
                                           const RegionLattice* lattice, const QuantizationGrid& grid,
                                           const std::string& where);

// Decodes a payload of `triangles` triangles. `withIds`: it carries vertex
// ids (as lattice points when `lattice` is set). Checks the vertex count
// against the triangles and the payload size before anything is allocated,
// the codecs' version bytes, every lattice index inside the grid, every
// lattice point inside the face, every triangle index below V with three
// distinct corners, and every vertex used by some triangle (encodeRegion
// writes no other). Errors are parse errors naming `where`.
Expected<RegionMesh> decodeMeshoptPayload(std::string_view payload, const QuantizationGrid& grid,
                                          bool withIds, uint32_t triangles, const RegionLattice* lattice,
                                          const std::string& where);

}  // namespace tessera::region_detail

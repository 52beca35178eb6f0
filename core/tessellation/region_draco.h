// The Draco side of the region codec (region_codec.h): a RegionMesh to and
// from the Draco bitstream that forms a region's payload. Internal to
// core/tessellation; region_codec.cc writes and checks everything around the
// payload (header, frame, checksum).
//
// Encoding quantizes positions on the document's grid exactly as the header
// states it, normals octahedrally, and carries vertex ids as GENERIC
// attributes: eight bytes per id, or a lattice point of the region's root
// face (region_lattice.h). Decoding checks, before Draco allocates anything,
// that the counts at the start of the bitstream agree with the header's
// triangle count, then that Draco used the header's grid, and dequantizes
// positions with Draco's own float operations, so the result is
// bit-identical to a plain Draco decode (docs/REGION_ENCODING.md).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/tessellation/quantization_grid.h"
#include "core/tessellation/region_codec.h"
#include "core/tessellation/region_lattice.h"
#include "core/util/status.h"

namespace tessera::region_detail {

// How a payload carries vertex ids.
enum class IdCoding { kNone, kBytes, kLattice };

// Draco's compression levels as core/io counts them: 0 its fastest
// (sequential coding), 10 its smallest; Draco speed = 10 - level.
inline constexpr int kMaxCompressionLevel = 10;

// Draco's stream has no size field to check its counts against, so the
// decoder refuses more triangles than this per payload byte before Draco
// allocates for them. Typical regions take about 3 bytes per triangle; the
// most compressible input found, a planar regular grid on the lattice with
// every id equal (every prediction exact), reaches 283 triangles per byte at
// 522k triangles. encodeRegion applies the same bound, so whatever it
// produces decodes.
inline constexpr uint64_t kMaxTrianglesPerPayloadByte = 1024;

// The Draco bytes of a mesh that passed encodeRegion's checks. `lattice` is
// set exactly when coding is kLattice. Errors: a vertex outside the
// lattice's face (invalidMesh, without context), and Draco refusing an
// option or the mesh (internalError, prefixed by `where`).
Expected<std::string> encodeDracoPayload(const RegionMesh& mesh, IdCoding coding,
                                         const RegionLattice* lattice, const QuantizationGrid& grid,
                                         int compressionLevel, const std::string& where);

// Reads the counts Draco will allocate for, from the start of its bitstream
// 2.2, before Draco sees the bytes; every count must be consistent with the
// header's triangle count, which the input size bounds.
Status checkDracoCounts(std::string_view payload, uint32_t triangles, const std::string& where);

// Decodes a payload that passed checkDracoCounts. `withIds`: the payload
// carries vertex ids (as lattice points when `lattice` is set). Errors are
// parse errors naming `where`.
Expected<RegionMesh> decodeDracoPayload(std::string_view payload, const QuantizationGrid& grid, bool withIds,
                                        uint32_t triangles, const RegionLattice* lattice,
                                        const std::string& where);

}  // namespace tessera::region_detail

// Region codec: one region of a document's displayed surface to and from the
// self-describing bytes streamed to viewers after an edit
// (docs/REGION_ENCODING.md).
//
// Input:  a RegionHeader (region id, document version, LOD profile and the
//         document's quantization grid) and a RegionMesh: positions inside the
//         grid, unit normals and packed VertexIds, one per vertex, and
//         triangles using every vertex.
// Output: little-endian bytes, format version 2:
//           offset  size  field
//                0     4  magic "TSRG" (Draco payload) or "TSRM"
//                         (meshoptimizer payload, region_meshopt.h)
//                4     2  format version (2)
//                6     2  flags, at most one set: bit 0 = no vertex ids (a
//                         display-only profile; the Draco mesh has no
//                         GENERIC attribute); bit 1 = the layout's ids (the
//                         profile has ids but this payload leaves them out:
//                         the receiver holds the same layout and keeps its
//                         ids, adoptLayoutIds); bit 2 = lattice ids (a
//                         frame follows the header and GENERIC holds each
//                         vertex's lattice point (u, v) as 2 x uint8);
//                         bit 3 = the same on a quad's lattice
//                8     8  region id
//               16     8  document version
//               24     8  layout version: the document version since which
//                         the region's triangles and vertex ids are unchanged
//               32    25  LOD profile: baseLevel i32, maxLevel i32,
//                         angleThresholdDegrees f64, triangleBudget i64,
//                         fidelity u8
//               57    34  grid: origin 3 x f64, range f64, positionBits u8,
//                         normalBits u8
//               91     4  triangle count
//               95     4  Draco payload size n
//               99     k  with bit 2 or 3 only, the frame: root face level
//                         u8 and index, (bit 3) its first child, corner
//                         vertex indices x 3 (4), edge indices x 3 (4), edge
//                         directions u8, base counts x 3, V, E, F (x 4, and C),
//                         the numbers as LEB128 varints (k is 12 bytes for a
//                         cube; region_lattice.h)
//           99 (+k)   n  "TSRM": the meshopt payload (region_meshopt.h);
//                         "TSRG": Draco mesh (bitstream 2.2): POSITION quantized on
//                         the grid, NORMAL octahedral, GENERIC ids as 8 x
//                         uint8, least significant byte first (or lattice
//                         points, bits 2 and 3)
//              ... + n 4  CRC-32 (zlib) of every byte before it
//
// Why layouts: an edit moves vertices but rarely changes which triangles a
// region has over which control vertices, and the ids are a third of a
// region's bytes. Draco's Edgebreaker orders the decoded vertices by the
// connectivity alone (identity-mapped attributes have no seams, so no
// attribute value steers the traversal), so two encodings of the same
// triangles over the same vertex order decode in the same order: ids sent
// once per layout stay valid for every later payload of that layout.
//
// Why one grid per document: so that a vertex shared by two regions decodes
// to the same floats in both and the separately decoded regions leave no
// cracks (quantization_grid.h). The Draco payload is written and read by
// region_draco.h.
//
// Errors name the region, the element and the reason: invalidArgument for a
// bad header, grid or compression level, invalidMesh for a mesh that breaks
// the rules of encodeRegion; parseError for bytes that are
// truncated, corrupted, foreign or oversized; unsupported for a later format
// version. Neither function throws, and decodeRegion bounds every count by the
// input size before anything is allocated.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/tessellation/lod_profile.h"
#include "core/tessellation/quantization_grid.h"
#include "core/tessellation/region_lattice.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera {

struct RegionMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // unit, one per position
  std::vector<uint64_t>
      vertexIds;  // packed VertexId (ids.h) of the control vertex each vertex is the limit of
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise
};

// A region's payload codec (docs/REGION_ENCODING.md): the header, frame,
// grid, ids and checksum are the same; the magic tells them apart.
enum class RegionCodec : uint8_t { kDraco, kMeshopt };
inline constexpr int kRegionCodecCount = 2;
const char* regionCodecName(RegionCodec codec);  // "draco", "meshopt"

struct RegionHeader {
  uint64_t regionId = 0;
  uint64_t documentVersion = 0;
  uint64_t layoutVersion = 0;  // <= documentVersion: since when triangles and ids are unchanged
  LodProfile profile;
  QuantizationGrid grid;
  // With a profile that has ids: false leaves them out of the payload, for
  // receivers that hold this layout already (deltas after a move).
  bool idsInline = true;
  // With inline ids: the region's root face, so that the ids travel as
  // lattice points (region_lattice.h) when the profile's depth below the
  // face allows (at most kMaxLatticeDepth), as eight bytes otherwise.
  std::optional<RegionFrame> frame = std::nullopt;
  RegionCodec codec = RegionCodec::kDraco;

  friend bool operator==(const RegionHeader&, const RegionHeader&) = default;
};

inline constexpr uint16_t kRegionFormatVersion = 2;
inline constexpr size_t kRegionHeaderBytes = 99;  // everything before the Draco payload, but a frame
inline constexpr size_t kMaxRegionFrameBytes = 2 + 14 * 10;  // level, forward and (quads) 14 varints
inline constexpr size_t kRegionTrailerBytes = 4;             // the CRC-32
inline constexpr uint32_t kMaxRegionTriangles = 1u << 24;    // LoopRefiner's default face cap
inline constexpr size_t kMaxRegionBytes = size_t{1} << 28;
// Compression levels follow core/io: 0 is Draco's fastest (sequential
// coding), 10 its smallest; Draco speed = 10 - level. The default, chosen for
// latency in docs/REGION_ENCODING.md, is the fastest Edgebreaker setting with
// parallelogram prediction: as fast as levels 1-2 and 20% smaller, 3.4x
// smaller than level 0, within 7% of level 10's size at a third of its time.
// The meshopt codec has no levels: it checks and ignores the argument.
inline constexpr int kDefaultRegionCompressionLevel = 3;

// Encodes one region. The mesh must have at least one triangle, one normal
// and one id per position, finite values, unit normals, every position
// inside header.grid, triangle indices in range with three distinct
// corners, and no unused vertex (Draco's Edgebreaker drops unused vertices
// and triangles with a repeated corner, which would lose ids silently).
Expected<std::string> encodeRegion(const RegionHeader& header, const RegionMesh& mesh,
                                   int compressionLevel = kDefaultRegionCompressionLevel);

// Decodes what encodeRegion produced, either codec (header.codec says
// which). Draco may reorder vertices and split
// non-manifold ones, so the decoded mesh describes the same triangles over
// the same ids, not the same vertex numbering. Positions are dequantized
// exactly as a plain Draco decoder does (float32), normals renormalized.
// A payload without its layout's ids (header.idsInline false) decodes with
// no vertexIds; adoptLayoutIds completes it.
Expected<std::pair<RegionHeader, RegionMesh>> decodeRegion(std::string_view bytes);

// Gives `decoded` (a payload without inline ids) the ids of `held`, the
// receiver's decoded copy of the same region at layout `heldLayout`. Errors
// (the receiver must resync): another layout, or triangles that differ from
// the held ones -- the sign that the decoded order is not the held one.
Status adoptLayoutIds(const RegionHeader& header, RegionMesh& decoded, const RegionMesh& held,
                      uint64_t heldLayout);

}  // namespace tessera

// The surface hash of docs/PROTOCOL.md 6.5: one 64-bit number for the
// displayed surface of one LOD profile at one version, defined from what a
// client decodes (vertex ids, float32 positions, triangles) so that a client
// in any language can recompute it and compare it with the server's
// (Snapshot.surface_hash, Delta.surface_hash).
//
// Definition, in short: every triangle of every region contributes the
// FNV-1a 64 of its 60-byte canonical form (its three corners, each the
// packed vertex id, 0 without ids, and the float32 bits of x, y, z, rotated
// so that the lexicographically smallest rotation comes first); the surface
// hash is the sum of the contributions modulo 2^64.
//
// Why this shape:
//   - a sum is independent of the order of regions, triangles and vertices
//     (Draco chooses the decoded order) and of how the surface is split
//     into regions, and it is updated per region: the server keeps one sum
//     per region and changes only those a delta carries;
//   - positions are hashed as the float32 values a Draco decoder returns,
//     which every region shares bit for bit (one grid per document), so no
//     tolerance is needed;
//   - normals are left out: octahedral decoding and renormalization are
//     float operations that decoders do differently, and a region's normals
//     travel in the same payload as the positions and ids that are hashed.
#pragma once

#include <array>
#include <cstdint>
#include <map>

#include "core/tessellation/region_codec.h"

namespace tessera {

// One corner as the hash sees it: the packed VertexId (0 when the profile
// omits ids) and the decoded float32 position.
struct HashedCorner {
  uint64_t id = 0;
  std::array<float, 3> position{};
};

// FNV-1a 64 (offset basis 0xcbf29ce484222325, prime 0x100000001b3) of the
// triangle's canonical 60 bytes.
uint64_t triangleHash(const std::array<HashedCorner, 3>& corners);

// The sum of triangleHash over a decoded region (decodeRegion's positions
// are float32 values; its vertexIds may be empty: display-only).
uint64_t regionSurfaceHash(const RegionMesh& decoded);

// The same for a region before it is encoded: each position quantized on
// `grid` and dequantized exactly as Draco's encoder and decoder do
// (region_draco.cc), so the result equals regionSurfaceHash of the decoded
// payload. `withIds` false hashes every id as 0 (a display-only profile).
uint64_t regionSurfaceHashOnGrid(const RegionMesh& mesh, const QuantizationGrid& grid, bool withIds);

// The surface hash of decoded regions: the sum of their region hashes.
uint64_t surfaceHash(const std::map<uint64_t, RegionMesh>& decodedRegions);

}  // namespace tessera

// A document as one subscriber sees it (docs/PROTOCOL.md §6): the decoded regions of
// its LOD profile, kept current by snapshots and deltas, with version
// continuity checked -- a delta that does not start at the current version
// is a gap, after which the view waits for a resync snapshot.
#pragma once

#include <array>
#include <cstdint>
#include <map>

#include "core/mesh/surface_mesh.h"
#include "core/tessellation/region_codec.h"
#include "core/view/tile_assembly.h"
#include "protocol/tessera.pb.h"

namespace tessera::client {

class DocumentView {
 public:
  explicit DocumentView(uint64_t documentId) : documentId_(documentId) {}

  // A Snapshot part or a Delta of this document; other messages are ignored.
  // Errors: a version gap, a region that does not decode.
  Status apply(const wire::ServerMessage& message);

  bool ready() const { return ready_; }
  // After a gap the view waits for a snapshot: subscribe again (the server
  // answers with one) and keep applying.
  bool needsResync() const { return !ready_ && gaps_ > 0; }
  uint64_t version() const { return version_; }
  uint64_t documentId() const { return documentId_; }
  const std::map<uint64_t, RegionMesh>& regions() const { return regions_; }
  int64_t numTriangles() const;
  // Everything decoded, merged by vertex id and normal (for export and tests).
  SurfaceMesh surface() const;
  // A view-dependent subscription's tiles as they are shown (docs/VIEWS.md
  // "Assembling tiles"): each tile's positions with the cracks towards
  // coarser neighbours closed (core/view/tile_assembly.h), by region id.
  // Each tile's boundary is summarised once, when first asked after it
  // arrived, so a call costs the tiles' boundaries, not their triangles.
  // While the surface's preview is held, it alone, as it came (VIEWS.md
  // "The first picture").
  std::map<uint64_t, std::vector<Vec3>> closedTilePositions(int64_t* moved = nullptr) const;
  // The last delta applied said the view's tiles are all here
  // (Delta.view_complete); a snapshot starts a view's picture, not complete.
  bool viewComplete() const { return viewComplete_; }
  // The SetView the last delta's tiles follow (Delta.view_seq; 0: the Subscribe's).
  uint64_t viewSeq() const { return viewSeq_; }
  // The surface hash of docs/PROTOCOL.md 6.5 (core/tessellation/
  // surface_hash.h) of the regions held: equal for equal document states
  // and profiles, and comparable with the server's. Each region is hashed
  // once, when first asked after it arrived.
  uint64_t surfaceHash() const;
  // The server's surface hash for the version held (Snapshot or Delta
  // surface_hash), 0 if it sent none.
  uint64_t announcedSurfaceHash() const { return announced_; }
  // Ok when the server sent no hash or it equals surfaceHash(); otherwise
  // an error naming both: the view's assembly differs from the server's.
  Status verifySurface() const;
  uint64_t gaps() const { return gaps_; }
  uint64_t bytesReceived() const { return bytes_; }
  // Regions decoded from snapshots and deltas in `codec` (their header's,
  // docs/REGION_ENCODING.md "meshopt regions"): which codec the server sent.
  uint64_t regionsReceived(RegionCodec codec) const { return regionsByCodec_[static_cast<size_t>(codec)]; }

 private:
  uint64_t documentId_;
  uint64_t version_ = 0;
  bool ready_ = false;
  // A region that comes without its ids (it only moved) takes those of the
  // held copy of its layout (region_codec.h).
  Status adoptIds(const RegionHeader& header, RegionMesh& decoded) const;

  std::map<uint64_t, RegionMesh> regions_;
  std::map<uint64_t, uint64_t> layouts_;    // region -> layout version of the held copy
  std::map<uint64_t, RegionMesh> staging_;  // snapshot parts still arriving
  std::map<uint64_t, uint64_t> stagingLayouts_;
  // What is derived from a held region, dropped when it changes or goes.
  void forgetDerived(uint64_t region) const;
  mutable std::map<uint64_t, uint64_t> regionHashes_;    // region -> its hash
  mutable std::map<uint64_t, TileBoundary> boundaries_;  // region -> its boundary (tile_assembly.h)
  uint64_t announced_ = 0;
  bool viewComplete_ = false;
  uint64_t viewSeq_ = 0;
  uint64_t gaps_ = 0, bytes_ = 0;
  std::array<uint64_t, kRegionCodecCount> regionsByCodec_{};
};

}  // namespace tessera::client

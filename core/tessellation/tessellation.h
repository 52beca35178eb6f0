// What one LOD profile's viewers draw (Pulli & Lounsbery, "Hierarchical
// Editing and Rendering of Subdivision Surfaces" §3): the crack-free
// triangles of an adaptive cut through the document's hierarchy, split
// into regions that are streamed and re-sent independently.
//
// Regions are the cut's nodes at level maxLevel - 5 (or its leaves above
// that level), so a region never holds more than 4^5 leaf triangles before
// crack-closing fans; their ids are the nodes' packed FaceIds, stable as
// long as the cut above them is. At a crease or corner the normal is that
// of the sector the triangle lies in, so shading breaks only along sharp
// features.
//
// Every region is a function of the document (base mesh, tags, active
// edits) and the profile alone, never of how far the hierarchy happens to
// be held (earlier profiles, undone or earlier edits): replaying a journal
// into a fresh document gives the same regions bit for bit. So a displayed
// vertex takes its limit at a level chosen from the document, the same
// whichever leaf reaches it:
//   * the level it was born at, or deeper: the deepest level k at which an
//     active edit reaches its limit -- a move (or vertex sharpness) of the
//     vertex or of a neighbour in its level-k 1-ring, or a sharpness on one
//     of its level-k edges. A limit mask reads only the vertex's 1-ring
//     (§2.2, OpenSubdiv's PrimvarRefiner::Limit), so an offset at level k
//     on w moves the limit of exactly the level-k vertices in w's 1-ring
//     and nothing else's, and from that level on every limit of the vertex
//     agrees in exact arithmetic: the chosen level is exact;
//   * then deeper while its limit mask there is not its limit: while a
//     semi-sharp edge or vertex sharpness still acts on it (OpenSubdiv's
//     masks count a not yet decayed sharpness as sharp; refined ceil(s)
//     levels it has decayed and the mask is exact, ARCHITECTURE "Semi-sharp
//     limits") and at darts (the smooth mask, which a dart's sharp edge
//     makes only converge level by level), but never past the document's
//     maximum level, a fixed cap: a sharpness still acting there, and every
//     infinitely sharp dart, shows the limit mask of that level.
// The hierarchy is grown (Document::refineHierarchy) where it does not
// hold the vertex's ring at that level.
#pragma once

#include <map>
#include <span>
#include <vector>

#include "core/document/document.h"
#include "core/mesh/surface_mesh.h"
#include "core/tessellation/adaptive_cut.h"
#include "core/tessellation/lod_profile.h"
#include "core/tessellation/region_codec.h"

namespace tessera {

class Tessellation {
 public:
  static Expected<Tessellation> build(Document& doc, const LodProfile& profile);

  struct Changes {
    std::vector<uint64_t> changed;  // regions whose triangles changed, or that are new (sorted)
    // Those of `changed` with a new layout: new, or other triangles or
    // vertex ids than before (the rest only moved; sorted).
    std::vector<uint64_t> relaid;
    std::vector<uint64_t> removed;  // regions that no longer exist (sorted)
    bool rebuilt = false;           // the cut had to be rebuilt (the hierarchy grew)
  };
  // After the document changed (doc.lastUpdate()): re-decides and
  // re-triangulates only around what changed, and reports exactly the
  // regions whose triangles differ.
  Expected<Changes> update(Document& doc) { return update(doc, doc.lastUpdate().limits); }
  // The same after several changes since the last update: `changedLimits`
  // is the sorted union of their dirty sets' limits (a server batching the
  // edits queued together updates once).
  Expected<Changes> update(Document& doc, std::span<const VertexId> changedLimits);

  const LodProfile& profile() const { return cut_.profile(); }
  int regionLevel() const { return regionLevel_; }
  const std::map<uint64_t, RegionMesh>& regions() const { return regions_; }
  int64_t numTriangles() const { return triangles_; }
  // All regions as one mesh, vertices merged by identity (tests, export).
  SurfaceMesh surface() const;

 private:
  Tessellation(AdaptiveCut cut, int regionLevel, const LevelCounts& counts)
      : cut_(std::move(cut)), regionLevel_(regionLevel), counts_(counts) {}

  // The regions of the cut under (level, face), appended as packed FaceIds.
  void regionsUnder(const SparseHierarchy& h, int l, Index f, std::vector<uint64_t>& out) const;
  // Appends to `growth` the faces the hierarchy must hold for the limits
  // the region shows (the mesh is then incomplete).
  RegionMesh buildRegion(const SparseHierarchy& h, FaceId region, std::vector<FaceId>& growth) const;
  Expected<Changes> rebuildAll(Document& doc);
  Status checkBudget() const;

  AdaptiveCut cut_;
  int regionLevel_ = 0;
  LevelCounts counts_;
  std::map<uint64_t, RegionMesh> regions_;
  int64_t triangles_ = 0;
};

}  // namespace tessera

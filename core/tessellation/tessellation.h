// What one LOD profile's viewers draw (seed 000 §3): the crack-free
// triangles of an adaptive cut through the document's hierarchy, split
// into regions that are streamed and re-sent independently.
//
// Regions are the cut's nodes at level maxLevel - 5 (or its leaves above
// that level), so a region never holds more than 4^5 leaf triangles before
// crack-closing fans; their ids are the nodes' packed FaceIds, stable as
// long as the cut above them is. Every displayed vertex takes its limit at
// the deepest level where its ring is held (edits deeper than that cannot
// reach it), so it has one position whichever leaf reaches it. That is the
// true limit wherever no semi-sharp crease or dart acts at that level
// (their limit masks, as in OpenSubdiv, are exact only once the feature
// has decayed). At a crease or corner the normal is that of the sector the
// triangle lies in, so shading breaks only along sharp features.
#pragma once

#include <map>
#include <span>
#include <vector>

#include "core/document/document.h"
#include "core/io/mesh_export.h"
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
  void regionsUnder(const SparseEvaluator& h, int l, Index f, std::vector<uint64_t>& out) const;
  RegionMesh buildRegion(const SparseEvaluator& h, FaceId region) const;
  Expected<Changes> rebuildAll(Document& doc);
  Status checkBudget() const;

  AdaptiveCut cut_;
  int regionLevel_ = 0;
  LevelCounts counts_;
  std::map<uint64_t, RegionMesh> regions_;
  int64_t triangles_ = 0;
};

}  // namespace tessera

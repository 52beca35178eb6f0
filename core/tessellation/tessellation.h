// What one LOD profile's viewers draw (Pulli & Lounsbery, "Hierarchical
// Editing and Rendering of Subdivision Surfaces" §3): the crack-free
// triangles of an adaptive cut through the document's hierarchy, split
// into regions that are streamed and re-sent independently.
//
// Regions are the cut's nodes at level maxLevel - 5 (or its leaves above
// that level), so a region never holds more than 4^5 leaf triangles before
// crack-closing fans; their ids are the nodes' packed FaceIds, stable as
// long as the cut above them is. For a profile whose deepest level is at
// most kMaxGroupedLevel (below), where a base face shows few triangles, the
// base faces' regions are grouped instead, 4^(kGroupDepth - maxLevel)
// neighbouring faces to a region (base_face_clusters.h), so that each
// region's fixed costs are shared (docs/REGION_ENCODING.md "Region
// groups"); a group is named by the packed FaceId of its seed face. At a crease or corner the normal is that
// of the sector the triangle lies in, so shading breaks only along sharp
// features.
//
// On a Catmull-Clark document (the quad split) the same holds with a node's
// children one per corner: a region holds at most 4^5 leaf quads (a base
// n-gon's, n 4^4), each quad leaf at least two triangles, and every vertex
// one normal (Catmull-Clark's limit masks
// give one: docs/LIMITS.md "Catmull-Clark documents").
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
//     limits") and at Loop's darts (the smooth mask, which a dart's sharp
//     edge makes only converge level by level; a Catmull-Clark dart's masks
//     are exact, core/catmark/dart_masks.h), but never past the document's
//     maximum level, a fixed cap: a sharpness still acting there, and every
//     infinitely sharp Loop dart, shows the limit mask of that level.
// The hierarchy is grown (Document::refineHierarchy) where it does not
// hold the vertex's ring at that level.
#pragma once

#include <map>
#include <memory>
#include <span>
#include <vector>

#include "core/document/document.h"
#include "core/mesh/surface_mesh.h"
#include "core/tessellation/adaptive_cut.h"
#include "core/tessellation/base_face_clusters.h"
#include "core/tessellation/lod_profile.h"
#include "core/tessellation/region_codec.h"

namespace tessera {

// Base faces' regions are grouped for profiles whose deepest level is at
// most kMaxGroupedLevel (a base face then shows at most 64 triangles):
// 4^(kGroupDepth - maxLevel) faces to a region, so a region holds at most
// 4^kGroupDepth = 4,096 leaf triangles. Deeper profiles keep a region per
// base face or below (at most 1,024 leaf triangles), which keeps an edit's
// delta small where edits are made.
inline constexpr int kGroupDepth = 6;
inline constexpr int kMaxGroupedLevel = 3;

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
  // The regions viewers receive: groups of base faces' regions, or the
  // cut's own regions (regionsAreGroups()).
  const std::map<uint64_t, RegionMesh>& regions() const { return clusters_ ? groups_ : fine_; }
  bool regionsAreGroups() const { return clusters_ != nullptr; }
  int64_t numTriangles() const { return triangles_; }
  // All regions as one mesh, vertices merged by identity (tests, export).
  SurfaceMesh surface() const;

 private:
  Tessellation(AdaptiveCut cut, int regionLevel, const LevelCounts& counts)
      : cut_(std::move(cut)), regionLevel_(regionLevel), counts_(counts) {}
  // build, with the clusters of an earlier build of the same document when
  // there are any (they depend on the base topology and profile alone).
  static Expected<Tessellation> build(Document& doc, const LodProfile& profile,
                                      std::shared_ptr<const BaseFaceClusters> clusters);

  // The regions of the cut under (level, face), appended as packed FaceIds.
  void regionsUnder(const SparseHierarchy& h, int l, Index f, std::vector<uint64_t>& out) const;
  // Appends to `growth` the faces the hierarchy must hold for the limits
  // the region shows (the mesh is then incomplete).
  RegionMesh buildRegion(const SparseHierarchy& h, FaceId region, std::vector<FaceId>& growth) const;
  // buildRegion for each of `ids` (packed FaceIds), in order, on several
  // cores (each reads the hierarchy alone); their growth is appended to
  // `growth` in the same order.
  std::vector<RegionMesh> buildRegions(const SparseHierarchy& h, std::span<const uint64_t> ids,
                                       std::vector<FaceId>& growth) const;
  Expected<Changes> rebuildAll(Document& doc);
  // The group of every base face's region, merged (vertices shared by id
  // and normal, region_merge.h).
  RegionMesh buildGroup(uint32_t cluster) const;
  // The cut's changes as changes of the groups that hold them.
  Changes regroup(const Changes& fine);
  Status checkBudget() const;

  AdaptiveCut cut_;
  int regionLevel_ = 0;
  LevelCounts counts_;
  std::map<uint64_t, RegionMesh> fine_;               // the cut's regions
  std::shared_ptr<const BaseFaceClusters> clusters_;  // when base faces' regions are grouped
  std::map<uint64_t, RegionMesh> groups_;             // by the seed face's packed FaceId
  int64_t triangles_ = 0;
};

}  // namespace tessera

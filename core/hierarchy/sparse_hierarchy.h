// The document's working state: a sparse forest of quadtrees, one per base
// face (Pulli & Lounsbery, "Hierarchical Editing and Rendering of
// Subdivision Surfaces" §4.1), evaluated incrementally (§4.2, Fig. 7). The
// faces split by Loop's triangle split or by Catmull-Clark's quad split, as
// the level counts say (ids.h); the scheme enters through the stencils that
// predict a child (child_stencils.h) and the limits (level_limits.h).
//
// Which faces exist: every level up to `uniformLevel` is whole; below it a
// face is a quadtree node only where it is demanded -- an edit addresses an
// element inside it -- or is an ancestor of a demanded face. Around the
// nodes the levels keep the padding the Loop stencils need: the 1-ring of
// every node (so node vertices have complete rings, for limits and frames)
// and its 1-ring again at the parent (so node children can be computed).
// With Sel_k the nodes that have children, the faces refined at level k are
// R_k = N1(Sel_k), and Sel_k = N1(ancestors at k of demanded faces); these
// nest (Sel_k+1 within the children of Sel_k, and N2 of a child face within
// the children of N1 of its parent), so every vertex of a refined face is
// complete and every present vertex is computed from complete stencils.
// Limits are kept for every complete vertex; the *leaves* -- nodes without
// children -- are the hierarchy's own display (tessellations cut through
// the nodes by their LOD profiles, core/tessellation).
//
// Semantics are those of core/document/document_evaluator.h, the dense reference: the
// property tests require agreement to 1e-9 at every present vertex. On the
// quad split the reference is OpenSubdiv Far with each level's edits added
// before the next level (tests/oracle/catmark_hierarchy_oracle_test.cc);
// interpolating vertices are Loop's (docs/INTERPOLATION.md) and refused there.
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <span>
#include <unordered_map>
#include <vector>

#include "core/hierarchy/edit.h"
#include "core/hierarchy/ids.h"
#include "core/hierarchy/level_limits.h"
#include "core/hierarchy/sparse_far_rings.h"
#include "core/hierarchy/sparse_level.h"
#include "core/hierarchy/sparse_selection.h"
#include "core/loop/ghost_ring.h"
#include "core/loop/level_builder.h"
#include "core/loop/limit.h"
#include "core/loop/local_frame.h"
#include "core/loop/loop_options.h"
#include "core/util/status.h"

namespace tessera {

// What one change recomputed: the limits it refreshed (the dirty set a
// tessellation starts from) and how much work that was.
struct DirtySet {
  std::vector<VertexId> limits;     // complete vertices whose limit position or normal was recomputed, sorted
  std::vector<FaceId> leaves;       // the hierarchy's displayed leaves around them, sorted
  std::vector<uint64_t> baseFaces;  // the quadtree roots holding those leaves, sorted
  int64_t pointsRecomputed = 0;     // control points, over all levels
  int64_t limitsRecomputed = 0;
  int grownFromLevel = -1;  // >= 0: the hierarchy grew; levels below this one gained faces
};

struct HierarchyStats {
  struct PerLevel {
    int64_t faces = 0, vertices = 0, completeVertices = 0, leaves = 0, displayedVertices = 0;
    size_t bytes = 0;
  };
  std::vector<PerLevel> levels;
  int64_t vertices = 0;           // control points held, all levels
  int64_t displayedVertices = 0;  // corners of leaves (counted per level)
  size_t bytes = 0;               // topology, ids, points, limits, edits' indices
};

class SparseHierarchy {
 public:
  static Expected<SparseHierarchy> create(const BaseTopology& base, std::span<const Vec3> basePoints,
                                          const LoopOptions& options, const LevelCounts& counts,
                                          int uniformLevel, std::span<const Edit> edits);
  // From a built base level (buildBaseLevel for Loop, buildPolyLevel
  // for Catmull-Clark's polygons); `counts` names the split.
  static Expected<SparseHierarchy> create(Level level0, std::span<const Vec3> basePoints,
                                          const LoopOptions& options, const LevelCounts& counts,
                                          int uniformLevel, std::span<const Edit> edits);

  // Grows the hierarchy so that it holds what `edit` addresses, with complete
  // rings (call before solving a move there). `edits` is the current list.
  // Where it held that already, the limits around the faces that became
  // edit nodes are reported (a tessellation's cut changes there).
  DirtySet reserve(const Edit& edit, std::span<const Edit> edits);
  // Grows it so that each face is a node whose vertices are complete (a
  // tessellation refining there). Returns the first level it grew from, or -1.
  int reserveFaces(std::span<const FaceId> faces, std::span<const Edit> edits);
  // Holds levels 0..level whole from now on.
  void raiseUniformLevel(int level, std::span<const Edit> edits);
  // Brings the state up to date after `edit` was added, undone, redone or
  // removed; `edits` is the list after that change. Only the edited
  // elements, their stencil neighbourhoods and their descendants are
  // recomputed.
  DirtySet update(const Edit& edit, std::span<const Edit> edits);
  // After an edit left the list for good (removed or retracted): its edit
  // nodes go too, so they are those of a document created with `edits`.
  // The structure it grew stays (a cache: limits and cuts do not depend on
  // it). Returns the limits around the faces that stopped being edit nodes,
  // for a tessellation to decide again there.
  DirtySet forgetEditNodes(std::span<const Edit> edits);

  int numLevels() const { return static_cast<int>(levels_.size()); }
  // Loop's triangle split or Catmull-Clark's quad split.
  bool quads() const { return counts_.quads(); }
  const LevelCounts& counts() const { return counts_; }
  // How many children face f of level l has (firstChildFace onwards): four
  // triangles, or a quad per corner.
  int numChildFaces(int l, Index f) const { return quads() ? levels_[l].topo.mesh.faceSize(f) : 4; }
  // Whether level l's vertices have limits (level_limits.h): all but a
  // Catmull-Clark base with other polygons than quads.
  bool hasLimits(int l) const { return LevelLimits::hasLimits(levels_[l].topo.mesh, counts_.split()); }
  int uniformLevel() const { return selection_.uniformLevel(); }
  const SparseLevel& level(int l) const { return levels_[l].topo; }
  std::span<const Vec3> points(int l) const { return levels_[l].points; }
  std::span<const Vec3> predicted(int l) const { return levels_[l].predicted; }
  bool isLeaf(int l, Index face) const { return levels_[l].leaf[face] != 0; }
  bool isDisplayed(int l, Index vertex) const { return levels_[l].displayed[vertex] != 0; }
  // A node with children because of an edit (not a tessellation's request).
  bool isEditNode(int l, Index face) const { return levels_[l].editSelected[face] != 0; }
  bool isNodeWithChildren(int l, Index face) const { return levels_[l].selected[face] != 0; }
  // Bumped whenever level l grows (what it held keeps its local index).
  uint64_t generation(int l) const { return levels_[l].generation; }
  // Limit position and unit normal of a complete vertex, and its limit
  // tangents (for crease tangents, §3.1.2).
  const Vec3& limitPosition(int l, Index vertex) const { return levels_[l].limitPosition[vertex]; }
  const Vec3& limitNormal(int l, Index vertex) const { return levels_[l].limitNormal[vertex]; }
  LimitFrame limitFrameOf(int l, Index vertex) const;
  // The control point of a complete vertex whose limit is `target`
  // (level_limits.h: direct manipulation by the document's scheme). On a
  // level without limits (a Catmull-Clark base with other polygons than
  // quads) the vertex's limit is its child's on level l + 1, which must
  // hold the child's ring (the document grows it there first).
  Vec3 solveControlPoint(int l, Index vertex, const Vec3& target) const;
  // The crease decay the limits follow (limit.h needs it for semi-sharp features).
  CreaseMethod creaseMethod() const { return options_.creaseMethod; }
  // Whether an active edit at level l reaches the limit of this vertex (as
  // a level-l vertex): a move or a vertex sharpness of the vertex or of a
  // ring neighbour (its limit mask reads their points; a vertex tag is
  // counted like a move, conservatively), or a sharpness on one of its
  // edges (its rule). Only complete vertices are reached; every vertex an
  // active edit reaches is complete, since the edit's node holds the
  // 1-rings of its vertices. Limits taken deeper than every level whose
  // edits reach a vertex, and past its semi-sharp features, are exact
  // (core/tessellation/tessellation.h).
  bool isReachedByEdit(int l, Index vertex) const { return levels_[l].reached[vertex] != 0; }

  // Whether level l+1's points and rules around the vertex it puts on edge
  // e of level l are what level l's stencils predict, so that its limit can
  // be read from level l (core/loop/edge_child_limit.h): no interpolating
  // vertex among the corners of e's faces (its ghost ring would move that
  // vertex or its ring) and no edit at level l+1 reaching it. An edit's node
  // holds every vertex the edit reaches, so a vertex the hierarchy does not
  // hold is reached by none. The ends of e must be complete.
  bool edgeChildIsPredicted(int l, Index e) const;
  const LoopOptions& options() const { return options_; }
  // The far rings Chaikin's decay reads at level l (sparse_far_rings.h):
  // pass it wherever a limit is taken on this hierarchy's levels.
  SparseFarRings farRings(int l) const {
    return SparseFarRings(levels_[l].topo, l > 0 ? &levels_[l - 1].topo : nullptr, options_);
  }
  // The vertices of level l that active edits at level l touch:
  // `visit(vertex, offset)` with the summed local offset of a moved vertex,
  // nullopt for a tagged one (its sharpness, an edge's at its first end, or
  // an interpolating vertex, which shapes level l+1).
  template <typename Visit>
  void forEachEditedVertex(int l, Visit&& visit) const {
    const LevelState& state = levels_[l];
    for (const auto& [v, offset] : state.offsets) visit(v, std::optional<Vec3>(offset));
    for (const auto& [v, s] : state.vertexTags) visit(v, std::optional<Vec3>());
    for (const auto& [v, t] : state.interpolationTags) visit(v, std::optional<Vec3>());
    for (const auto& [e, s] : state.edgeTags)
      visit(state.topo.mesh.edgeVertices[e][0], std::optional<Vec3>());
  }

  // The local index of a vertex with a complete ring, or a clear error.
  Expected<Index> completeVertex(VertexId id) const;
  // The frame offsets of `id` are stored in (from the predicted points).
  LocalFrame frameOf(int l, Index vertex) const;

  HierarchyStats stats() const;

 private:
  struct LevelState {
    SparseLevel topo;
    Buffer<uint8_t> selected;      // per face: a node with children
    Buffer<uint8_t> editSelected;  // per face: one because of an edit
    uint64_t generation = 0;
    Buffer<uint8_t> leaf;       // per face: a node without children (displayed)
    Buffer<uint8_t> displayed;  // per vertex: a corner of a leaf
    std::vector<Vec3> predicted, points;
    std::vector<Vec3> limitPosition, limitNormal;  // valid where displayed
    std::unordered_map<Index, Vec3> offsets;       // summed local offsets of active moves
    std::unordered_map<Index, float> edgeTags, vertexTags;
    // Interpolating vertices of this level: they shape the next level's
    // points (their ghost rings, core/loop/ghost_ring.h).
    std::unordered_map<Index, InterpolationTag> interpolationTags;
    Buffer<uint8_t> reached;  // per vertex: isReachedByEdit
    // Scratch for the incremental update: all zero between updates.
    std::vector<uint8_t> vertexMarks, faceMarks;
  };

  SparseHierarchy(const LoopOptions& options, const LevelCounts& counts, int uniformLevel);

  // Structure (sparse_hierarchy.cc; which faces exist is selection_'s,
  // core/hierarchy/sparse_selection.h).
  // The faces an edit addresses below level 0 (incident to its elements).
  std::vector<FaceId> demandedFaces(const Edit& edit) const;
  void addDemand(const Edit& edit);
  void markEditNodes(FaceId face, DirtySet& dirty);
  bool demandCovered(FaceId face) const;
  int firstChangedSelection() const;
  // Grows every level from l on in place to the selection (growFrom in
  // sparse_hierarchy.cc); levels it adds are built and evaluated whole.
  void growFrom(int l, std::span<const Edit> edits);
  // Points and tags of a level built whole.
  void evaluateLevel(int l, std::span<const Edit> edits);
  // The predictions and points of the vertices level l just gained.
  void evaluateNewVertices(int l, const LevelExtension& grown);
  // Leaves and displayed vertices of level l; the limits of every complete
  // vertex of a level built whole, or else of `newLimits` (the vertices a
  // growth completed).
  void markLeaves(int l, bool freshLevel, const std::vector<Index>& newLimits);
  void refreshLimit(int l, Index vertex, const LevelLimits& limits);
  LevelLimits limitsOf(
      int l, CatmarkLimitEvaluator::Scope scope = CatmarkLimitEvaluator::Scope::kSomeVertices) const;

  // Edits at one level (sparse_hierarchy.cc).
  void resolveTags(int l, std::span<const Edit> edits);
  void applyTags(int l);
  float inheritedEdgeSharpness(int l, Index edge) const;
  float inheritedVertexSharpness(int l, Index vertex) const;
  void recomputeRule(int l, Index vertex);
  void applyOffset(int l, Index vertex);
  // The ghost ring of interpolating vertex v of level l-1 written over the
  // predictions of level l (present children only).
  void applyGhostRing(int l, Index parentVertex);
  // A level-l vertex whose prediction a ghost ring of level l-1 set: V0's
  // child or the vertex on one of V0's edges.
  bool isGhosted(int l, Index vertex) const;
  // The present children at level l+1 of interpolating vertex v of level l
  // and of its edges.
  std::vector<Index> ghostRingChildren(int l, Index vertex) const;
  // Re-derives isReachedByEdit for these vertices from the level's offsets
  // and tags (the vertices around the edited ones).
  void refreshReached(int l, const std::vector<Index>& vertices);

  // Incremental propagation (sparse_update.cc).
  std::vector<Index> applyEditAtItsLevel(const Edit& edit, std::span<const Edit> edits);
  void propagate(int l, std::vector<Index> sources, DirtySet& dirty);
  std::vector<Index> refreshChildren(int l, const std::vector<Index>& parentFaces);
  std::vector<Index> verticesAround(int l, const std::vector<Index>& vertices);
  void refreshLimitsNear(int l, const std::vector<Index>& changed, const std::vector<Index>& candidates,
                         DirtySet& dirty);

  LoopOptions options_;
  LevelCounts counts_;
  std::vector<float> baseEdgeSharpness_, baseVertexSharpness_;
  std::vector<Vec3> basePoints_;
  SparseSelection selection_;  // the demanded faces and the uniform level: which faces exist
  std::vector<LevelState> levels_;
};

}  // namespace tessera

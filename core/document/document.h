// Document: a base mesh, its feature tags and a hierarchy of edits made at
// any subdivision level (Pulli & Lounsbery, "Hierarchical Editing and
// Rendering of Subdivision Surfaces"). Edits are validated before they change
// anything: an invalid command leaves the document exactly as it was.
//
//   auto doc = Document::create(mesh, {}, {.maxLevel = 5});
//   auto id = doc->moveToLimit({VertexId(2, 17)}, target);   // direct manipulation
//   doc->undo(*id);  doc->redo(*id);
//   auto surface = doc->surface(4, SurfaceKind::kLimit);
//
// The working state is a sparse forest of quadtrees updated incrementally
// after every change (sparse_hierarchy.h); lastUpdate() says what changed.
// Uniform surfaces for export are evaluated from scratch by the dense
// reference (document_evaluator.h).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include "core/catmark/polygon_level.h"
#include "core/document/document_evaluator.h"
#include "core/document/document_scheme.h"
#include "core/hierarchy/edit.h"
#include "core/hierarchy/ids.h"
#include "core/hierarchy/sparse_hierarchy.h"
#include "core/loop/ghost_ring.h"
#include "core/loop/level_builder.h"
#include "core/loop/loop_options.h"
#include "core/mesh/base_mesh.h"
#include "core/mesh/surface_mesh.h"
#include "core/util/status.h"

namespace tessera {

struct DocumentOptions {
  // The crease options (OpenSubdiv's Sdc options), under either scheme.
  LoopOptions loop{};
  int maxLevel = 6;  // deepest level an edit may address (at most kMaxDocumentLevel)
  // Levels 0..uniformLevel are held whole (the coarsest display); deeper
  // levels only where edits are. Not part of the saved document.
  int uniformLevel = 0;
  DocumentScheme scheme = DocumentScheme::kLoop;
};

// A document's base mesh: triangles under Loop, polygons under
// Catmull-Clark.
using DocumentBase = std::variant<BaseTopology, PolyTopology>;

inline constexpr int kMaxDocumentLevel = 12;

enum class SurfaceKind { kControl, kLimit };

class Document {
 public:
  // Under options.scheme; a Loop document refuses a polygon that is not a
  // triangle, naming the face.
  static Expected<Document> create(const BaseMesh& mesh, const DocumentOptions& options);
  static Expected<Document> create(BaseTopology topology, std::vector<Vec3> points,
                                   const DocumentOptions& options);
  static Expected<Document> create(PolyTopology topology, std::vector<Vec3> points,
                                   const DocumentOptions& options);

  DocumentScheme scheme() const { return options_.scheme; }
  const DocumentBase& base() const { return base_; }
  // Loop documents only (check scheme() first): the base triangles.
  const BaseTopology& baseTopology() const { return std::get<BaseTopology>(base_); }
  // Catmull-Clark documents only: the base polygons.
  const PolyTopology& polygonTopology() const { return std::get<PolyTopology>(base_); }
  const std::vector<Vec3>& basePoints() const { return basePoints_; }
  const DocumentOptions& options() const { return options_; }
  const LevelCounts& counts() const { return counts_; }
  const std::vector<Edit>& edits() const { return edits_; }
  uint64_t nextEditId() const { return nextEditId_; }

  // Direct manipulation (§2.2): the first vertex's limit position goes to
  // `target`; the others (same level) move by the same displacement.
  Expected<EditId> moveToLimit(std::span<const VertexId> vertices, const Vec3& target);
  // A plain world-space displacement of the vertices' control points.
  Expected<EditId> moveBy(std::span<const VertexId> vertices, const Vec3& displacement);
  Expected<EditId> setEdgeSharpness(EdgeId edge, float sharpness);
  Expected<EditId> setVertexSharpness(VertexId vertex, float sharpness);
  // A locally interpolating vertex (docs/INTERPOLATION.md): the surface passes
  // through this vertex's control point (core/loop/ghost_ring.h), with this
  // tension; `tangent` (boundary and crease vertices only) sets the tangent
  // line. Refused where no ghost ring applies (ghostRuleOf says why), at the
  // deepest level, where finer edits conflict (interpolation_conflicts.h),
  // and in Catmull-Clark documents (ghost rings are Loop's).
  // interpolating = false ends it.
  Expected<EditId> setInterpolation(VertexId vertex, bool interpolating, double tension = 1.0,
                                    const Vec3& tangent = Vec3(0, 0, 0));
  // The vertex's tension if it interpolates now (the latest active edit).
  std::optional<InterpolationTag> interpolationOf(VertexId vertex) const;
  // The edge joining two vertices of one level, in either order: how a
  // client that knows only vertex ids names an edge (hierarchy/incidence.h).
  // Errors name both ids.
  Expected<EdgeId> edgeBetween(VertexId a, VertexId b) const;

  // Re-applies an edit exactly as it was recorded (journal replay): its id
  // must be the next one, and it is validated as if just made.
  Status replay(const Edit& edit);

  // Takes back the most recent edit as if it had never been made (its id is
  // reused): for a server refusing an edit after applying it.
  Status retractLast();

  Status undo(EditId id);  // the edit stops applying; error if unknown or already undone
  Status redo(EditId id);  // it applies again; error if unknown or not undone
  // Takes back an undo (a server retracting a refused command): like redo,
  // without redo's conflict checks, since the state before the undo held.
  Status reinstate(EditId id);
  Status remove(EditId id);  // gone for good; error if unknown

  // Control points or limit surface at `level` <= maxLevel. Loop: triangles,
  // limit normals split per side at creases. Catmull-Clark: the level's
  // polygons kept (core/catmark/surfaces.h); the limit of level 0 needs a
  // base of quads only.
  Expected<SurfaceMesh> surface(int level, SurfaceKind kind) const;
  // Grows the hierarchy so that these faces are nodes (a tessellation
  // refining there); changes no surface. Returns the level it grew from, or -1.
  int refineHierarchy(std::span<const FaceId> faces) { return sparse_->reserveFaces(faces, edits_); }
  // Holds levels 0..level whole (a profile's base level); changes no surface.
  void holdWhole(int level) { sparse_->raiseUniformLevel(std::min(level, options_.maxLevel), edits_); }

  // The incremental state, and what the last change recomputed.
  const SparseHierarchy& hierarchy() const { return *sparse_; }
  const DirtySet& lastUpdate() const { return lastUpdate_; }

  // Full evaluation up to `level`, cached until the next change.
  Expected<std::shared_ptr<const Evaluation>> evaluate(int level) const;

  // Restores a document from its parts (document_file.cc); every edit is
  // validated as if it had just been made.
  static Expected<Document> restore(DocumentBase base, std::vector<Vec3> points,
                                    const DocumentOptions& options, std::vector<Edit> edits,
                                    uint64_t nextEditId);

 private:
  Document(DocumentBase base, std::vector<Vec3> points, const DocumentOptions& options, LevelCounts counts);
  static Expected<Document> createFrom(DocumentBase base, std::vector<Vec3> points,
                                       const DocumentOptions& options);

  bool isBoundaryEdge(EdgeId edge) const;
  Status checkVertices(std::span<const VertexId> vertices) const;
  Status checkEdit(const Edit& edit) const;
  // Whether the vertex's rule at its level admits a ghost ring (grows the
  // hierarchy there first).
  Status checkGhostRule(const InterpolationEdit& tag);
  Status checkUncovered(const Edit& leaving);
  Expected<EditId> add(Edit edit);
  void append(Edit edit);
  Status reserveVertices(std::span<const VertexId> vertices);
  Edit* find(EditId id);
  Status setActive(EditId id, bool active, bool checked = true);
  Expected<MoveEdit> offsetsFor(std::span<const VertexId> vertices, const Vec3& world);
  Status rebuildHierarchy();
  Status rebuildHierarchy(Level level0);  // from a base level already built
  // Grows the hierarchy for an edit about to be made; remembers the growth
  // for lastUpdate().
  void reserve(const Edit& edit);
  // After a removal or retraction: drops the gone edit's edit nodes.
  void forgetRemovedEditNodes();
  // Adds `limits` to lastUpdate()'s, which stay sorted and unique.
  void addChangedLimits(std::span<const VertexId> limits);

  DocumentBase base_;
  std::vector<Vec3> basePoints_;
  DocumentOptions options_;
  LevelCounts counts_;
  std::vector<uint8_t> baseBoundaryEdges_;
  std::vector<Edit> edits_;
  uint64_t nextEditId_ = 1;
  std::optional<SparseHierarchy> sparse_;
  DirtySet lastUpdate_;
  int pendingGrowth_ = -1;
  std::vector<VertexId> pendingLimits_;  // limits reserve() reported, for lastUpdate()
  mutable std::shared_ptr<const Evaluation> cache_;
};

}  // namespace tessera

#include "core/document/document.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/catmark/surfaces.h"
#include "core/hierarchy/incidence.h"
#include "core/hierarchy/interpolation_conflicts.h"
#include "core/loop/local_frame.h"
#include "core/loop/surfaces.h"

namespace tessera {

namespace {

// The dense reference evaluation refuses what would not fit in memory.
constexpr uint64_t kMaxEvaluatedFaces = 16ull * 1024 * 1024;

Status checkSharpness(float sharpness, const std::string& what) {
  if (!(sharpness >= 0.0f)) {  // also NaN
    return invalidArgument(what + ": sharpness must be >= 0 (or inf), got " + std::to_string(sharpness));
  }
  return Status::ok();
}

// The base level under the document's scheme: Loop's triangles or the
// polygons of Catmull-Clark.
Expected<Level> buildLevel0(const DocumentBase& base, const LoopOptions& options) {
  if (const auto* triangles = std::get_if<BaseTopology>(&base)) return buildBaseLevel(*triangles, options);
  return buildPolyLevel(std::get<PolyTopology>(base), options);
}

std::vector<int> faceSizes(const Level& level) {
  std::vector<int> sizes(level.numFaces());
  for (Index f = 0; f < level.numFaces(); ++f) sizes[f] = level.faceSize(f);
  return sizes;
}

Status checkFinite(const Vec3& p, const std::string& what) {
  if (!isFinite(p)) return invalidArgument(what + " must be finite");
  return Status::ok();
}

}  // namespace

Document::Document(DocumentBase base, std::vector<Vec3> points, const DocumentOptions& options,
                   LevelCounts counts)
    : base_(std::move(base)), basePoints_(std::move(points)), options_(options), counts_(std::move(counts)) {}

Expected<Document> Document::create(const BaseMesh& mesh, const DocumentOptions& options) {
  return create(BaseTopology::fromBaseMesh(mesh), mesh.positions(), options);
}

Expected<Document> Document::create(BaseTopology topology, std::vector<Vec3> points,
                                    const DocumentOptions& options) {
  if (options.scheme == DocumentScheme::kLoop)
    return createFrom(std::move(topology), std::move(points), options);
  return createFrom(PolyTopology::fromTriangles(std::move(topology)), std::move(points), options);
}

Expected<Document> Document::create(PolyTopology topology, std::vector<Vec3> points,
                                    const DocumentOptions& options) {
  if (options.scheme == DocumentScheme::kCatmullClark)
    return createFrom(std::move(topology), std::move(points), options);
  BaseTopology triangles;
  triangles.numVertices = topology.numVertices;
  for (int f = 0; f < topology.numFaces(); ++f) {
    const int size = topology.faceOffsets[f + 1] - topology.faceOffsets[f];
    if (size != 3) {
      return invalidArgument("face " + std::to_string(f) + " has " + std::to_string(size) +
                             " corners: a Loop document takes triangles only (choose catmull-clark)");
    }
    const int* corners = topology.indices.data() + topology.faceOffsets[f];
    triangles.triangles.push_back({corners[0], corners[1], corners[2]});
  }
  triangles.creases = std::move(topology.creases);
  triangles.vertexSharpness = std::move(topology.vertexSharpness);
  return createFrom(std::move(triangles), std::move(points), options);
}

Expected<Document> Document::createFrom(DocumentBase base, std::vector<Vec3> points,
                                        const DocumentOptions& options) {
  if (options.maxLevel < 0 || options.maxLevel > kMaxDocumentLevel) {
    return invalidArgument("maximum level must be 0.." + std::to_string(kMaxDocumentLevel) + ", got " +
                           std::to_string(options.maxLevel));
  }
  const int numVertices = std::visit([](const auto& t) { return t.numVertices; }, base);
  if (static_cast<int>(points.size()) != numVertices) {
    return invalidArgument("the base mesh has " + std::to_string(numVertices) + " vertices but " +
                           std::to_string(points.size()) + " points");
  }
  for (size_t v = 0; v < points.size(); ++v) {
    TESSERA_RETURN_IF_ERROR(checkFinite(points[v], "base vertex " + std::to_string(v)));
  }
  if (options.uniformLevel < 0 || options.uniformLevel > options.maxLevel) {
    return invalidArgument("uniform level must be 0.." + std::to_string(options.maxLevel) + ", got " +
                           std::to_string(options.uniformLevel));
  }
  // Building level 0 validates the topology and the base tags; the first
  // hierarchy takes it.
  TESSERA_ASSIGN_OR_RETURN(Level built, buildLevel0(base, options.loop));
  LevelCounts counts =
      options.scheme == DocumentScheme::kLoop
          ? LevelCounts(built.numVertices, built.numEdges(), built.numFaces(), options.maxLevel)
          : LevelCounts::quads(built.numVertices, built.numEdges(), faceSizes(built), options.maxLevel);
  Document doc(std::move(base), std::move(points), options, std::move(counts));
  doc.baseBoundaryEdges_.resize(built.numEdges());
  for (Index e = 0; e < built.numEdges(); ++e) doc.baseBoundaryEdges_[e] = built.isBoundaryEdge(e);
  TESSERA_RETURN_IF_ERROR(doc.rebuildHierarchy(std::move(built)));
  return doc;
}

Expected<Document> Document::restore(DocumentBase base, std::vector<Vec3> points,
                                     const DocumentOptions& options, std::vector<Edit> edits,
                                     uint64_t nextEditId) {
  TESSERA_ASSIGN_OR_RETURN(
      Document doc,
      std::visit([&](auto& topology) { return create(std::move(topology), std::move(points), options); },
                 base));
  uint64_t last = 0;
  for (const Edit& edit : edits) {
    if (edit.id.value <= last) return invalidArgument(edit.id.toString() + ": edit ids must increase");
    last = edit.id.value;
    TESSERA_RETURN_IF_ERROR(doc.checkEdit(edit).withContext(edit.id.toString()));
  }
  if (nextEditId <= last) return invalidArgument("next edit id must exceed the last edit's");
  doc.edits_ = std::move(edits);
  doc.nextEditId_ = nextEditId;
  TESSERA_RETURN_IF_ERROR(doc.rebuildHierarchy());
  return doc;
}

bool Document::isBoundaryEdge(EdgeId edge) const {
  // Halves of a parent edge share its boundary status; edges inside a parent
  // face never lie on the boundary. Loop numbers the halves first, the quad
  // split the edges inside faces first (docs/ARCHITECTURE.md "Numbering").
  uint64_t index = edge.index();
  for (int l = edge.level(); l > 0; --l) {
    if (counts_.quads()) {
      if (index < counts_.corners(l - 1)) return false;
      index -= counts_.corners(l - 1);
    } else if (index >= 2 * counts_.edges(l - 1)) {
      return false;
    }
    index /= 2;
  }
  return baseBoundaryEdges_[index] != 0;
}

// The order of the checks is the protocol's (PROTOCOL 7.2, "Which error
// wins"): the list's shape, then every id's existence in the order given
// (notFound), then how the ids relate (invalidArgument), so the reason does
// not depend on where in the list a missing id stands.
Status Document::checkVertices(std::span<const VertexId> vertices) const {
  if (vertices.empty()) return invalidArgument("a move names no vertex");
  for (VertexId v : vertices) TESSERA_RETURN_IF_ERROR(counts_.check(v));
  for (VertexId v : vertices) {
    if (v.level() != vertices[0].level()) {
      return invalidArgument("vertices moved together must share a level: " + vertices[0].toString() +
                             " and " + v.toString());
    }
  }
  for (size_t i = 0; i < vertices.size(); ++i) {
    for (size_t j = i + 1; j < vertices.size(); ++j) {
      if (vertices[i] == vertices[j]) return invalidArgument(vertices[i].toString() + " is named twice");
    }
  }
  return Status::ok();
}

Status Document::checkEdit(const Edit& edit) const {
  if (const auto* move = std::get_if<MoveEdit>(&edit.change)) {
    std::vector<VertexId> vertices;
    for (const auto& o : move->offsets) {
      vertices.push_back(o.vertex);
      TESSERA_RETURN_IF_ERROR(checkFinite(o.localOffset, o.vertex.toString() + " offset"));
    }
    return checkVertices(vertices);
  }
  if (const auto* e = std::get_if<EdgeSharpnessEdit>(&edit.change)) {
    TESSERA_RETURN_IF_ERROR(counts_.check(e->edge));
    TESSERA_RETURN_IF_ERROR(checkSharpness(e->sharpness, e->edge.toString()));
    if (isBoundaryEdge(e->edge)) {
      return invalidArgument(e->edge.toString() + " lies on the boundary, which is always infinitely sharp");
    }
    return Status::ok();
  }
  if (const auto* t = std::get_if<InterpolationEdit>(&edit.change)) {
    if (options_.scheme != DocumentScheme::kLoop) {
      return invalidArgument(t->vertex.toString() +
                             ": interpolating vertices are defined for Loop documents only "
                             "(docs/INTERPOLATION.md); this document is catmull-clark");
    }
    TESSERA_RETURN_IF_ERROR(counts_.check(t->vertex));
    if (t->vertex.level() >= options_.maxLevel) {
      return invalidArgument(t->vertex.toString() +
                             ": an interpolating vertex shapes the next level (its ghost ring), "
                             "so it must lie above the document's deepest level " +
                             std::to_string(options_.maxLevel));
    }
    if (!t->interpolating) return Status::ok();
    TESSERA_RETURN_IF_ERROR(checkTension(t->tension, t->vertex.toString()));
    return checkFinite(t->tangent, t->vertex.toString() + " tangent");
  }
  const auto& v = std::get<VertexSharpnessEdit>(edit.change);
  TESSERA_RETURN_IF_ERROR(counts_.check(v.vertex));
  return checkSharpness(v.sharpness, v.vertex.toString());
}

Status Document::rebuildHierarchy() {
  TESSERA_ASSIGN_OR_RETURN(Level level0, buildLevel0(base_, options_.loop));
  return rebuildHierarchy(std::move(level0));
}

Status Document::rebuildHierarchy(Level level0) {
  TESSERA_ASSIGN_OR_RETURN(SparseHierarchy sparse,
                           SparseHierarchy::create(std::move(level0), basePoints_, options_.loop, counts_,
                                                   options_.uniformLevel, edits_));
  sparse_.emplace(std::move(sparse));
  return Status::ok();
}

void Document::reserve(const Edit& edit) {
  const DirtySet reserved = sparse_->reserve(edit, edits_);
  const int grown = reserved.grownFromLevel;
  if (grown >= 0) pendingGrowth_ = pendingGrowth_ < 0 ? grown : std::min(pendingGrowth_, grown);
  pendingLimits_.insert(pendingLimits_.end(), reserved.limits.begin(), reserved.limits.end());
}

Expected<EditId> Document::add(Edit edit) {
  TESSERA_RETURN_IF_ERROR(checkEdit(edit));
  TESSERA_RETURN_IF_ERROR(checkInterpolationConflicts(edit, edits_, sparse_->level(0).mesh, counts_));
  edit.id = EditId{nextEditId_};
  edit.active = true;
  append(std::move(edit));
  return edits_.back().id;
}

Status Document::replay(const Edit& edit) {
  if (edit.id.value != nextEditId_) {
    return invalidArgument(edit.id.toString() + ": replayed out of order (next is edit" +
                           std::to_string(nextEditId_) + ")");
  }
  TESSERA_RETURN_IF_ERROR(checkEdit(edit));
  append(edit);
  return Status::ok();
}

// A checked edit with the next id: the hierarchy grows for it, then takes
// it in incrementally.
void Document::append(Edit edit) {
  ++nextEditId_;
  reserve(edit);
  edits_.push_back(std::move(edit));
  cache_.reset();
  lastUpdate_ = sparse_->update(edits_.back(), edits_);
  lastUpdate_.grownFromLevel = std::exchange(pendingGrowth_, -1);
  addChangedLimits(pendingLimits_);
  pendingLimits_.clear();
}

void Document::addChangedLimits(std::span<const VertexId> limits) {
  if (limits.empty()) return;
  std::vector<VertexId>& all = lastUpdate_.limits;
  all.insert(all.end(), limits.begin(), limits.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
}

// The hierarchy grows first, so that the moved vertices have their rings.
// A move an interpolating vertex forbids is refused before that: growth for
// an edit marks edit nodes, which must come from edits the document holds.
Status Document::reserveVertices(std::span<const VertexId> vertices) {
  MoveEdit probe;
  for (VertexId id : vertices) probe.offsets.push_back({id, Vec3(0, 0, 0)});
  Edit edit{{}, true, std::move(probe)};
  TESSERA_RETURN_IF_ERROR(checkInterpolationConflicts(edit, edits_, sparse_->level(0).mesh, counts_));
  reserve(edit);
  return Status::ok();
}

// Needs reserveVertices(vertices) first.
Expected<MoveEdit> Document::offsetsFor(std::span<const VertexId> vertices, const Vec3& world) {
  MoveEdit move;
  for (VertexId id : vertices) move.offsets.push_back({id, Vec3(0, 0, 0)});
  for (VertexOffset& o : move.offsets) {
    TESSERA_ASSIGN_OR_RETURN(Index v, sparse_->completeVertex(o.vertex));
    // Frames come from the coarser prediction, as the evaluator applies them.
    o.localOffset = sparse_->frameOf(o.vertex.level(), v).toLocal(world);
  }
  return move;
}

Expected<EditId> Document::moveToLimit(std::span<const VertexId> vertices, const Vec3& target) {
  TESSERA_RETURN_IF_ERROR(checkVertices(vertices));
  TESSERA_RETURN_IF_ERROR(checkFinite(target, "target position"));
  const int level = vertices[0].level();
  TESSERA_RETURN_IF_ERROR(reserveVertices(vertices));
  TESSERA_ASSIGN_OR_RETURN(Index v, sparse_->completeVertex(vertices[0]));
  if (!sparse_->hasLimits(level) && level < counts_.maxLevel()) {
    // Its limit is its child's (SparseHierarchy::solveControlPoint): the
    // hierarchy grows the children of the faces around it, as a view's
    // growth would.
    std::vector<FaceId> around;
    for (Index f : sparse_->level(level).mesh.ringFacesOf(v)) {
      if (f < 0) continue;
      const FaceId face(level, sparse_->level(level).faceIds[f]);
      for (int k = 0; k < counts_.faceSize(face); ++k) around.push_back(counts_.childFace(face, k));
    }
    sparse_->reserveFaces(around, edits_);
  }
  const auto points = sparse_->points(level);
  // An interpolating vertex's limit is its control point (ghost_ring.h).
  const bool interpolates = interpolationOf(vertices[0]).has_value() &&
                            ghostRuleOf(sparse_->level(level).mesh, v) != GhostRule::kNone;
  const Vec3 solved = interpolates ? target : sparse_->solveControlPoint(level, v, target);
  TESSERA_ASSIGN_OR_RETURN(MoveEdit move, offsetsFor(vertices, solved - points[v]));
  return add(Edit{{}, true, std::move(move)});
}

Expected<EditId> Document::moveBy(std::span<const VertexId> vertices, const Vec3& displacement) {
  TESSERA_RETURN_IF_ERROR(checkVertices(vertices));
  TESSERA_RETURN_IF_ERROR(checkFinite(displacement, "displacement"));
  TESSERA_RETURN_IF_ERROR(reserveVertices(vertices));
  TESSERA_ASSIGN_OR_RETURN(MoveEdit move, offsetsFor(vertices, displacement));
  return add(Edit{{}, true, std::move(move)});
}

Expected<EditId> Document::setEdgeSharpness(EdgeId edge, float sharpness) {
  return add(Edit{{}, true, EdgeSharpnessEdit{edge, sharpness}});
}

Expected<EditId> Document::setVertexSharpness(VertexId vertex, float sharpness) {
  return add(Edit{{}, true, VertexSharpnessEdit{vertex, sharpness}});
}

Status Document::checkGhostRule(const InterpolationEdit& tag) {
  if (!tag.interpolating) return Status::ok();
  // The rule that decides the ghost ring is the vertex's at its level now.
  // The hierarchy grows to hold its ring as a tessellation's request would:
  // a refused tag must leave no edit node behind (what the document shows
  // may depend only on the edits it holds).
  if (tag.vertex.level() > 0) {
    const FaceId around = incidentFace(sparse_->level(0).mesh, counts_, tag.vertex);
    sparse_->reserveFaces(std::span(&around, 1), edits_);
  }
  TESSERA_ASSIGN_OR_RETURN(Index v, sparse_->completeVertex(tag.vertex));
  std::string why;
  const GhostRule rule = ghostRuleOf(sparse_->level(tag.vertex.level()).mesh, v, &why);
  if (rule == GhostRule::kNone) return invalidArgument(tag.vertex.toString() + " cannot interpolate: " + why);
  if (rule == GhostRule::kInterior && tag.tangent.norm() > 0) {
    return invalidArgument(tag.vertex.toString() +
                           ": a tangent applies only to boundary and crease vertices");
  }
  return Status::ok();
}

// Taking back an interpolation edit hands the vertex to the one before it,
// which may make it interpolate again: that must still be allowed.
Status Document::checkUncovered(const Edit& leaving) {
  const auto* tag = std::get_if<InterpolationEdit>(&leaving.change);
  if (tag == nullptr || !leaving.active) return Status::ok();
  std::vector<Edit> after;
  for (const Edit& e : edits_) {
    if (&e != &leaving) after.push_back(e);
  }
  const Edit* deciding = decidingInterpolationEdit(after, tag->vertex);
  if (deciding == nullptr || !std::get<InterpolationEdit>(deciding->change).interpolating)
    return Status::ok();
  const std::string back =
      "it would make " + tag->vertex.toString() + " interpolate again (" + deciding->id.toString() + ")";
  TESSERA_RETURN_IF_ERROR(
      checkInterpolationConflicts(*deciding, after, sparse_->level(0).mesh, counts_).withContext(back));
  return checkGhostRule(std::get<InterpolationEdit>(deciding->change)).withContext(back);
}

Expected<EditId> Document::setInterpolation(VertexId vertex, bool interpolating, double tension,
                                            const Vec3& tangent) {
  Edit edit{{}, true, InterpolationEdit{vertex, interpolating, tension, tangent}};
  TESSERA_RETURN_IF_ERROR(checkEdit(edit));
  TESSERA_RETURN_IF_ERROR(checkGhostRule(std::get<InterpolationEdit>(edit.change)));
  return add(std::move(edit));
}

std::optional<InterpolationTag> Document::interpolationOf(VertexId vertex) const {
  const Edit* deciding = decidingInterpolationEdit(edits_, vertex);
  if (deciding == nullptr) return std::nullopt;
  const auto& t = std::get<InterpolationEdit>(deciding->change);
  return t.interpolating ? std::optional<InterpolationTag>(InterpolationTag{t.tension, t.tangent})
                         : std::nullopt;
}

Expected<EdgeId> Document::edgeBetween(VertexId a, VertexId b) const {
  return tessera::edgeBetween(sparse_->level(0).mesh, counts_, a, b);
}

Edit* Document::find(EditId id) {
  auto it = std::find_if(edits_.begin(), edits_.end(), [&](const Edit& e) { return e.id == id; });
  return it == edits_.end() ? nullptr : &*it;
}

Status Document::setActive(EditId id, bool active, bool checked) {
  Edit* edit = find(id);
  if (edit == nullptr) return notFound(id.toString() + ": no such edit");
  if (edit->active == active) {
    return invalidArgument(id.toString() + (active ? " is not undone" : " is already undone"));
  }
  if (active && checked) {
    TESSERA_RETURN_IF_ERROR(checkInterpolationConflicts(*edit, edits_, sparse_->level(0).mesh, counts_)
                                .withContext("redo " + id.toString()));
    if (const auto* tag = std::get_if<InterpolationEdit>(&edit->change)) {
      TESSERA_RETURN_IF_ERROR(checkGhostRule(*tag).withContext("redo " + id.toString()));
    }
  }
  if (!active) TESSERA_RETURN_IF_ERROR(checkUncovered(*edit).withContext("undo " + id.toString()));
  edit->active = active;
  cache_.reset();
  lastUpdate_ = sparse_->update(*edit, edits_);
  return Status::ok();
}

Status Document::retractLast() {
  if (edits_.empty() || edits_.back().id.value + 1 != nextEditId_)
    return invalidArgument("no edit to retract");
  const Edit removed = edits_.back();
  edits_.pop_back();
  --nextEditId_;
  cache_.reset();
  lastUpdate_ = sparse_->update(removed, edits_);
  forgetRemovedEditNodes();
  return Status::ok();
}

// The removed edit's edit nodes go with it (sparse_hierarchy.h): what the
// document shows is what a document created without it shows.
void Document::forgetRemovedEditNodes() {
  addChangedLimits(sparse_->forgetEditNodes(edits_).limits);
}

Status Document::undo(EditId id) {
  return setActive(id, false);
}
Status Document::redo(EditId id) {
  return setActive(id, true);
}
Status Document::reinstate(EditId id) {
  return setActive(id, true, false);
}

Status Document::remove(EditId id) {
  Edit* edit = find(id);
  if (edit == nullptr) return notFound(id.toString() + ": no such edit");
  TESSERA_RETURN_IF_ERROR(checkUncovered(*edit).withContext("remove " + id.toString()));
  const Edit removed = *edit;
  edits_.erase(edits_.begin() + (edit - edits_.data()));
  cache_.reset();
  lastUpdate_ = sparse_->update(removed, edits_);
  forgetRemovedEditNodes();
  return Status::ok();
}

Expected<std::shared_ptr<const Evaluation>> Document::evaluate(int level) const {
  if (level < 0 || level > options_.maxLevel) {
    return invalidArgument("level " + std::to_string(level) + " is outside 0.." +
                           std::to_string(options_.maxLevel));
  }
  if (counts_.faces(level) > kMaxEvaluatedFaces) {
    return invalidArgument("level " + std::to_string(level) + " has " + std::to_string(counts_.faces(level)) +
                           " faces, above the evaluation limit of " + std::to_string(kMaxEvaluatedFaces));
  }
  if (cache_ && static_cast<int>(cache_->levels.size()) > level) return cache_;
  TESSERA_ASSIGN_OR_RETURN(
      Evaluation eval,
      options_.scheme == DocumentScheme::kLoop
          ? evaluateDocument(std::get<BaseTopology>(base_), basePoints_, options_.loop, edits_, level)
          : evaluateCatmarkDocument(std::get<PolyTopology>(base_), basePoints_, options_.loop, edits_,
                                    level));
  cache_ = std::make_shared<const Evaluation>(std::move(eval));
  return cache_;
}

Expected<SurfaceMesh> Document::surface(int level, SurfaceKind kind) const {
  TESSERA_ASSIGN_OR_RETURN(auto eval, evaluate(level));
  const Level& topology = eval->levels[level];
  if (options_.scheme == DocumentScheme::kCatmullClark) {
    if (kind == SurfaceKind::kControl) return polygonControlSurfaceOf(topology, eval->points[level]);
    auto limit = catmarkLimitSurfaceOf(topology, options_.loop, eval->points[level]);
    if (!limit.isOk()) return limit.status().withContext("level " + std::to_string(level));
    return limit;
  }
  if (kind == SurfaceKind::kControl) return controlSurfaceOf(eval->levels[level], eval->points[level]);
  return limitSurfaceOf(eval->levels[level], eval->points[level], options_.loop.creaseMethod);
}

}  // namespace tessera

#include "core/tessellation/adaptive_cut.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/loop/limit.h"

namespace tessera {

namespace {

// The limit normal of vertex v on the side of face f: a crease or corner
// has one per sector between sharp edges (limit.h).
Vec3 sideNormal(const SparseHierarchy& h, int l, Index v, Index f) {
  const Level& m = h.level(l).mesh;
  // Catmull-Clark's Limit() masks give one normal per vertex
  // (core/catmark/limit.h): a crease counts as a disagreement there.
  if (isSmoothLike(m.vertexRules[v]) || h.quads()) return h.limitNormal(l, v);
  auto faces = m.ringFacesOf(v);
  const int n = static_cast<int>(faces.size());
  const int k = static_cast<int>(std::find(faces.begin(), faces.end(), f) - faces.begin());
  const SparseFarRings far = h.farRings(l);
  for (const LimitSector& sector : otherLimitSectors(m, v, h.points(l), h.creaseMethod(), &far)) {
    if ((k - sector.firstFace + n) % n < sector.faceCount) return sector.normal;
  }
  return h.limitNormal(l, v);
}

double cosAngle(const Vec3& a, const Vec3& b) {
  const double la = a.norm(), lb = b.norm();
  return la > 0 && lb > 0 ? dot(a, b) / (la * lb) : 1.0;
}

// The direction of the crease through edge a->b at a: the limit tangent
// along the crease at a crease vertex, the chord elsewhere (a corner has no
// single tangent), oriented from a towards b.
Vec3 creaseTangent(const SparseHierarchy& h, int l, Index a, Index b) {
  const Vec3 chord = h.limitPosition(l, b) - h.limitPosition(l, a);
  if (h.level(l).mesh.vertexRules[a] != VertexRule::kCrease) return chord;
  const Vec3 t = h.limitFrameOf(l, a).tangent1;
  return dot(t, chord) < 0 ? -1.0 * t : t;
}

}  // namespace

Expected<AdaptiveCut> AdaptiveCut::build(Document& doc, const LodProfile& profile) {
  TESSERA_RETURN_IF_ERROR(profile.check());
  AdaptiveCut cut(profile);
  cut.profile_.maxLevel = std::min(profile.maxLevel, doc.options().maxLevel);
  cut.profile_.baseLevel = std::min(profile.baseLevel, cut.profile_.maxLevel);
  cut.cosThreshold_ = std::cos(profile.angleThresholdDegrees * std::numbers::pi / 180.0);
  doc.holdWhole(cut.profile_.baseLevel);
  // Top-down: a level's decisions need the nodes of that level, which the
  // decisions above it create. Growth adds faces to the levels below the
  // first whose selection changed, whose decisions are then sized for
  // fewer faces; restart from there.
  if (cut.profile_.fidelity) cut.markEditedVertices(doc);
  for (int l = 0; l < doc.hierarchy().numLevels(); ++l) {
    const SparseHierarchy& h = doc.hierarchy();
    cut.split_.resize(h.numLevels());
    cut.split_[l].assign(h.level(l).mesh.numFaces(), 0);
    std::vector<FaceId> requests;
    for (Index f = 0; f < h.level(l).mesh.numFaces(); ++f) {
      if (!cut.isNode(h, l, f) || !cut.wantsSplit(h, l, f)) continue;
      cut.split_[l][f] = 1;
      if (!h.isNodeWithChildren(l, f))
        requests.push_back(doc.counts().childFace(FaceId(l, h.level(l).faceIds[f]), 0));
    }
    if (requests.empty()) continue;
    const int first = doc.refineHierarchy(requests);
    if (first >= 0 && first < l) l = -1;  // local indices above changed: start over
  }
  const SparseHierarchy& h = doc.hierarchy();
  cut.split_.resize(h.numLevels());
  cut.generations_.clear();
  for (int l = 0; l < h.numLevels(); ++l) cut.generations_.push_back(h.generation(l));
  return cut;
}

// By canonical id, so the set does not depend on the hierarchy's local
// indices and costs what the edit list costs, not what the levels hold.
void AdaptiveCut::markEditedVertices(const Document& doc) {
  editedVertices_.clear();
  for (const Edit& edit : doc.edits()) {
    const auto* move = std::get_if<MoveEdit>(&edit.change);
    if (move == nullptr) continue;
    for (const VertexOffset& o : move->offsets) editedVertices_.push_back(o.vertex.packed());
  }
  std::sort(editedVertices_.begin(), editedVertices_.end());
}

bool AdaptiveCut::isCurrent(const SparseHierarchy& h) const {
  if (h.numLevels() != numLevels()) return false;
  for (int l = 0; l < h.numLevels(); ++l) {
    if (h.generation(l) != generations_[l]) return false;
  }
  return true;
}

bool AdaptiveCut::wantsSplit(const SparseHierarchy& h, int l, Index f) const {
  if (l >= profile_.maxLevel) return false;
  if (l < profile_.baseLevel || h.isEditNode(l, f)) return true;
  // A level without limits (a Catmull-Clark base of other polygons than
  // quads) is never shown.
  if (!h.hasLimits(l)) return true;
  if (profile_.fidelity && aroundEditedVertex(h, l, f)) return true;
  return normalsDisagree(h, l, f) || creaseTangentsDisagree(h, l, f);
}

bool AdaptiveCut::aroundEditedVertex(const SparseHierarchy& h, int l, Index f) const {
  for (Index v : h.level(l).mesh.faceVerticesOf(f)) {
    const uint64_t id = VertexId(l, h.level(l).vertexIds[v]).packed();
    if (std::binary_search(editedVertices_.begin(), editedVertices_.end(), id)) return true;
  }
  return false;
}

bool AdaptiveCut::normalsDisagree(const SparseHierarchy& h, int l, Index f) const {
  const auto fv = h.level(l).mesh.faceVerticesOf(f);
  const size_t n = fv.size();
  for (size_t j = 0; j < n; ++j) {
    if (cosAngle(sideNormal(h, l, fv[j], f), sideNormal(h, l, fv[(j + 1) % n], f)) < cosThreshold_)
      return true;
  }
  return false;
}

bool AdaptiveCut::creaseTangentsDisagree(const SparseHierarchy& h, int l, Index f) const {
  const Level& m = h.level(l).mesh;
  const auto fv = m.faceVerticesOf(f);
  const auto fe = m.faceEdgesOf(f);
  const size_t n = fv.size();
  for (size_t j = 0; j < n; ++j) {
    if (!isSharp(m.edgeSharpness[fe[j]])) continue;
    const Index a = fv[j], b = fv[(j + 1) % n];
    const Vec3 ta = creaseTangent(h, l, a, b);
    const Vec3 tb = -1.0 * creaseTangent(h, l, b, a);
    if (cosAngle(ta, tb) < cosThreshold_) return true;
  }
  return false;
}

void AdaptiveCut::clearSubtree(const SparseHierarchy& h, int l, Index f) {
  if (!split_[l][f]) return;
  split_[l][f] = 0;
  const Index first = h.level(l).firstChildFace[f];
  if (first < 0 || l + 1 >= numLevels()) return;
  const int children = h.numChildFaces(l, f);
  for (int k = 0; k < children; ++k) clearSubtree(h, l + 1, first + k);
}

bool AdaptiveCut::decideSubtree(Document& doc, int l, Index f, std::vector<std::pair<int, Index>>& flipped) {
  const SparseHierarchy& h = doc.hierarchy();
  if (!h.isNodeWithChildren(l, f)) return false;  // needs growth
  const Index first = h.level(l).firstChildFace[f];
  const int children = h.numChildFaces(l, f);
  for (int k = 0; k < children; ++k) {
    const Index c = first + k;
    if (!wantsSplit(h, l + 1, c)) continue;
    split_[l + 1][c] = 1;
    flipped.emplace_back(l + 1, c);
    if (!decideSubtree(doc, l + 1, c, flipped)) return false;
  }
  return true;
}

std::optional<std::vector<std::pair<int, Index>>> AdaptiveCut::redecide(Document& doc,
                                                                        std::span<const VertexId> limits) {
  std::vector<std::pair<int, Index>> flipped;
  const SparseHierarchy& h = doc.hierarchy();
  if (profile_.fidelity) markEditedVertices(doc);
  // The faces around the changed limits, each once, by level and index. A
  // level-0 edit on a surface held to level 4 changes thousands of limits:
  // marking faces costs what sorting every (level, face) pair did not.
  std::vector<std::vector<Index>> byLevel(static_cast<size_t>(numLevels()));
  if (faceMarks_.size() < byLevel.size()) faceMarks_.resize(byLevel.size());
  for (VertexId id : limits) {
    const int l = id.level();
    if (l >= numLevels()) continue;
    const Index v = h.level(l).findVertex(id.index());
    std::vector<uint8_t>& marks = faceMarks_[l];
    if (marks.size() < static_cast<size_t>(h.level(l).mesh.numFaces()))
      marks.resize(h.level(l).mesh.numFaces(), 0);
    for (Index f : h.level(l).mesh.ringFacesOf(v)) {
      if (f < 0 || marks[f]) continue;
      marks[f] = 1;
      byLevel[l].push_back(f);
    }
  }
  std::vector<std::pair<int, Index>> faces;
  for (int l = 0; l < numLevels(); ++l) {
    for (Index f : byLevel[l]) faceMarks_[l][f] = 0;
    std::sort(byLevel[l].begin(), byLevel[l].end());
    for (Index f : byLevel[l]) faces.emplace_back(l, f);
  }
  // Coarser levels first: a flip there decides (or clears) the finer ones.
  for (auto [l, f] : faces) {
    if (!isNode(h, l, f)) continue;
    const bool want = wantsSplit(h, l, f);
    if (want == isSplit(l, f)) continue;
    flipped.emplace_back(l, f);
    if (!want) {
      clearSubtree(h, l, f);
      continue;
    }
    split_[l][f] = 1;
    if (!decideSubtree(doc, l, f, flipped)) return std::nullopt;
  }
  return flipped;
}

}  // namespace tessera

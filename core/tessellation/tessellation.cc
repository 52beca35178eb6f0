#include "core/tessellation/tessellation.h"

#include <algorithm>
#include <cstring>

#include <optional>
#include <tuple>
#include <unordered_map>

#include "core/hierarchy/incidence.h"
#include "core/loop/limit.h"
#include "core/tessellation/leaf_triangulation.h"
#include "core/tessellation/region_merge.h"

namespace tessera {

namespace {

// Regions are cut nodes this many levels above the profile's deepest, so a
// region holds at most 4^5 = 1,024 leaf triangles before fans.
constexpr int kRegionDepth = 5;

// Whether the limit mask of a complete vertex at this level may differ
// from its true limit: a semi-sharp edge or vertex sharpness still acts on
// it (its own sharpness or one of its edges' is finite and not yet decayed:
// the mask counts it as sharp, ARCHITECTURE "Semi-sharp limits"), or it is
// a dart, whose mask is the smooth one (limit.cc, as OpenSubdiv's) although
// its sharp edge refines by the crease rule: a dart's mask only converges
// towards its limit level by level.
bool maskInexact(const Level& m, Index v) {
  if (m.vertexRules[v] == VertexRule::kDart || isSemiSharp(m.vertexSharpness[v])) return true;
  for (Index e : m.ringEdgesOf(v)) {
    if (isSemiSharp(m.edgeSharpness[e])) return true;
  }
  return false;
}

// Where a displayed vertex's limit comes from, a function of the document
// alone (the rule and its reasons are in tessellation.h): from the level
// the vertex was born at, down to the deepest level whose active edits
// reach its limit, then further while its limit mask is inexact (semi-sharp
// features, darts), up to the document's deepest level. Vertex children keep
// their canonical index, so whichever leaf reaches the vertex (any `v` of
// it) gives the same answer, and regions sharing a border agree bit for
// bit. When the hierarchy does not hold the vertex's ring at the chosen
// level, a face to grow it there is appended to `growth` and nothing is
// returned.
std::optional<VertexRef> limitSource(const SparseHierarchy& h, const LevelCounts& counts, VertexRef v,
                                     std::vector<FaceId>& growth) {
  while (v.level > 0 && v.local < h.level(v.level).numVertexChildren) {
    v = {v.level - 1, h.level(v.level).origin[v.local]};
  }
  VertexRef at = v;
  for (VertexRef w = v;;) {
    if (h.isReachedByEdit(w.level, w.local)) at = w;
    if (w.level + 1 >= h.numLevels()) break;
    const Index child = h.level(w.level).childOfVertex[w.local];
    if (child < 0) break;
    w = {w.level + 1, child};
  }
  auto held = [&](int l, Index local) { return local >= 0 && h.level(l).isComplete(local); };
  auto grow = [&](int l, uint64_t canonical) {
    growth.push_back(incidentFace(h.level(0).mesh, counts, VertexId(l, canonical)));
    return std::nullopt;
  };
  if (!held(at.level, at.local)) return grow(at.level, h.level(at.level).vertexIds[at.local]);
  while (at.level < counts.maxLevel() && maskInexact(h.level(at.level).mesh, at.local)) {
    const Index child = at.level + 1 < h.numLevels() ? h.level(at.level).childOfVertex[at.local] : kNoIndex;
    if (!held(at.level + 1, child)) return grow(at.level + 1, h.level(at.level).vertexIds[at.local]);
    at = {at.level + 1, child};
  }
  return at;
}

// The limit normal of side `side` > 0 of a crease or corner vertex
// (limitSideOfRingFace's numbering; side 0's is its limit normal).
Vec3 sideNormal(const SparseHierarchy& h, VertexRef v, int side) {
  return otherLimitSectors(h.level(v.level).mesh, v.local, h.points(v.level), h.creaseMethod())[side - 1]
      .normal;
}

// The side of a displayed vertex (`at`: its limit's level and index) that
// a triangle inside leaf face f of level l lies on, chosen topologically:
// the sector, at the limit's level, of the ring face that descends from f
// or that f descends from. Those ring faces are one contiguous run of the
// ring (a single face, for a corner of f: its corner child and that one's,
// and so on); a tag set below f's level can put a sharp edge among them,
// so the run's first face (counter-clockwise) decides. Sides then follow
// the leaves around the vertex in ring order, each side's triangles form
// one fan, and every leaf or region that reaches the vertex agrees -- where
// a flat triangle's normal against the sectors' normals need not: at the
// limit's level, deeper than the display, a semi-sharp edge may have
// decayed and merged two displayed sectors into one whose normal is far
// from (even perpendicular to) the faces in it.
int sideOf(const SparseHierarchy& h, VertexRef at, int l, Index f) {
  const SparseLevel& level = h.level(at.level);
  if (isSmoothLike(level.mesh.vertexRules[at.local])) return 0;
  const uint64_t leaf = h.level(l).faceIds[f];
  auto ring = level.mesh.ringFacesOf(at.local);
  const int n = static_cast<int>(ring.size());
  auto inLeaf = [&](int k) {
    if (ring[k] < 0) return false;
    const uint64_t g = level.faceIds[ring[k]];
    return at.level >= l ? (g >> (2 * (at.level - l))) == leaf : (leaf >> (2 * (l - at.level))) == g;
  };
  int k = 0;
  while (k < n && !inLeaf(k)) ++k;
  if (k == n) return 0;  // not reached: the leaf holds the vertex
  for (int steps = 1; steps < n && inLeaf((k + n - 1) % n); ++steps) k = (k + n - 1) % n;
  return limitSideOfRingFace(level.mesh, at.local, k);
}

// The same triangles over the same vertex ids in the same order: Draco
// decodes both in the same order (region_codec.h, "Why layouts").
bool sameLayout(const RegionMesh& a, const RegionMesh& b) {
  return a.triangles == b.triangles && a.vertexIds == b.vertexIds;
}

bool sameMesh(const RegionMesh& a, const RegionMesh& b) {
  auto sameVec = [](const std::vector<Vec3>& x, const std::vector<Vec3>& y) {
    return x.size() == y.size() &&
           (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(Vec3)) == 0);
  };
  return sameLayout(a, b) && sameVec(a.positions, b.positions) && sameVec(a.normals, b.normals);
}

}  // namespace

Expected<Tessellation> Tessellation::build(Document& doc, const LodProfile& profile) {
  return build(doc, profile, nullptr);
}

Expected<Tessellation> Tessellation::build(Document& doc, const LodProfile& profile,
                                           std::shared_ptr<const BaseFaceClusters> clusters) {
  // The base level is held whole, so its face count is a lower bound on the
  // triangles: refuse before growing the hierarchy to it.
  if (profile.baseLevel >= 0 && profile.baseLevel <= doc.counts().maxLevel() &&
      static_cast<int64_t>(doc.counts().faces(profile.baseLevel)) > profile.triangleBudget) {
    return invalidArgument("LOD profile (" + profile.describe() + ")" + " needs at least " +
                           std::to_string(doc.counts().faces(profile.baseLevel)) +
                           " triangles (its base level " + std::to_string(profile.baseLevel) +
                           "), above its budget of " + std::to_string(profile.triangleBudget));
  }
  // Growing the hierarchy for the limits' levels rebuilds levels (new local
  // indices), so the cut is made again over the grown hierarchy; its
  // decisions do not change, and the second round needs no growth.
  for (int round = 0;; ++round) {
    TESSERA_ASSIGN_OR_RETURN(AdaptiveCut cut, AdaptiveCut::build(doc, profile));
    const int regionLevel = std::max(0, cut.profile().maxLevel - kRegionDepth);
    Tessellation tessellation(std::move(cut), regionLevel, doc.counts());
    const SparseHierarchy& h = doc.hierarchy();
    std::vector<uint64_t> ids;
    for (Index f = 0; f < h.level(0).mesh.numFaces(); ++f) tessellation.regionsUnder(h, 0, f, ids);
    std::vector<FaceId> growth;
    for (uint64_t id : ids) {
      RegionMesh& mesh = tessellation.fine_[id] = tessellation.buildRegion(h, FaceId::fromPacked(id), growth);
      tessellation.triangles_ += static_cast<int64_t>(mesh.triangles.size());
    }
    if (growth.empty()) {
      TESSERA_RETURN_IF_ERROR(tessellation.checkBudget());
      const int maxLevel = tessellation.profile().maxLevel;
      if (maxLevel <= kMaxGroupedLevel) {
        const int size = 1 << (2 * (kGroupDepth - maxLevel));
        if (!clusters || clusters->size() != size)
          clusters =
              std::make_shared<const BaseFaceClusters>(BaseFaceClusters::build(doc.baseTopology(), size));
        tessellation.clusters_ = clusters;
        for (uint32_t c = 0; c < static_cast<uint32_t>(clusters->numClusters()); ++c)
          tessellation.groups_[FaceId(0, clusters->seedOf(c)).packed()] = tessellation.buildGroup(c);
      }
      return tessellation;
    }
    if (round > kMaxDocumentLevel) {
      return internalError("LOD profile (" + profile.describe() + ")" +
                           ": the hierarchy does not hold the limits' rings after " + std::to_string(round) +
                           " growths");
    }
    doc.refineHierarchy(growth);
  }
}

Status Tessellation::checkBudget() const {
  const int64_t triangles = numTriangles();
  if (triangles > profile().triangleBudget) {
    return invalidArgument("LOD profile (" + profile().describe() + ")" + " needs " +
                           std::to_string(triangles) + " triangles, above its budget of " +
                           std::to_string(profile().triangleBudget));
  }
  return Status::ok();
}

void Tessellation::regionsUnder(const SparseHierarchy& h, int l, Index f, std::vector<uint64_t>& out) const {
  if (l == regionLevel_ || !cut_.isSplit(l, f)) {
    out.push_back(FaceId(l, h.level(l).faceIds[f]).packed());
    return;
  }
  const Index first = h.level(l).firstChildFace[f];
  for (int k = 0; k < 4; ++k) regionsUnder(h, l + 1, first + k, out);
}

RegionMesh Tessellation::buildRegion(const SparseHierarchy& h, FaceId region,
                                     std::vector<FaceId>& growth) const {
  std::vector<RefTriangle> triangles;
  std::vector<VertexRef> leaves;  // per triangle, its leaf (level, face)
  std::vector<VertexRef> stack{{region.level(), h.level(region.level()).findFace(region.index())}};
  while (!stack.empty()) {
    const VertexRef node = stack.back();  // (level, face)
    stack.pop_back();
    if (!cut_.isSplit(node.level, node.local)) {
      triangulateLeaf(h, cut_, node.level, node.local, triangles);
      leaves.resize(triangles.size(), node);
      continue;
    }
    const Index first = h.level(node.level).firstChildFace[node.local];
    for (int k = 3; k >= 0; --k) stack.push_back({node.level + 1, first + k});
  }
  RegionMesh mesh;
  std::unordered_map<uint64_t, int> index;  // (canonical vertex, side) -> region vertex
  for (size_t i = 0; i < triangles.size(); ++i) {
    const RefTriangle& t = triangles[i];
    VertexRef at[3];
    bool held = true;
    for (int k = 0; k < 3; ++k) {
      const std::optional<VertexRef> source = limitSource(h, counts_, t[k], growth);
      held = held && source.has_value();
      if (source) at[k] = *source;
    }
    if (!held) continue;  // the caller grows the hierarchy and starts again
    std::array<int, 3> tri;
    for (int k = 0; k < 3; ++k) {
      const int side = sideOf(h, at[k], leaves[i].level, leaves[i].local);
      const uint64_t canonical = h.level(at[k].level).vertexIds[at[k].local];
      const uint64_t key = canonical * 64 + static_cast<uint64_t>(side);
      auto [it, fresh] = index.emplace(key, static_cast<int>(mesh.positions.size()));
      if (fresh) {
        const VertexId id(counts_.birthLevel(VertexId(at[k].level, canonical)), canonical);
        mesh.positions.push_back(h.limitPosition(at[k].level, at[k].local));
        mesh.normals.push_back(side == 0 ? h.limitNormal(at[k].level, at[k].local)
                                         : sideNormal(h, at[k], side));
        mesh.vertexIds.push_back(id.packed());
      }
      tri[k] = it->second;
    }
    mesh.triangles.push_back(tri);
  }
  return mesh;
}

SurfaceMesh Tessellation::surface() const {
  return mergeRegions(fine_);
}

RegionMesh Tessellation::buildGroup(uint32_t cluster) const {
  // A vertex shared by two member faces is one vertex of the group: its id
  // and normal (creases keep a copy per side) are the same in both, and so
  // is its position, bit for bit (the rule in this file's header).
  RegionMesh group;
  std::map<std::tuple<uint64_t, double, double, double>, int> index;
  for (int f : clusters_->facesOf(cluster)) {
    const RegionMesh& member = fine_.at(FaceId(0, static_cast<uint64_t>(f)).packed());
    std::vector<int> map(member.positions.size());
    for (size_t v = 0; v < member.positions.size(); ++v) {
      const Vec3& n = member.normals[v];
      auto [it, fresh] = index.emplace(std::tuple{member.vertexIds[v], n[0], n[1], n[2]},
                                       static_cast<int>(group.positions.size()));
      if (fresh) {
        group.positions.push_back(member.positions[v]);
        group.normals.push_back(n);
        group.vertexIds.push_back(member.vertexIds[v]);
      }
      map[v] = it->second;
    }
    for (const auto& t : member.triangles) group.triangles.push_back({map[t[0]], map[t[1]], map[t[2]]});
  }
  return group;
}

Tessellation::Changes Tessellation::regroup(const Changes& fine) {
  std::vector<uint32_t> touched;
  for (const auto* ids : {&fine.changed, &fine.removed}) {
    for (uint64_t id : *ids) {
      const FaceId face = FaceId::fromPacked(id);
      touched.push_back(clusters_->clusterOf(static_cast<int>(face.index() >> (2 * face.level()))));
    }
  }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  Changes changes;
  changes.rebuilt = fine.rebuilt;
  for (uint32_t c : touched) {
    const uint64_t id = FaceId(0, clusters_->seedOf(c)).packed();
    RegionMesh mesh = buildGroup(c);
    RegionMesh& old = groups_.at(id);
    if (sameMesh(old, mesh)) continue;
    if (!sameLayout(old, mesh)) changes.relaid.push_back(id);
    changes.changed.push_back(id);
    old = std::move(mesh);
  }
  std::sort(changes.changed.begin(), changes.changed.end());
  std::sort(changes.relaid.begin(), changes.relaid.end());
  return changes;
}

Expected<Tessellation::Changes> Tessellation::rebuildAll(Document& doc) {
  TESSERA_ASSIGN_OR_RETURN(Tessellation fresh, build(doc, profile(), clusters_));
  Changes changes;
  changes.rebuilt = true;
  for (const auto& [id, mesh] : fresh.regions()) {
    auto old = regions().find(id);
    if (old == regions().end() || !sameMesh(old->second, mesh)) changes.changed.push_back(id);
    if (old == regions().end() || !sameLayout(old->second, mesh)) changes.relaid.push_back(id);
  }
  for (const auto& [id, mesh] : regions()) {
    if (fresh.regions().count(id) == 0) changes.removed.push_back(id);
  }
  *this = std::move(fresh);
  return changes;
}

Expected<Tessellation::Changes> Tessellation::update(Document& doc, std::span<const VertexId> changedLimits) {
  if (!cut_.isCurrent(doc.hierarchy())) return rebuildAll(doc);
  auto flipped = cut_.redecide(doc, changedLimits);
  if (!flipped) return rebuildAll(doc);
  const SparseHierarchy& h = doc.hierarchy();

  // The area whose triangles may differ: the faces around every vertex
  // whose limit changed (every triangle using it lies in them) and around
  // the corners of every node whose decision flipped (its neighbours' fans).
  // Below the region level only the ancestor there matters (regions and
  // their cut nodes all lie at or above it), so areas collapse onto it.
  std::vector<std::pair<int, uint64_t>> areas;
  auto addAround = [&](int l, Index v) {
    for (Index f : h.level(l).mesh.ringFacesOf(v)) {
      if (f < 0) continue;
      const uint64_t canonical = h.level(l).faceIds[f];
      if (l <= regionLevel_) {
        areas.emplace_back(l, canonical);
      } else {
        areas.emplace_back(regionLevel_, canonical >> (2 * (l - regionLevel_)));
      }
    }
  };
  for (VertexId id : changedLimits) addAround(id.level(), h.level(id.level()).findVertex(id.index()));
  for (auto [l, f] : *flipped) {
    for (Index v : h.level(l).mesh.triangleVertices(f)) addAround(l, v);
  }
  std::sort(areas.begin(), areas.end());
  areas.erase(std::unique(areas.begin(), areas.end()), areas.end());

  std::vector<uint64_t> candidates, gone;
  for (auto [l, canonical] : areas) {
    // New regions overlapping the area: walk down its ancestors in the cut.
    for (int j = 0; j <= l; ++j) {
      const uint64_t a = canonical >> (2 * (l - j));
      if (j == regionLevel_) {
        candidates.push_back(FaceId(j, a).packed());
        break;
      }
      const Index local = h.level(j).findFace(a);
      if (!cut_.isSplit(j, local)) {
        candidates.push_back(FaceId(j, a).packed());
        break;
      }
      if (j == l) regionsUnder(h, l, local, candidates);
    }
    // Old regions overlapping it: an ancestor, or descendants down to the
    // region level.
    for (int j = 0; j <= l; ++j) {
      const uint64_t id = FaceId(j, canonical >> (2 * (l - j))).packed();
      if (fine_.count(id)) gone.push_back(id);
    }
    for (int j = l + 1; j <= regionLevel_; ++j) {
      const int shift = 2 * (j - l);
      auto it = fine_.lower_bound(FaceId(j, canonical << shift).packed());
      const auto end = fine_.lower_bound(FaceId(j, (canonical + 1) << shift).packed());
      for (; it != end; ++it) gone.push_back(it->first);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  std::sort(gone.begin(), gone.end());
  gone.erase(std::unique(gone.begin(), gone.end()), gone.end());

  // Every candidate is built before any is stored: when a limit needs a
  // level the hierarchy does not hold, it grows and everything is rebuilt
  // (and diffed against the regions as they were).
  std::vector<FaceId> growth;
  std::vector<RegionMesh> meshes;
  for (uint64_t id : candidates) meshes.push_back(buildRegion(h, FaceId::fromPacked(id), growth));
  if (!growth.empty()) {
    doc.refineHierarchy(growth);
    return rebuildAll(doc);
  }
  Changes changes;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const uint64_t id = candidates[i];
    RegionMesh& mesh = meshes[i];
    auto old = fine_.find(id);
    if (old != fine_.end() && sameMesh(old->second, mesh)) continue;
    triangles_ += static_cast<int64_t>(mesh.triangles.size());
    if (old != fine_.end()) triangles_ -= static_cast<int64_t>(old->second.triangles.size());
    if (old == fine_.end() || !sameLayout(old->second, mesh)) changes.relaid.push_back(id);
    fine_[id] = std::move(mesh);
    changes.changed.push_back(id);
  }
  for (uint64_t id : gone) {
    if (std::binary_search(candidates.begin(), candidates.end(), id)) continue;
    triangles_ -= static_cast<int64_t>(fine_.at(id).triangles.size());
    fine_.erase(id);
    changes.removed.push_back(id);
  }
  TESSERA_RETURN_IF_ERROR(checkBudget());
  if (clusters_) return regroup(changes);
  return changes;
}

}  // namespace tessera

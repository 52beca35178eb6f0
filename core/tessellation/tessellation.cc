#include "core/tessellation/tessellation.h"

#include <algorithm>
#include <cstring>

#include <optional>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "core/hierarchy/incidence.h"
#include "core/loop/limit.h"
#include "core/tessellation/displayed_vertices.h"
#include "core/tessellation/leaf_triangulation.h"
#include "core/tessellation/region_merge.h"
#include "core/util/parallel_for.h"

namespace tessera {

namespace {

// Regions are cut nodes this many levels above the profile's deepest, so a
// region holds at most 4^5 = 1,024 leaf triangles before fans.
constexpr int kRegionDepth = 5;

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
  // Growing the hierarchy for the limits' levels adds faces to levels, so
  // the cut is made again over the grown hierarchy; its
  // decisions do not change, and the second round needs no growth.
  for (int round = 0;; ++round) {
    TESSERA_ASSIGN_OR_RETURN(AdaptiveCut cut, AdaptiveCut::build(doc, profile));
    const int regionLevel = std::max(0, cut.profile().maxLevel - kRegionDepth);
    Tessellation tessellation(std::move(cut), regionLevel, doc.counts());
    const SparseHierarchy& h = doc.hierarchy();
    std::vector<uint64_t> ids;
    for (Index f = 0; f < h.level(0).mesh.numFaces(); ++f) tessellation.regionsUnder(h, 0, f, ids);
    std::vector<FaceId> growth;
    std::vector<RegionMesh> meshes = tessellation.buildRegions(h, ids, growth);
    for (size_t i = 0; i < ids.size(); ++i) {
      tessellation.triangles_ += static_cast<int64_t>(meshes[i].triangles.size());
      tessellation.fine_[ids[i]] = std::move(meshes[i]);
    }
    if (growth.empty()) {
      TESSERA_RETURN_IF_ERROR(tessellation.checkBudget());
      const int maxLevel = tessellation.profile().maxLevel;
      if (maxLevel <= kMaxGroupedLevel) {
        const int size = 1 << (2 * (kGroupDepth - maxLevel));
        if (!clusters || clusters->size() != size) {
          clusters = std::make_shared<const BaseFaceClusters>(std::visit(
              [size](const auto& base) { return BaseFaceClusters::build(base, size); }, doc.base()));
        }
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
  for (int k = 0; k < h.numChildFaces(l, f); ++k) regionsUnder(h, l + 1, first + k, out);
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
    for (int k = h.numChildFaces(node.level, node.local) - 1; k >= 0; --k)
      stack.push_back({node.level + 1, first + k});
  }
  return meshOfTriangles(h, counts_, triangles, leaves, growth);
}

std::vector<RegionMesh> Tessellation::buildRegions(const SparseHierarchy& h, std::span<const uint64_t> ids,
                                                   std::vector<FaceId>& growth) const {
  std::vector<RegionMesh> meshes(ids.size());
  std::vector<std::vector<FaceId>> growths(ids.size());
  parallelFor(ids.size(), workThreads(),
              [&](size_t i) { meshes[i] = buildRegion(h, FaceId::fromPacked(ids[i]), growths[i]); });
  for (const auto& g : growths) growth.insert(growth.end(), g.begin(), g.end());
  return meshes;
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
      touched.push_back(clusters_->clusterOf(static_cast<int>(counts_.baseFace(face).index())));
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
  // A deep edit changes thousands of limits whose ring faces collapse onto
  // a few areas: each is kept once as it comes, and only the distinct ones
  // are sorted.
  std::vector<std::pair<int, uint64_t>> areas;
  std::unordered_set<uint64_t> seen;
  auto add = [&](int l, uint64_t canonical) {
    if (seen.insert(FaceId(l, canonical).packed()).second) areas.emplace_back(l, canonical);
  };
  auto addAround = [&](int l, Index v) {
    for (Index f : h.level(l).mesh.ringFacesOf(v)) {
      if (f < 0) continue;
      const uint64_t canonical = h.level(l).faceIds[f];
      if (l <= regionLevel_) {
        add(l, canonical);
      } else {
        add(regionLevel_, counts_.ancestorAt(FaceId(l, canonical), regionLevel_).index());
      }
    }
  };
  for (VertexId id : changedLimits) addAround(id.level(), h.level(id.level()).findVertex(id.index()));
  for (auto [l, f] : *flipped) {
    for (Index v : h.level(l).mesh.faceVerticesOf(f)) addAround(l, v);
  }
  std::sort(areas.begin(), areas.end());  // each is listed once already (seen)

  std::vector<uint64_t> candidates, gone;
  for (auto [l, canonical] : areas) {
    // New regions overlapping the area: walk down its ancestors in the cut.
    const FaceId area(l, canonical);
    for (int j = 0; j <= l; ++j) {
      const uint64_t a = counts_.ancestorAt(area, j).index();
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
      const uint64_t id = counts_.ancestorAt(area, j).packed();
      if (fine_.count(id)) gone.push_back(id);
    }
    for (int j = l + 1; j <= regionLevel_; ++j) {
      const auto [first, last] = counts_.descendantsAt(area, j);
      auto it = fine_.lower_bound(FaceId(j, first).packed());
      const auto end = fine_.lower_bound(FaceId(j, last).packed());
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
  std::vector<RegionMesh> meshes = buildRegions(h, candidates, growth);
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

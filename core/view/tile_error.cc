#include "core/view/tile_error.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/loop/edge_child_limit.h"
#include "core/tessellation/displayed_vertices.h"

namespace tessera {

namespace {

BoundingSphere sphereOf(const RegionMesh& mesh) {
  if (mesh.positions.empty()) return {};
  Vec3 lo = mesh.positions[0], hi = lo;
  for (const Vec3& p : mesh.positions)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  BoundingSphere s{0.5 * (lo + hi), 0};
  for (const Vec3& p : mesh.positions) s.radius = std::max(s.radius, (p - s.centre).norm());
  return s;
}

struct DeepEdits {
  double offsets = 0;  // summed L1 norms of the local offsets
  bool tags = false;
};

// The edits more than one level below level l whose support reaches the
// faces shown. A vertex of level k >= l + 2 moves the limit surface only
// within its 2-ring there, which lies inside the faces of level l that share
// a vertex with the level-l ancestor of a face around it: so an edit counts
// when that ancestor shares a vertex with a face shown.
DeepEdits deepEditsNear(const SparseHierarchy& h, int l, std::span<const FaceId> faces) {
  DeepEdits out;
  // The deep edits first: without any (the common case) the faces'
  // neighbourhood is not needed.
  struct Edited {
    int level;
    Index vertex;
    std::optional<Vec3> offset;
  };
  std::vector<Edited> edited;
  for (int k = l + 2; k < h.numLevels(); ++k) {
    h.forEachEditedVertex(k, [&](Index v, const std::optional<Vec3>& offset) {
      edited.push_back({k, v, offset});
    });
  }
  if (edited.empty()) return out;
  const SparseLevel& level = h.level(l);
  std::vector<uint64_t> near;
  for (const FaceId& f : faces) {
    const Index local = level.findFace(f.index());
    if (local == kNoIndex) continue;
    for (Index v : level.mesh.triangleVertices(local)) {
      for (Index g : level.mesh.ringFacesOf(v)) {
        if (g >= 0) near.push_back(level.faceIds[g]);
      }
    }
  }
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  for (const Edited& e : edited) {
    const SparseLevel& deep = h.level(e.level);
    for (Index g : deep.mesh.ringFacesOf(e.vertex)) {
      if (g < 0) continue;
      if (!std::binary_search(near.begin(), near.end(), deep.faceIds[g] >> (2 * (e.level - l)))) break;
      if (e.offset) {
        out.offsets += std::abs((*e.offset)[0]) + std::abs((*e.offset)[1]) + std::abs((*e.offset)[2]);
      } else {
        out.tags = true;
      }
      break;
    }
  }
  return out;
}

}  // namespace

Expected<TileBounds> tileBounds(Document& doc, const TileTree& tree, const TileKey& tile,
                                const RegionMesh& mesh, double parentError) {
  if (!tree.contains(tile)) return notFound(tile.toString() + " is not a tile of this document");
  TileBounds b;
  b.sphere = sphereOf(mesh);
  const int l = tile.level;
  if (l >= doc.counts().maxLevel()) {
    b.error = parentError / 4;
    b.sphere.radius += b.error;
    return b;
  }
  const std::vector<FaceId> faces = tree.facesShown(tile);
  for (int round = 0; round <= kMaxDocumentLevel + 1; ++round) {
    const SparseHierarchy& h = doc.hierarchy();
    const SparseLevel& level = h.level(l);
    EdgeChildLimits predicted(level.mesh, h.points(l), h.options());
    std::vector<FaceId> growth;
    double worst = 0;
    auto limit = [&](int at, Index v) -> std::optional<Vec3> {
      const auto source = limitSource(h, doc.counts(), VertexRef{at, v}, growth);
      if (!source) return std::nullopt;
      return h.limitPosition(source->level, source->local);
    };
    // Each end's limit once: a vertex ends about six of the tile's edges.
    std::unordered_map<Index, std::optional<Vec3>> ends;
    ends.reserve(faces.size());
    auto endLimit = [&](Index v) -> const std::optional<Vec3>& {
      auto [it, fresh] = ends.try_emplace(v);
      if (fresh) it->second = limit(l, v);
      return it->second;
    };
    // The next level's vertex on an edge: from this level's points where
    // they predict it (edge_child_limit.h), from the next level otherwise,
    // which is then grown under the face (a face refined once one child is
    // demanded). The choice depends on the document alone, so a tile's
    // bounds do not depend on what the hierarchy happened to hold.
    auto middle = [&](uint64_t face, Index e) -> std::optional<Vec3> {
      if (h.edgeChildIsPredicted(l, e)) {
        if (auto p = predicted.limit(e)) return p;
      }
      const Index m = l + 1 < h.numLevels() ? level.childOfEdge[e] : kNoIndex;
      if (m == kNoIndex) {
        growth.push_back(FaceId(l + 1, 4 * face));
        return std::nullopt;
      }
      return limit(l + 1, m);
    };
    // Each edge once, with the first face of the tile on it (where its
    // child is grown if it must be).
    std::vector<std::pair<Index, uint64_t>> edges;
    edges.reserve(3 * faces.size());
    for (const FaceId& f : faces) {
      const Index local = level.findFace(f.index());
      if (local == kNoIndex)
        return internalError(tile.toString() + ": the hierarchy does not hold " + f.toString());
      for (Index e : level.mesh.triangleEdges(local)) edges.emplace_back(e, f.index());
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end(),
                            [](const auto& x, const auto& y) { return x.first == y.first; }),
                edges.end());
    for (const auto& [e, face] : edges) {
      const auto& a = endLimit(level.mesh.edgeVertices[e][0]);
      const auto& c = endLimit(level.mesh.edgeVertices[e][1]);
      const auto mid = middle(face, e);
      if (!a || !c || !mid) continue;
      worst = std::max(worst, (*mid - 0.5 * (*a + *c)).norm());
    }
    if (growth.empty()) {
      const DeepEdits deep = deepEditsNear(h, l, faces);
      b.midpoints = worst;
      b.deepOffsets = deep.offsets;
      b.deepTags = deep.tags;
      b.error = worst * 4.0 / 3.0 + deep.offsets * 14.0 / 3.0;
      b.sphere.radius += b.error;
      return b;
    }
    doc.refineHierarchy(growth);
  }
  return internalError(tile.toString() +
                       ": the hierarchy does not hold the limits' rings after repeated growth");
}

}  // namespace tessera

#include "core/view/tile_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/loop/edge_child_limit.h"
#include "core/render/surface_distance.h"
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
DeepEdits deepEditsNear(const SparseHierarchy& h, const LevelCounts& counts, int l,
                        std::span<const FaceId> faces) {
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
    for (Index v : level.mesh.faceVerticesOf(local)) {
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
      const uint64_t above = counts.ancestorAt(FaceId(e.level, deep.faceIds[g]), l).index();
      if (!std::binary_search(near.begin(), near.end(), above)) break;
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
    // Loop's stencils predict the next level; the quad split's is read.
    std::optional<EdgeChildLimits> predicted;
    if (!h.quads()) predicted.emplace(level.mesh, h.points(l), h.options());
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
    auto grownUnder = [&](uint64_t face, Index m) -> std::optional<Vec3> {
      if (m == kNoIndex) {
        growth.push_back(doc.counts().childFace(FaceId(l, face), 0));
        return std::nullopt;
      }
      return limit(l + 1, m);
    };
    auto middle = [&](uint64_t face, Index e) -> std::optional<Vec3> {
      if (predicted && h.edgeChildIsPredicted(l, e)) {
        if (auto p = predicted->limit(e)) return p;
      }
      return grownUnder(face, l + 1 < h.numLevels() ? level.childOfEdge[e] : kNoIndex);
    };
    // Each edge once, with the first face of the tile on it (where its
    // child is grown if it must be).
    std::vector<std::pair<Index, uint64_t>> edges;
    edges.reserve(3 * faces.size());
    std::vector<Vec3> at;  // a face's corners' limits, quad split only
    for (const FaceId& f : faces) {
      const Index local = level.findFace(f.index());
      if (local == kNoIndex)
        return internalError(tile.toString() + ": the hierarchy does not hold " + f.toString());
      for (Index e : level.mesh.faceEdgesOf(local)) edges.emplace_back(e, f.index());
      if (!h.quads()) continue;
      // The quad split's vertex in the face, against the flat face at the
      // same place: a quad's diagonal midpoint (its triangles meet on the
      // first diagonal, leaf_triangulation.h); a base n-gon's fan, which
      // has no such place, at its nearest point.
      const auto centre = grownUnder(f.index(), l + 1 < h.numLevels() ? level.childOfFace[local] : kNoIndex);
      if (!centre) continue;
      const auto corners = level.mesh.faceVerticesOf(local);
      at.clear();
      for (Index v : corners) {
        if (const auto& p = endLimit(v)) at.push_back(*p);
      }
      if (at.size() != corners.size()) continue;
      if (at.size() == 4) {
        worst = std::max(worst, (*centre - 0.5 * (at[0] + at[2])).norm());
        continue;
      }
      double nearest = std::numeric_limits<double>::infinity();
      for (size_t k = 1; k + 1 < at.size(); ++k)
        nearest = std::min(nearest, (*centre - closestOnTriangle(*centre, at[0], at[k], at[k + 1])).norm());
      worst = std::max(worst, nearest);
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
      const DeepEdits deep = deepEditsNear(h, doc.counts(), l, faces);
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

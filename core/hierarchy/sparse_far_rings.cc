#include "core/hierarchy/sparse_far_rings.h"

#include <algorithm>

#include "core/loop/sharpness_inheritance.h"

namespace tessera {

void SparseFarRings::edgesAt(Index u, std::vector<float>& out) const {
  const Level& m = level_.mesh;
  if (parent_ == nullptr || level_.isComplete(u)) {
    out.resize(m.valence(u));
    m.ringSharpness(u, out.data());
    return;
  }
  const SparseLevel& p = *parent_;
  out.clear();
  const Index origin = level_.origin[u];
  if (level_.isVertexChild(u)) {
    // In the parent's ring order, which is the child's.
    SharpnessInheritance inherit(p.mesh, options_);
    for (Index e : p.mesh.ringEdgesOf(origin)) {
      const int end = p.mesh.edgeVertices[e][0] == origin ? 0 : 1;
      const Index half = p.halvesOfEdge[e];
      out.push_back(half >= 0 ? m.edgeSharpness[half + end] : inherit.halfSharpness(e, end));
    }
    return;
  }
  // A vertex on a parent edge has the edge's two halves; one in a parent
  // face (quads) has none. Its other edges lie inside the parent's faces.
  const Index half = level_.isFaceChild(u) ? kNoIndex : p.halvesOfEdge[origin];
  if (half != kNoIndex) {
    out.push_back(m.edgeSharpness[half]);
    out.push_back(m.edgeSharpness[half + 1]);
  }
  std::vector<Index> interior;
  for (Index f : m.ringFacesOf(u)) {
    if (f < 0) continue;
    for (Index e : m.faceEdgesOf(f)) {
      const auto& ends = m.edgeVertices[e];
      if ((ends[0] == u || ends[1] == u) && (half == kNoIndex || (e != half && e != half + 1)))
        interior.push_back(e);
    }
  }
  // In canonical order, whatever the local one (a level grown in place).
  std::sort(interior.begin(), interior.end(),
            [&](Index a, Index b) { return level_.edgeIds[a] < level_.edgeIds[b]; });
  interior.erase(std::unique(interior.begin(), interior.end()), interior.end());
  for (Index e : interior) out.push_back(m.edgeSharpness[e]);
}

}  // namespace tessera

#include "core/tessellation/base_face_clusters.h"

#include <algorithm>
#include <deque>
#include <unordered_map>

namespace tessera {

namespace cluster_detail {

template <typename Corners, typename SameParent>
BaseFaceClusters grow(int n, Corners corners, int size, SameParent sameParent) {
  BaseFaceClusters c;
  c.size_ = std::max(1, size);
  constexpr uint32_t kNone = ~uint32_t{0};
  c.clusterOf_.assign(n, kNone);
  // Faces across each edge, in the order of a face's corners: face f's
  // neighbours are across[acrossBegin[f] .. acrossBegin[f + 1]).
  std::vector<int> acrossBegin{0};
  for (int f = 0; f < n; ++f) acrossBegin.push_back(acrossBegin.back() + static_cast<int>(corners(f).size()));
  std::vector<int> across(acrossBegin.back(), -1);
  if (c.size_ > 1) {
    std::unordered_map<uint64_t, std::pair<int, int>> byEdge;  // (lo, hi) -> (face, slot) of the first side
    byEdge.reserve(across.size());
    for (int f = 0; f < n; ++f) {
      const auto fc = corners(f);
      const size_t k = fc.size();
      for (size_t j = 0; j < k; ++j) {
        const uint32_t a = static_cast<uint32_t>(fc[j]);
        const uint32_t b = static_cast<uint32_t>(fc[(j + 1) % k]);
        const uint64_t key = (uint64_t{std::min(a, b)} << 32) | std::max(a, b);
        const int slot = acrossBegin[f] + static_cast<int>(j);
        auto [it, fresh] = byEdge.try_emplace(key, f, slot);
        if (!fresh) {
          across[slot] = it->second.first;
          across[it->second.second] = f;
        }
      }
    }
  }
  std::vector<int> members;
  std::deque<int> queue;
  c.offsets_.push_back(0);
  for (int seed = 0; seed < n; ++seed) {
    if (c.clusterOf_[seed] != kNone) continue;
    const uint32_t cluster = static_cast<uint32_t>(c.seeds_.size());
    c.seeds_.push_back(seed);
    members.clear();
    queue.assign(1, seed);
    c.clusterOf_[seed] = cluster;
    members.push_back(seed);
    while (!queue.empty() && static_cast<int>(members.size()) < c.size_) {
      const int f = queue.front();
      queue.pop_front();
      for (int s = acrossBegin[f]; s < acrossBegin[f + 1]; ++s) {
        const int g = across[s];
        if (g < 0 || c.clusterOf_[g] != kNone || static_cast<int>(members.size()) >= c.size_) continue;
        if (!sameParent(f, g)) continue;
        c.clusterOf_[g] = cluster;
        members.push_back(g);
        queue.push_back(g);
      }
    }
    std::sort(members.begin(), members.end());
    c.faces_.insert(c.faces_.end(), members.begin(), members.end());
    c.offsets_.push_back(static_cast<int>(c.faces_.size()));
  }
  return c;
}

}  // namespace cluster_detail

namespace {

auto triangleCorners(const BaseTopology& base) {
  return [&base](int f) { return std::span<const int>(base.triangles[f]); };
}

auto polygonCorners(const PolyTopology& base) {
  return [&base](int f) {
    return std::span<const int>(base.indices.data() + base.faceOffsets[f],
                                static_cast<size_t>(base.faceOffsets[f + 1] - base.faceOffsets[f]));
  };
}

auto anyParent() {
  return [](int, int) { return true; };
}

auto sameClusterOf(const BaseFaceClusters& within) {
  return [&within](int f, int g) { return within.clusterOf(f) == within.clusterOf(g); };
}

}  // namespace

BaseFaceClusters BaseFaceClusters::build(const BaseTopology& base, int size) {
  return cluster_detail::grow(static_cast<int>(base.triangles.size()), triangleCorners(base), size,
                              anyParent());
}

BaseFaceClusters BaseFaceClusters::build(const PolyTopology& base, int size) {
  return cluster_detail::grow(base.numFaces(), polygonCorners(base), size, anyParent());
}

BaseFaceClusters BaseFaceClusters::buildWithin(const BaseTopology& base, int size,
                                               const BaseFaceClusters& within) {
  return cluster_detail::grow(static_cast<int>(base.triangles.size()), triangleCorners(base), size,
                              sameClusterOf(within));
}

BaseFaceClusters BaseFaceClusters::buildWithin(const PolyTopology& base, int size,
                                               const BaseFaceClusters& within) {
  return cluster_detail::grow(base.numFaces(), polygonCorners(base), size, sameClusterOf(within));
}

}  // namespace tessera

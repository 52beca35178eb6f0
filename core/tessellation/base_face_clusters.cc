#include "core/tessellation/base_face_clusters.h"

#include <algorithm>
#include <array>
#include <deque>
#include <functional>
#include <unordered_map>

namespace tessera {

namespace cluster_detail {

template <typename SameParent>
BaseFaceClusters grow(const BaseTopology& base, int size, SameParent sameParent,
                      std::function<int(int)> limitOf) {
  BaseFaceClusters c;
  c.size_ = std::max(1, size);
  const int n = static_cast<int>(base.triangles.size());
  constexpr uint32_t kNone = ~uint32_t{0};
  c.clusterOf_.assign(n, kNone);
  // Faces across each edge: neighbours in the order of a face's corners.
  std::vector<std::array<int, 3>> across(n, {-1, -1, -1});
  if (c.size_ > 1) {
    std::unordered_map<uint64_t, std::pair<int, int>> byEdge;  // (lo, hi) -> (face, corner)
    byEdge.reserve(static_cast<size_t>(n) * 2);
    for (int f = 0; f < n; ++f) {
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = static_cast<uint32_t>(base.triangles[f][k]);
        const uint32_t b = static_cast<uint32_t>(base.triangles[f][(k + 1) % 3]);
        const uint64_t key = (uint64_t{std::min(a, b)} << 32) | std::max(a, b);
        auto [it, fresh] = byEdge.try_emplace(key, f, k);
        if (!fresh) {
          across[f][k] = it->second.first;
          across[it->second.first][it->second.second] = f;
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
    const int limit = limitOf(seed);
    queue.assign(1, seed);
    c.clusterOf_[seed] = cluster;
    members.push_back(seed);
    while (!queue.empty() && static_cast<int>(members.size()) < limit) {
      const int f = queue.front();
      queue.pop_front();
      for (int g : across[f]) {
        if (g < 0 || c.clusterOf_[g] != kNone || static_cast<int>(members.size()) >= limit) continue;
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

BaseFaceClusters BaseFaceClusters::build(const BaseTopology& base, int size) {
  return cluster_detail::grow(
      base, size, [](int, int) { return true; }, [size](int) { return size; });
}

BaseFaceClusters BaseFaceClusters::buildWithin(const BaseTopology& base, int size,
                                               const BaseFaceClusters& within) {
  return cluster_detail::grow(
      base, size, [&](int f, int g) { return within.clusterOf(f) == within.clusterOf(g); },
      [size](int) { return size; });
}

}  // namespace tessera

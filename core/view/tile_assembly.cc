#include "core/view/tile_assembly.h"

#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>

namespace tessera {

namespace {

using Edge = std::pair<uint64_t, uint64_t>;  // vertex ids, ordered

Edge edgeOf(uint64_t a, uint64_t b) {
  return a < b ? Edge{a, b} : Edge{b, a};
}

// A tile's edges by vertex id, with how many of its triangles use each:
// crease sides split a vertex into copies, which share the id.
std::map<Edge, int> edgesOf(const RegionMesh& m) {
  std::map<Edge, int> out;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++out[edgeOf(m.vertexIds[t[k]], m.vertexIds[t[(k + 1) % 3]])];
  return out;
}

}  // namespace

std::vector<std::vector<Vec3>> closeCracks(const std::vector<const RegionMesh*>& tiles, int64_t* moved) {
  const size_t n = tiles.size();
  std::vector<std::map<Edge, int>> edges(n);
  std::unordered_map<uint64_t, std::vector<uint32_t>> owners;  // vertex id -> tiles having it
  for (size_t i = 0; i < n; ++i) {
    edges[i] = edgesOf(*tiles[i]);
    std::set<uint64_t> ids(tiles[i]->vertexIds.begin(), tiles[i]->vertexIds.end());
    for (uint64_t id : ids) owners[id].push_back(static_cast<uint32_t>(i));
  }
  std::vector<std::vector<Vec3>> out(n);
  int64_t count = 0;
  for (size_t i = 0; i < n; ++i) {
    const RegionMesh& m = *tiles[i];
    out[i] = m.positions;
    // Boundary edges (used by one triangle) as a graph over ids.
    std::unordered_map<uint64_t, std::vector<uint64_t>> next;
    for (const auto& [e, uses] : edges[i]) {
      if (uses != 1) continue;
      next[e.first].push_back(e.second);
      next[e.second].push_back(e.first);
    }
    auto shared = [&](uint64_t id) { return owners[id].size() > 1; };
    std::unordered_map<uint64_t, Vec3> position;
    for (size_t v = 0; v < m.positions.size(); ++v) position.emplace(m.vertexIds[v], m.positions[v]);
    std::unordered_map<uint64_t, Vec3> target;
    // From each shared boundary vertex, follow each boundary direction over
    // unshared vertices to the next shared one.
    for (const auto& [start, around] : next) {
      if (!shared(start)) continue;
      for (uint64_t first : around) {
        if (shared(first)) continue;
        std::vector<uint64_t> run{start};
        uint64_t prev = start, at = first;
        while (!shared(at) && next[at].size() == 2 && run.size() < (1u << 20)) {
          run.push_back(at);
          const uint64_t after = next[at][0] == prev ? next[at][1] : next[at][0];
          prev = at, at = after;
        }
        if (!shared(at)) continue;  // not a run between shared vertices (a fold of the boundary)
        run.push_back(at);
        const uint64_t a = run.front(), b = run.back();
        if (a > b) continue;  // each run once, from its lower end
        // A tile shows one level: if it has the edge a-b itself, the run
        // went the other way round it, not along a finer copy of a-b.
        if (edges[i].count(edgeOf(a, b))) continue;
        // The other tile that has both ends and joins them by an edge.
        bool coarser = false;
        for (uint32_t j : owners[a]) {
          if (j == i) continue;
          if (std::find(owners[b].begin(), owners[b].end(), j) == owners[b].end()) continue;
          if (edges[j].count(edgeOf(a, b))) coarser = true;
        }
        if (!coarser) continue;
        const Vec3 pa = position.at(a), pb = position.at(b);
        const double segments = static_cast<double>(run.size() - 1);
        for (size_t k = 1; k + 1 < run.size(); ++k) {
          const double t = static_cast<double>(k) / segments;
          target[run[k]] = (1 - t) * pa + t * pb;
        }
      }
    }
    for (size_t v = 0; v < m.positions.size(); ++v) {
      auto it = target.find(m.vertexIds[v]);
      if (it == target.end()) continue;
      out[i][v] = it->second;
      ++count;
    }
  }
  if (moved) *moved = count;
  return out;
}

}  // namespace tessera

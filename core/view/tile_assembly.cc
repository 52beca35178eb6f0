#include "core/view/tile_assembly.h"

#include <algorithm>
#include <map>

namespace tessera {

namespace {

IdEdge edgeOf(uint64_t a, uint64_t b) {
  return a < b ? IdEdge{a, b} : IdEdge{b, a};
}

}  // namespace

TileBoundary tileBoundary(const RegionMesh& tile) {
  // Edges by id with how many triangles use each, in id order so that the
  // boundary graph lists its neighbours in one order whatever the hashing.
  std::map<IdEdge, int> uses;
  for (const auto& t : tile.triangles)
    for (int k = 0; k < 3; ++k) ++uses[edgeOf(tile.vertexIds[t[k]], tile.vertexIds[t[(k + 1) % 3]])];
  TileBoundary b;
  for (const auto& [e, n] : uses) {
    if (n != 1) continue;
    b.next[e.first].push_back(e.second);
    b.next[e.second].push_back(e.first);
  }
  for (const auto& [e, n] : uses) {
    if (b.next.count(e.first) && b.next.count(e.second)) b.chords.insert(e);
  }
  for (size_t v = 0; v < tile.positions.size(); ++v) {
    const uint64_t id = tile.vertexIds[v];
    if (!b.next.count(id)) continue;
    b.position.emplace(id, tile.positions[v]);
    b.copies[id].push_back(static_cast<uint32_t>(v));
  }
  return b;
}

std::vector<std::vector<Vec3>> closeCracks(const std::vector<const RegionMesh*>& tiles,
                                           const std::vector<const TileBoundary*>& boundaries,
                                           int64_t* moved) {
  const size_t n = tiles.size();
  // A vertex two tiles have is on the boundary of both: only boundary
  // vertices are counted.
  std::unordered_map<uint64_t, std::vector<uint32_t>> owners;  // vertex id -> tiles having it
  for (size_t i = 0; i < n; ++i)
    for (const auto& [id, around] : boundaries[i]->next) owners[id].push_back(static_cast<uint32_t>(i));
  auto shared = [&](uint64_t id) { return owners.at(id).size() > 1; };
  std::vector<std::vector<Vec3>> out(n);
  int64_t count = 0;
  for (size_t i = 0; i < n; ++i) {
    const TileBoundary& b = *boundaries[i];
    out[i] = tiles[i]->positions;
    std::unordered_map<uint64_t, Vec3> target;
    // From each shared boundary vertex, follow each boundary direction over
    // unshared vertices to the next shared one.
    for (const auto& [start, around] : b.next) {
      if (!shared(start)) continue;
      for (uint64_t first : around) {
        if (shared(first)) continue;
        std::vector<uint64_t> run{start};
        uint64_t prev = start, at = first;
        while (!shared(at) && b.next.at(at).size() == 2 && run.size() < (1u << 20)) {
          run.push_back(at);
          const auto& hop = b.next.at(at);
          const uint64_t after = hop[0] == prev ? hop[1] : hop[0];
          prev = at, at = after;
        }
        if (!shared(at)) continue;  // not a run between shared vertices (a fold of the boundary)
        run.push_back(at);
        const uint64_t lo = run.front(), hi = run.back();
        if (lo > hi) continue;  // each run once, from its lower end
        // A tile shows one level: if it has the edge lo-hi itself, the run
        // went the other way round it, not along a finer copy of lo-hi.
        if (b.chords.count(edgeOf(lo, hi))) continue;
        // The other tile that has both ends and joins them by an edge.
        bool coarser = false;
        const auto& ownersHi = owners.at(hi);
        for (uint32_t j : owners.at(lo)) {
          if (j == i || std::find(ownersHi.begin(), ownersHi.end(), j) == ownersHi.end()) continue;
          if (boundaries[j]->chords.count(edgeOf(lo, hi))) coarser = true;
        }
        if (!coarser) continue;
        const Vec3 pa = b.position.at(lo), pb = b.position.at(hi);
        const double segments = static_cast<double>(run.size() - 1);
        for (size_t k = 1; k + 1 < run.size(); ++k) {
          const double t = static_cast<double>(k) / segments;
          target[run[k]] = (1 - t) * pa + t * pb;
        }
      }
    }
    for (const auto& [id, p] : target) {
      for (uint32_t v : b.copies.at(id)) out[i][v] = p;
      count += static_cast<int64_t>(b.copies.at(id).size());
    }
  }
  if (moved) *moved = count;
  return out;
}

std::vector<std::vector<Vec3>> closeCracks(const std::vector<const RegionMesh*>& tiles, int64_t* moved) {
  std::vector<TileBoundary> boundaries;
  boundaries.reserve(tiles.size());
  for (const RegionMesh* tile : tiles) boundaries.push_back(tileBoundary(*tile));
  std::vector<const TileBoundary*> pointers;
  for (const TileBoundary& b : boundaries) pointers.push_back(&b);
  return closeCracks(tiles, pointers, moved);
}

}  // namespace tessera

#include "core/render/dynamic_refinement.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "core/render/split_table.h"

namespace tessera {

namespace {

using Bits = std::array<uint64_t, 3>;

Bits bitsOf(const Vec3& p) {
  return {std::bit_cast<uint64_t>(p[0]), std::bit_cast<uint64_t>(p[1]), std::bit_cast<uint64_t>(p[2])};
}

// The edges of a mesh, found by position: each edge lists the half-edges
// (3 * triangle + k, from corner k to corner k + 1) on it, at most two; a
// third triangle on an edge (non-manifold) gets an edge of its own. Sorting
// rather than hashing: a frame refines thousands of small regions.
struct MeshEdges {
  std::vector<int> vertexClass;           // one per vertex: equal positions, equal class
  std::vector<std::array<int, 2>> sides;  // half-edges of each edge; sides[e][1] < 0 when alone
};

MeshEdges findEdges(const RefineInput& mesh) {
  MeshEdges out;
  const size_t n = mesh.positions.size();
  std::vector<std::pair<Bits, int>> byPosition(n);
  for (size_t v = 0; v < n; ++v) byPosition[v] = {bitsOf(mesh.positions[v]), static_cast<int>(v)};
  std::sort(byPosition.begin(), byPosition.end());
  out.vertexClass.resize(n);
  int classes = -1;
  for (size_t i = 0; i < n; ++i) {
    if (i == 0 || byPosition[i].first != byPosition[i - 1].first) ++classes;
    out.vertexClass[byPosition[i].second] = classes;
  }
  std::vector<std::pair<uint64_t, int>> halves;
  halves.reserve(mesh.triangles.size() * 3);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<uint64_t>(out.vertexClass[mesh.triangles[t][k]]);
      const auto b = static_cast<uint64_t>(out.vertexClass[mesh.triangles[t][(k + 1) % 3]]);
      halves.push_back({std::min(a, b) << 32 | std::max(a, b), static_cast<int>(3 * t) + k});
    }
  }
  std::sort(halves.begin(), halves.end());
  out.sides.reserve(halves.size() / 2 + 1);
  for (size_t i = 0; i < halves.size(); ++i) {
    const bool paired = i + 1 < halves.size() && halves[i + 1].first == halves[i].first;
    out.sides.push_back({halves[i].second, paired ? halves[i + 1].second : -1});
    if (!paired) continue;
    ++i;
    // A third side and beyond: alone (non-manifold input).
    while (i + 1 < halves.size() && halves[i + 1].first == halves[i].first)
      out.sides.push_back({halves[++i].second, -1});
  }
  return out;
}

int corner(const RefineInput& mesh, int half, int offset) {
  return mesh.triangles[half / 3][(half % 3 + offset) % 3];
}

Status checkInput(const RefineInput& mesh, const SplitCriterion& c) {
  if (c.maxSplits < 0 || c.maxSplits > 2)
    return invalidArgument("refinement: maxSplits " + std::to_string(c.maxSplits) + " is not 0, 1 or 2");
  if (!std::isfinite(c.splitOnceBelow) || !std::isfinite(c.splitTwiceBelow) ||
      c.splitTwiceBelow > c.splitOnceBelow)
    return invalidArgument("refinement: thresholds must be finite with splitTwiceBelow <= splitOnceBelow");
  if (mesh.normals.size() != mesh.positions.size())
    return invalidArgument("refinement: " + std::to_string(mesh.normals.size()) + " normals for " +
                           std::to_string(mesh.positions.size()) + " positions");
  const auto n = static_cast<int64_t>(mesh.positions.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (tri[k] < 0 || tri[k] >= n || tri[k] == tri[(k + 1) % 3])
        return invalidArgument("refinement: triangle " + std::to_string(t) + ": corner " + std::to_string(k) +
                               " is out of range or repeated");
    }
  }
  return Status::ok();
}

void recordBorders(const RefineInput& mesh, const MeshEdges& edges, BorderEdges& borders) {
  for (const auto& sides : edges.sides) {
    if (sides[1] >= 0) continue;
    const int u = corner(mesh, sides[0], 0), v = corner(mesh, sides[0], 1);
    borders.record(mesh.positions[u], mesh.positions[v], {mesh.normals[u], mesh.normals[v]});
  }
}

RefinedMesh refineWith(const RefineInput& mesh, const MeshEdges& edges, const SplitCriterion& criterion,
                       const BorderEdges* borders) {
  RefinedMesh out;
  // At most one point per edge and side with one split, three with two.
  const size_t most = mesh.positions.size() + 2 * pointsForSplits(criterion.maxSplits) * edges.sides.size();
  out.positions.reserve(most);
  out.normals.reserve(most);
  out.positions.assign(mesh.positions.begin(), mesh.positions.end());
  out.normals.assign(mesh.normals.begin(), mesh.normals.end());
  out.originalVertices = out.positions.size();
  const size_t halves = 3 * mesh.triangles.size();
  std::vector<int8_t> splits(halves, 0);
  // Output vertex of the point q/4 along each half-edge, in its direction.
  std::vector<std::array<int, 3>> points(halves, {-1, -1, -1});
  auto emit = [&](const Vec3& p, const Vec3& n) {
    out.positions.push_back(p);
    out.normals.push_back(n);
    return static_cast<int>(out.positions.size() - 1);
  };

  for (const auto& [h0, h1] : edges.sides) {
    const int u = corner(mesh, h0, 0), v = corner(mesh, h0, 1);
    const EdgeSide side{mesh.normals[u], mesh.normals[v]};
    std::optional<EdgeSide> other;
    bool reversed = true;  // h1 runs v -> u, as on an oriented surface
    if (h1 >= 0) {
      const int u1 = corner(mesh, h1, 0), v1 = corner(mesh, h1, 1);
      reversed = edges.vertexClass[u1] != edges.vertexClass[u];
      other = reversed ? EdgeSide{mesh.normals[v1], mesh.normals[u1]}
                       : EdgeSide{mesh.normals[u1], mesh.normals[v1]};
    } else if (borders) {
      other = borders->other(mesh.positions[u], mesh.positions[v], side);
    }
    const EdgeSplit s = splitEdge(mesh.positions[u], mesh.positions[v], side, other, criterion);
    splits[h0] = static_cast<int8_t>(s.splits);
    if (h1 >= 0) splits[h1] = static_cast<int8_t>(s.splits);
    for (int q = 0; q < 3; ++q) {
      if (s.splits == 0 || (s.splits == 1 && q != 1)) continue;
      points[h0][q] = emit(s.points[q], s.normals[q]);
      if (h1 < 0) continue;
      // One vertex where both sides agree on the normal, two at a crease.
      const int far =
          bitsEqual(s.normals[q], s.otherNormals[q]) ? points[h0][q] : emit(s.points[q], s.otherNormals[q]);
      points[h1][reversed ? 2 - q : q] = far;
    }
  }

  auto patternOf = [&](size_t t) -> const SplitPattern& {
    return splitPattern(splitTableIndex(splits[3 * t], splits[3 * t + 1], splits[3 * t + 2]));
  };
  size_t count = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) count += patternOf(t).count;
  out.triangles.reserve(count);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const size_t h = 3 * t;
    const SplitPattern& pattern = patternOf(t);
    auto vertex = [&](int slot) {
      if (slot < 3) return mesh.triangles[t][slot];
      return points[h + (slot - 3) / 3][(slot - 3) % 3];
    };
    for (int i = 0; i < pattern.count; ++i) {
      const auto& tri = pattern.triangles[i];
      out.triangles.push_back({vertex(tri[0]), vertex(tri[1]), vertex(tri[2])});
    }
  }
  return out;
}

}  // namespace

Status addBorderEdges(const RefineInput& mesh, BorderEdges& borders) {
  TESSERA_RETURN_IF_ERROR(checkInput(mesh, SplitCriterion{}));
  recordBorders(mesh, findEdges(mesh), borders);
  return Status::ok();
}

Expected<RefinedMesh> refineMesh(const RefineInput& mesh, const SplitCriterion& criterion,
                                 const BorderEdges* borders) {
  TESSERA_RETURN_IF_ERROR(checkInput(mesh, criterion));
  return refineWith(mesh, findEdges(mesh), criterion, borders);
}

Expected<std::vector<RefinedMesh>> refineMeshes(std::span<const RefineInput> meshes,
                                                const SplitCriterion& criterion) {
  BorderEdges borders;
  std::vector<MeshEdges> edges;
  edges.reserve(meshes.size());
  for (size_t i = 0; i < meshes.size(); ++i) {
    const Status ok = checkInput(meshes[i], criterion);
    if (!ok.isOk()) return ok.withContext("mesh " + std::to_string(i));
    edges.push_back(findEdges(meshes[i]));
    recordBorders(meshes[i], edges.back(), borders);
  }
  std::vector<RefinedMesh> out;
  out.reserve(meshes.size());
  for (size_t i = 0; i < meshes.size(); ++i)
    out.push_back(refineWith(meshes[i], edges[i], criterion, &borders));
  return out;
}

}  // namespace tessera

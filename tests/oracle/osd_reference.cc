#include "oracle/osd_reference.h"

#include <stdexcept>
#include <string>

#include "oracle/osd_adapter.h"

namespace tessera::oracle {

namespace {

namespace Far = OpenSubdiv::Far;

// map[l][ourVertex] = OpenSubdiv's vertex, level by level through children.
std::vector<std::vector<int>> vertexMaps(const Far::TopologyRefiner& osd, const LoopRefiner& ours,
                                         int levels) {
  std::vector<std::vector<int>> maps(levels + 1);
  maps[0].resize(ours.level(0).numVertices);
  for (int v = 0; v < ours.level(0).numVertices; ++v) maps[0][v] = v;
  for (int l = 0; l < levels; ++l) {
    const Level& parent = ours.level(l);
    const Far::TopologyLevel& osdParent = osd.GetLevel(l);
    auto& next = maps[l + 1];
    next.resize(ours.level(l + 1).numVertices);
    for (int v = 0; v < parent.numVertices; ++v) next[v] = osdParent.GetVertexChildVertex(maps[l][v]);
    for (int e = 0; e < parent.numEdges(); ++e) {
      int osdEdge =
          osdParent.FindEdge(maps[l][parent.edgeVertices[e][0]], maps[l][parent.edgeVertices[e][1]]);
      if (osdEdge < 0) throw std::runtime_error("edge missing in OpenSubdiv at level " + std::to_string(l));
      next[parent.numVertices + e] = osdParent.GetEdgeChildVertex(osdEdge);
    }
  }
  return maps;
}

}  // namespace

std::vector<OsdLevelResult> refineWithOpenSubdiv(const BaseTopology& topology,
                                                 std::span<const Vec3> basePoints, const LoopOptions& options,
                                                 const LoopRefiner& ours, bool withLimit) {
  const int levels = ours.maxLevel();
  const OsdInput input(topology);
  auto refiner = createOsdRefiner(input, options, levels, true);
  auto maps = vertexMaps(*refiner, ours, levels);

  std::vector<OsdPoint> base;
  for (const Vec3& p : basePoints) base.push_back(OsdPoint::from(p));

  std::vector<OsdLevelResult> results(levels + 1);
  for (int l = 0; l <= levels; ++l) {
    // Limit() applies to the last level only: one refiner per level. Vertex
    // numbering up to level l does not depend on deeper levels, so the map holds.
    // The deepest one is the refiner already built for the vertex maps.
    std::unique_ptr<Far::TopologyRefiner> owned =
        l == levels ? nullptr : createOsdRefiner(input, options, l, true);
    const Far::TopologyRefiner& levelRefiner = l == levels ? *refiner : *owned;
    std::vector<OsdPoint> points = interpolateOsd(levelRefiner, base, l);
    const int count = levelRefiner.GetLevel(l).GetNumVertices();
    std::vector<OsdPoint> pos(count), t1(count), t2(count);
    if (withLimit) {
      OsdPoint *posOut = pos.data(), *t1Out = t1.data(), *t2Out = t2.data();
      Far::PrimvarRefiner(levelRefiner).Limit(points.data(), posOut, t1Out, t2Out);
    }
    const int n = ours.level(l).numVertices;
    auto& r = results[l];
    r.points.resize(n);
    for (int v = 0; v < n; ++v) r.points[v] = points[maps[l][v]].toVec3();
    if (!withLimit) continue;
    r.limitPositions.resize(n);
    r.limitTangent1.resize(n);
    r.limitTangent2.resize(n);
    for (int v = 0; v < n; ++v) {
      r.limitPositions[v] = pos[maps[l][v]].toVec3();
      r.limitTangent1[v] = t1[maps[l][v]].toVec3();
      r.limitTangent2[v] = t2[maps[l][v]].toVec3();
    }
  }
  return results;
}

}  // namespace tessera::oracle

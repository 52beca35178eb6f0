#include "oracle/osd_reference.h"

#include <memory>
#include <stdexcept>
#include <string>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

namespace tessera::oracle {

namespace {

using namespace OpenSubdiv;

struct OsdPoint {
  double x = 0, y = 0, z = 0;
  void Clear(void* = nullptr) { x = y = z = 0; }
  void AddWithWeight(const OsdPoint& src, float w) {
    x += w * src.x;
    y += w * src.y;
    z += w * src.z;
  }
};

// OpenSubdiv reports topology problems through a callback (to stdout by
// default); a test must fail loudly instead.
void throwOnOsdError(Far::ErrorType, const char* message) {
  throw std::runtime_error(std::string("OpenSubdiv: ") + message);
}

std::unique_ptr<Far::TopologyRefiner> makeRefiner(const BaseTopology& topology, const LoopOptions& options,
                                                  int levels) {
  std::vector<int> vertsPerFace(topology.triangles.size(), 3);
  std::vector<int> indices;
  indices.reserve(topology.triangles.size() * 3);
  for (const auto& t : topology.triangles) indices.insert(indices.end(), t.begin(), t.end());
  std::vector<int> creasePairs;
  std::vector<float> creaseWeights;
  for (const auto& c : topology.creases) {
    creasePairs.push_back(c.v0);
    creasePairs.push_back(c.v1);
    creaseWeights.push_back(c.sharpness);
  }
  std::vector<int> cornerIndices;
  std::vector<float> cornerWeights;
  for (size_t v = 0; v < topology.vertexSharpness.size(); ++v) {
    if (topology.vertexSharpness[v] > 0.0f) {
      cornerIndices.push_back(static_cast<int>(v));
      cornerWeights.push_back(topology.vertexSharpness[v]);
    }
  }

  Far::TopologyDescriptor desc;
  desc.numVertices = topology.numVertices;
  desc.numFaces = static_cast<int>(topology.triangles.size());
  desc.numVertsPerFace = vertsPerFace.data();
  desc.vertIndicesPerFace = indices.data();
  desc.numCreases = static_cast<int>(creaseWeights.size());
  desc.creaseVertexIndexPairs = creasePairs.data();
  desc.creaseWeights = creaseWeights.data();
  desc.numCorners = static_cast<int>(cornerWeights.size());
  desc.cornerVertexIndices = cornerIndices.data();
  desc.cornerWeights = cornerWeights.data();

  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(options.boundary == BoundaryInterpolation::kEdgeOnly
                                      ? Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                                      : Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  sdc.SetCreasingMethod(options.creaseMethod == CreaseMethod::kUniform ? Sdc::Options::CREASE_UNIFORM
                                                                      : Sdc::Options::CREASE_CHAIKIN);
  Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Options factoryOptions(Sdc::SCHEME_LOOP, sdc);
  Far::SetErrorCallback(throwOnOsdError);
  std::unique_ptr<Far::TopologyRefiner> refiner(
      Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Create(desc, factoryOptions));
  if (!refiner) throw std::runtime_error("OpenSubdiv refused the topology");
  Far::TopologyRefiner::UniformOptions uniform(levels);
  // Limit() silently does nothing without full topology in the last level.
  uniform.fullTopologyInLastLevel = true;
  refiner->RefineUniform(uniform);
  return refiner;
}

// map[l][ourVertex] = OpenSubdiv's vertex, level by level through children.
std::vector<std::vector<int>> vertexMaps(const Far::TopologyRefiner& osd, const LoopRefiner& ours, int levels) {
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
      int osdEdge = osdParent.FindEdge(maps[l][parent.edgeVertices[e][0]], maps[l][parent.edgeVertices[e][1]]);
      if (osdEdge < 0) throw std::runtime_error("edge missing in OpenSubdiv at level " + std::to_string(l));
      next[parent.numVertices + e] = osdParent.GetEdgeChildVertex(osdEdge);
    }
  }
  return maps;
}

Vec3 toVec(const OsdPoint& p) { return Vec3(p.x, p.y, p.z); }

}  // namespace

std::vector<OsdLevelResult> refineWithOpenSubdiv(const BaseTopology& topology, std::span<const Vec3> basePoints,
                                                 const LoopOptions& options, const LoopRefiner& ours,
                                                 bool withLimit) {
  const int levels = ours.maxLevel();
  auto refiner = makeRefiner(topology, options, levels);
  auto maps = vertexMaps(*refiner, ours, levels);

  std::vector<std::vector<OsdPoint>> osdPoints(levels + 1);
  osdPoints[0].resize(basePoints.size());
  for (size_t v = 0; v < basePoints.size(); ++v) osdPoints[0][v] = {basePoints[v][0], basePoints[v][1], basePoints[v][2]};
  Far::PrimvarRefiner primvar(*refiner);
  for (int l = 1; l <= levels; ++l) {
    osdPoints[l].resize(refiner->GetLevel(l).GetNumVertices());
    OsdPoint* dst = osdPoints[l].data();
    primvar.Interpolate(l, osdPoints[l - 1].data(), dst);
  }

  std::vector<OsdLevelResult> results(levels + 1);
  for (int l = 0; l <= levels; ++l) {
    const int n = ours.level(l).numVertices;
    results[l].points.resize(n);
    for (int v = 0; v < n; ++v) results[l].points[v] = toVec(osdPoints[l][maps[l][v]]);
  }
  if (!withLimit) return results;

  // Limit() applies to the last level only: one refiner per level.
  for (int l = 0; l <= levels; ++l) {
    auto levelRefiner = makeRefiner(topology, options, l);
    Far::PrimvarRefiner levelPrimvar(*levelRefiner);
    std::vector<OsdPoint> pts = osdPoints[0], next;
    for (int k = 1; k <= l; ++k) {
      next.assign(levelRefiner->GetLevel(k).GetNumVertices(), OsdPoint{});
      OsdPoint* dst = next.data();
      levelPrimvar.Interpolate(k, pts.data(), dst);
      pts.swap(next);
    }
    const int count = levelRefiner->GetLevel(l).GetNumVertices();
    std::vector<OsdPoint> pos(count), t1(count), t2(count);
    OsdPoint *posOut = pos.data(), *t1Out = t1.data(), *t2Out = t2.data();
    levelPrimvar.Limit(pts.data(), posOut, t1Out, t2Out);
    // Same topology as the full refiner, so the same vertex map applies.
    const int n = ours.level(l).numVertices;
    results[l].limitPositions.resize(n);
    results[l].limitTangent1.resize(n);
    results[l].limitTangent2.resize(n);
    for (int v = 0; v < n; ++v) {
      results[l].limitPositions[v] = toVec(pos[maps[l][v]]);
      results[l].limitTangent1[v] = toVec(t1[maps[l][v]]);
      results[l].limitTangent2[v] = toVec(t2[maps[l][v]]);
    }
  }
  return results;
}

}  // namespace tessera::oracle

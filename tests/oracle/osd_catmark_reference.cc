#include "oracle/osd_catmark_reference.h"

#include <set>
#include <stdexcept>
#include <string>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include "core/catmark/quad_split.h"
#include "core/loop/local_frame.h"

namespace tessera::oracle {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

OsdPolyInput::OsdPolyInput(const PolyTopology& topology) {
  for (int f = 0; f < topology.numFaces(); ++f) {
    vertsPerFace_.push_back(topology.faceOffsets[f + 1] - topology.faceOffsets[f]);
  }
  indices_ = topology.indices;
  for (const auto& c : topology.creases) {
    creasePairs_.push_back(c.v0);
    creasePairs_.push_back(c.v1);
    creaseWeights_.push_back(c.sharpness);
  }
  for (size_t v = 0; v < topology.vertexSharpness.size(); ++v) {
    if (topology.vertexSharpness[v] > 0.0f) {
      cornerIndices_.push_back(static_cast<int>(v));
      cornerWeights_.push_back(topology.vertexSharpness[v]);
    }
  }
  descriptor_.numVertices = topology.numVertices;
  descriptor_.numFaces = topology.numFaces();
  descriptor_.numVertsPerFace = vertsPerFace_.data();
  descriptor_.vertIndicesPerFace = indices_.data();
  descriptor_.numCreases = static_cast<int>(creaseWeights_.size());
  descriptor_.creaseVertexIndexPairs = creasePairs_.data();
  descriptor_.creaseWeights = creaseWeights_.data();
  descriptor_.numCorners = static_cast<int>(cornerWeights_.size());
  descriptor_.cornerVertexIndices = cornerIndices_.data();
  descriptor_.cornerWeights = cornerWeights_.data();
}

namespace {

void throwOnOsdError(Far::ErrorType, const char* message) {
  throw std::runtime_error(std::string("OpenSubdiv: ") + message);
}

// map[l][ourVertex] = OpenSubdiv's vertex, level by level through children:
// vertices by GetVertexChildVertex, faces by GetFaceChildFaces (child j at
// corner j) and GetFaceChildVertex, edges by FindEdge and GetEdgeChildVertex.
std::vector<std::vector<int>> vertexMaps(const Far::TopologyRefiner& osd, const schemes::QuadRefiner& ours,
                                         int levels) {
  std::vector<std::vector<int>> maps(levels + 1);
  std::vector<int> faceMap(ours.level(0).numFaces());
  for (size_t f = 0; f < faceMap.size(); ++f) faceMap[f] = static_cast<int>(f);
  maps[0].resize(ours.level(0).numVertices);
  for (int v = 0; v < ours.level(0).numVertices; ++v) maps[0][v] = v;
  for (int l = 0; l < levels; ++l) {
    const Level& parent = ours.level(l);
    const Far::TopologyLevel& osdParent = osd.GetLevel(l);
    auto& next = maps[l + 1];
    next.assign(ours.level(l + 1).numVertices, -1);
    std::vector<int> nextFaceMap(ours.level(l + 1).numFaces(), -1);
    for (int v = 0; v < parent.numVertices; ++v) next[v] = osdParent.GetVertexChildVertex(maps[l][v]);
    for (int f = 0; f < parent.numFaces(); ++f) {
      const int of = faceMap[f];
      next[faceChildVertex(parent, f)] = osdParent.GetFaceChildVertex(of);
      auto ourCorners = parent.faceVerticesOf(f);
      auto osdCorners = osdParent.GetFaceVertices(of);
      auto children = osdParent.GetFaceChildFaces(of);
      if (osdCorners.size() != static_cast<int>(ourCorners.size()))
        throw std::runtime_error("face sizes differ");
      for (int j = 0; j < osdCorners.size(); ++j) {
        if (osdCorners[j] != maps[l][ourCorners[j]]) {
          throw std::runtime_error("face corners differ at level " + std::to_string(l));
        }
        nextFaceMap[parent.faceBegin(f) + j] = children[j];
      }
    }
    for (int e = 0; e < parent.numEdges(); ++e) {
      const int osdEdge =
          osdParent.FindEdge(maps[l][parent.edgeVertices[e][0]], maps[l][parent.edgeVertices[e][1]]);
      if (osdEdge < 0) throw std::runtime_error("edge missing in OpenSubdiv at level " + std::to_string(l));
      next[edgeChildVertex(parent, e)] = osdParent.GetEdgeChildVertex(osdEdge);
    }
    faceMap.swap(nextFaceMap);
  }
  return maps;
}

Vec3 toVec3(const OsdDoublePoint& p) {
  return Vec3(p.x, p.y, p.z);
}

}  // namespace

std::unique_ptr<Far::TopologyRefiner> createOsdQuadRefiner(const OsdPolyInput& input,
                                                           schemes::QuadScheme scheme,
                                                           const CreaseOptions& options, int levels,
                                                           bool fullTopologyInLastLevel) {
  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(options.boundary == BoundaryInterpolation::kEdgeOnly
                                      ? Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                                      : Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  sdc.SetCreasingMethod(options.creaseMethod == CreaseMethod::kUniform ? Sdc::Options::CREASE_UNIFORM
                                                                       : Sdc::Options::CREASE_CHAIKIN);
  const Sdc::SchemeType type =
      scheme == schemes::QuadScheme::kBilinear ? Sdc::SCHEME_BILINEAR : Sdc::SCHEME_CATMARK;
  Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Options factoryOptions(type, sdc);
  Far::SetErrorCallback(throwOnOsdError);
  std::unique_ptr<Far::TopologyRefiner> refiner(
      Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Create(input.descriptor(), factoryOptions));
  if (!refiner) throw std::runtime_error("OpenSubdiv refused the topology");
  Far::TopologyRefiner::UniformOptions uniform(levels);
  uniform.fullTopologyInLastLevel = fullTopologyInLastLevel;
  refiner->RefineUniform(uniform);
  return refiner;
}

std::vector<OsdDoublePoint> interpolateOsdDouble(const Far::TopologyRefiner& refiner,
                                                 std::span<const OsdDoublePoint> basePoints, int level) {
  Far::PrimvarRefinerReal<double> primvar(refiner);
  std::vector<OsdDoublePoint> current(basePoints.begin(), basePoints.end()), next;
  for (int l = 1; l <= level; ++l) {
    next.assign(refiner.GetLevel(l).GetNumVertices(), OsdDoublePoint{});
    OsdDoublePoint* dst = next.data();
    primvar.Interpolate(l, current.data(), dst);
    current.swap(next);
  }
  return current;
}

std::vector<OsdQuadLevel> refineQuadsWithOpenSubdiv(const PolyTopology& topology,
                                                    std::span<const Vec3> basePoints,
                                                    const CreaseOptions& options,
                                                    const schemes::QuadRefiner& ours, bool withLimit,
                                                    int firstLimitLevel, const OsdLevelEdit& edit) {
  const int levels = ours.maxLevel();
  const OsdPolyInput input(topology);
  auto refiner = createOsdQuadRefiner(input, ours.scheme(), options, levels, true);
  const auto maps = vertexMaps(*refiner, ours, levels);
  const Far::PrimvarRefinerReal<double> primvar(*refiner);
  std::vector<OsdDoublePoint> current, next;  // OpenSubdiv's numbering
  for (const Vec3& p : basePoints) current.push_back({p[0], p[1], p[2]});

  std::vector<OsdQuadLevel> results(levels + 1);
  for (int l = 0; l <= levels; ++l) {
    if (l > 0) {
      next.assign(refiner->GetLevel(l).GetNumVertices(), OsdDoublePoint{});
      OsdDoublePoint* dst = next.data();
      primvar.Interpolate(l, current.data(), dst);
      current.swap(next);
    }
    const int count = refiner->GetLevel(l).GetNumVertices();
    const int n = ours.level(l).numVertices;
    if (count != n) throw std::runtime_error("vertex counts differ at level " + std::to_string(l));
    auto& r = results[l];
    r.points.resize(n);
    for (int v = 0; v < n; ++v) r.points[v] = toVec3(current[maps[l][v]]);
    if (edit) {
      edit(l, r.points);
      for (int v = 0; v < n; ++v) current[maps[l][v]] = {r.points[v][0], r.points[v][1], r.points[v][2]};
    }
    if (!withLimit || l < firstLimitLevel) continue;
    // Limit() applies to the last level only: a refiner that stops at l
    // (vertex numbering up to level l does not depend on deeper levels).
    std::unique_ptr<Far::TopologyRefiner> owned =
        l == levels ? nullptr : createOsdQuadRefiner(input, ours.scheme(), options, l, true);
    const Far::TopologyRefiner& levelRefiner = l == levels ? *refiner : *owned;
    std::vector<OsdDoublePoint> pos(count), t1(count), t2(count);
    OsdDoublePoint *posOut = pos.data(), *t1Out = t1.data(), *t2Out = t2.data();
    Far::PrimvarRefinerReal<double>(levelRefiner).Limit(current.data(), posOut, t1Out, t2Out);
    r.limitPositions.resize(n);
    r.limitTangent1.resize(n);
    r.limitTangent2.resize(n);
    for (int v = 0; v < n; ++v) {
      r.limitPositions[v] = toVec3(pos[maps[l][v]]);
      r.limitTangent1[v] = toVec3(t1[maps[l][v]]);
      r.limitTangent2[v] = toVec3(t2[maps[l][v]]);
    }
  }
  return results;
}

PolyTopology taggedTopology(const PolyTopology& baseTopology, const Level& base,
                            std::span<const Edit> edits) {
  PolyTopology topology = baseTopology;
  topology.vertexSharpness.resize(static_cast<size_t>(base.numVertices), 0.0f);
  std::set<Index> taggedEdges, taggedVertices;
  for (const Edit& edit : edits) {
    if (!edit.active || std::holds_alternative<MoveEdit>(edit.change)) continue;
    if (edit.level() != 0) throw std::invalid_argument("a sharpness edit below the base level");
    if (const auto* e = std::get_if<EdgeSharpnessEdit>(&edit.change)) {
      const auto at = static_cast<Index>(e->edge.index());
      if (!taggedEdges.insert(at).second) throw std::invalid_argument("a second tag of one edge");
      const auto& ends = base.edgeVertices[at];
      topology.creases.push_back({ends[0], ends[1], e->sharpness});
    } else if (const auto* v = std::get_if<VertexSharpnessEdit>(&edit.change)) {
      if (!taggedVertices.insert(static_cast<Index>(v->vertex.index())).second)
        throw std::invalid_argument("a second tag of one vertex");
      topology.vertexSharpness[v->vertex.index()] = v->sharpness;
    } else {
      throw std::invalid_argument("an edit Far cannot state");
    }
  }
  return topology;
}

std::vector<OsdQuadLevel> refineEditedQuadsWithOpenSubdiv(const PolyTopology& baseTopology,
                                                          std::span<const Vec3> basePoints,
                                                          const CreaseOptions& options,
                                                          const schemes::QuadRefiner& ours,
                                                          std::span<const Edit> edits) {
  const Level& base = ours.level(0);
  const PolyTopology topology = taggedTopology(baseTopology, base, edits);
  auto moveLevel = [&](int l, std::vector<Vec3>& points) {
    const std::vector<Vec3> predicted = points;
    for (const Edit& edit : edits) {
      const auto* move = std::get_if<MoveEdit>(&edit.change);
      if (move == nullptr || !edit.active || edit.level() != l) continue;
      for (const VertexOffset& o : move->offsets) {
        const auto v = static_cast<Index>(o.vertex.index());
        points[v] += localFrame(ours.level(l), v, predicted).toWorld(o.localOffset);
      }
    }
  };
  // Far's Limit() needs a level of quads: level 0 only where the base is one.
  const int firstLimitLevel = base.regularFaceSize == 4 ? 0 : 1;
  return refineQuadsWithOpenSubdiv(topology, basePoints, options, ours, true, firstLimitLevel, moveLevel);
}

}  // namespace tessera::oracle

#include "oracle/osd_adapter.h"

#include <stdexcept>
#include <string>

namespace tessera::oracle {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

OsdInput::OsdInput(const BaseTopology& topology) {
  vertsPerFace_.assign(topology.triangles.size(), 3);
  indices_.reserve(topology.triangles.size() * 3);
  for (const auto& t : topology.triangles) indices_.insert(indices_.end(), t.begin(), t.end());
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
  descriptor_.numFaces = static_cast<int>(topology.triangles.size());
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

}  // namespace

std::unique_ptr<Far::TopologyRefiner> createOsdRefiner(const OsdInput& input, const LoopOptions& options,
                                                       int levels, bool fullTopologyInLastLevel) {
  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(options.boundary == BoundaryInterpolation::kEdgeOnly
                                      ? Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                                      : Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  sdc.SetCreasingMethod(options.creaseMethod == CreaseMethod::kUniform ? Sdc::Options::CREASE_UNIFORM
                                                                       : Sdc::Options::CREASE_CHAIKIN);
  Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Options factoryOptions(Sdc::SCHEME_LOOP, sdc);
  Far::SetErrorCallback(throwOnOsdError);
  std::unique_ptr<Far::TopologyRefiner> refiner(
      Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Create(input.descriptor(), factoryOptions));
  if (!refiner) throw std::runtime_error("OpenSubdiv refused the topology");
  Far::TopologyRefiner::UniformOptions uniform(levels);
  // Limit() silently does nothing without full topology in the last level.
  uniform.fullTopologyInLastLevel = fullTopologyInLastLevel;
  refiner->RefineUniform(uniform);
  return refiner;
}

std::vector<OsdPoint> interpolateOsd(const Far::TopologyRefiner& refiner,
                                     std::span<const OsdPoint> basePoints, int level) {
  Far::PrimvarRefiner primvar(refiner);
  std::vector<OsdPoint> current(basePoints.begin(), basePoints.end()), next;
  for (int l = 1; l <= level; ++l) {
    next.assign(refiner.GetLevel(l).GetNumVertices(), OsdPoint{});
    OsdPoint* dst = next.data();
    primvar.Interpolate(l, current.data(), dst);
    current.swap(next);
  }
  return current;
}

}  // namespace tessera::oracle

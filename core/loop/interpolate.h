// Applies Loop refinement to vertex data: child points from parent points.
//
// LoopStencils evaluates one child vertex at a time from the parent level
// alone -- what the child inherits (sharpness, rules) is derived on the fly
// (sharpness_inheritance.h) -- so the same stencils serve uniform levels and
// the sparse, incrementally updated hierarchy (core/hierarchy/).
#pragma once

#include <span>
#include <vector>

#include "core/loop/loop_options.h"
#include "core/loop/sharpness_inheritance.h"
#include "core/topology/level.h"
#include "core/util/vec3.h"

namespace tessera {

class LoopStencils {
 public:
  LoopStencils(const Level& parent, const LoopOptions& options);

  // The child of parent vertex v; v's ring must be complete.
  Vec3 vertexChild(Index v, std::span<const Vec3> p);
  // The vertex on parent edge e; both faces of e must be present.
  Vec3 edgeChild(Index e, std::span<const Vec3> p);

 private:
  Vec3 vertexPointForRule(Index v, VertexRule rule, const float* ringSharpness,
                          std::span<const Vec3> p) const;

  const Level& parent_;
  SharpnessInheritance inherit_;
  std::vector<double> smoothWeight_;  // beta(n) by valence
  std::vector<float> parentSharpness_, childSharpness_;
};

// Uniform numbering (refinement.h): parent vertex v -> child v, parent edge
// e -> child numVertices + e. `childPoints` holds at least V + E points.
void interpolateLevel(const Level& parent, const LoopOptions& options, std::span<const Vec3> parentPoints,
                      std::span<Vec3> childPoints);

}  // namespace tessera

// What a child level inherits from its parent's sharpness (Sdc semantics:
// uniform decay or Chaikin's rule at semi-sharp ends), computed from the
// parent alone. Refinement uses it to fill a child level; interpolation uses
// it to know the child's rules without reading the child, so tags set on a
// level after it was refined change how it refines, never how it was
// predicted (document_evaluator.h).
#pragma once

#include <vector>

#include "core/loop/crease.h"
#include "core/loop/loop_options.h"
#include "core/topology/level.h"

namespace tessera {

class SharpnessInheritance {
 public:
  SharpnessInheritance(const Level& parent, const LoopOptions& options);

  // Sharpness of the half of parent edge e at its end `end` (0 or 1). Reads
  // that end vertex's ring only for Chaikin decay of a semi-sharp edge.
  float halfSharpness(Index e, int end);
  // Sharpness and rule of the child of parent vertex v (v's ring complete).
  float vertexChildSharpness(Index v) const { return decrementSharpness(parent_.vertexSharpness[v]); }
  VertexRule vertexChildRule(Index v);
  // Rule of the vertex on parent edge e: crease if both halves stay sharp,
  // dart if one does.
  VertexRule edgeChildRule(Index e);

 private:
  const Level& parent_;
  CreaseMethod method_;
  std::vector<float> ring_;
};

}  // namespace tessera

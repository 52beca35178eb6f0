// Catmull-Clark's new points one at a time from the parent level alone, for
// levels that hold only part of the uniform one (the sparse hierarchy,
// core/hierarchy/sparse_level.h), as core/loop/interpolate.h's
// LoopStencils for Loop. The child's rules and sharpness come from the
// parent's by Sdc's inheritance (core/loop/sharpness_inheritance.h), never
// from the child: tags set on a child level change how it refines, not how
// it was predicted. Each point equals the uniform refinement's
// (core/catmark/interpolate.h; both compute through point_rules.h).
#pragma once

#include <span>
#include <vector>

#include "core/loop/loop_options.h"
#include "core/loop/sharpness_inheritance.h"
#include "core/topology/level.h"
#include "core/util/vec3.h"

namespace tessera {

class CatmarkStencils {
 public:
  CatmarkStencils(const Level& parent, const LoopOptions& options);

  // The vertex in parent face f (present).
  Vec3 faceChild(Index f, std::span<const Vec3> p) const;
  // The vertex on parent edge e; both faces of e must be present.
  Vec3 edgeChild(Index e, std::span<const Vec3> p);
  // The child of parent vertex v; v's ring must be complete.
  Vec3 vertexChild(Index v, std::span<const Vec3> p);

 private:
  const Level& parent_;
  SharpnessInheritance inherit_;
  std::vector<float> parentSharpness_, childSharpness_;
};

}  // namespace tessera

// Builds the base Level (level 0) of a triangle mesh for the Loop scheme:
// the triangles go through the one topology builder (core/topology/
// level_builder.h), the creases, corners and boundary rules through the one
// tag applier (core/topology/tags.h), as for every other scheme.
#pragma once

#include <array>
#include <vector>

#include "core/loop/loop_options.h"
#include "core/mesh/base_mesh.h"
#include "core/topology/level.h"
#include "core/topology/tags.h"
#include "core/util/status.h"

namespace tessera {

struct BaseTopology {
  int numVertices = 0;
  std::vector<std::array<int, 3>> triangles;
  using Crease = topology::Crease;
  std::vector<Crease> creases;
  std::vector<float> vertexSharpness;  // empty, or one per vertex

  static BaseTopology fromBaseMesh(const BaseMesh& mesh);
};

// Errors (never asserts) on non-manifold or inconsistently oriented input,
// unused vertices, out-of-range indices and creases on missing edges.
Expected<Level> buildBaseLevel(const BaseTopology& topology, const LoopOptions& options);

}  // namespace tessera

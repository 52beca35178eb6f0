// Builds the base Level (level 0) from triangles and feature tags, applying
// the boundary rules: boundary edges become infinitely sharp, and with
// kEdgeAndCorner a boundary vertex with a single face becomes a corner
// (Sdc's prepareComponentTagsAndSharpness semantics).
#pragma once

#include <array>
#include <vector>

#include "core/loop/level.h"
#include "core/loop/loop_options.h"
#include "core/mesh/base_mesh.h"
#include "core/util/status.h"

namespace tessera {

struct BaseTopology {
  int numVertices = 0;
  std::vector<std::array<int, 3>> triangles;
  struct Crease {
    int v0, v1;
    float sharpness;
  };
  std::vector<Crease> creases;
  std::vector<float> vertexSharpness;  // empty, or one per vertex

  static BaseTopology fromBaseMesh(const BaseMesh& mesh);
};

// Errors (never asserts) on non-manifold or inconsistently oriented input,
// unused vertices, out-of-range indices and creases on missing edges.
Expected<Level> buildBaseLevel(const BaseTopology& topology, const LoopOptions& options);

}  // namespace tessera

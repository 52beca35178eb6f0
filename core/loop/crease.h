// Pure sharpness rules: how sharpness decays per level and which vertex rule
// applies. Semantics of OpenSubdiv 3.5's Sdc::Crease; the vertex rules by
// number of sharp edges are those of Hoppe et al. '94 (Pulli & Lounsbery,
// "Hierarchical Editing and Rendering of Subdivision Surfaces" §2.4):
// 0 smooth, 1 dart, 2 crease, 3+ corner; a sharp vertex is a corner (or a cusp
// when no sharp edge meets it -- the corner mask serves both).
#pragma once

#include <cstdint>
#include <span>

#include "core/loop/loop_options.h"
#include "core/mesh/sharpness.h"

namespace tessera {

enum class VertexRule : uint8_t {
  kSmooth = 1,
  kDart = 2,
  kCrease = 4,
  kCorner = 8,
};

inline bool isSmoothLike(VertexRule r) {
  return r == VertexRule::kSmooth || r == VertexRule::kDart;
}

float decrementSharpness(float s);

VertexRule vertexRule(float vertexSharpness, int sharpEdgeCount);

// Sharpness of the child of an edge with sharpness `edgeSharpness` at one of
// its end vertices, whose incident edges have `sharpnessAtVertex`.
float subdivideEdgeSharpnessAtVertex(CreaseMethod method, float edgeSharpness,
                                     std::span<const float> sharpnessAtVertex);

// The weight of the parent rule when a vertex changes rule between levels:
// the mean parent sharpness of the features that become smooth (Sdc's
// ComputeFractionalWeightAtVertex), so fractional sharpness blends the masks.
float fractionalWeightAtVertex(float parentVertexSharpness, float childVertexSharpness,
                               std::span<const float> parentEdgeSharpness,
                               std::span<const float> childEdgeSharpness);

// Ring positions of the first two sharp edges: the crease the vertex lies on.
// Requires at least two sharp entries.
void sharpEdgePair(std::span<const float> edgeSharpness, int ends[2]);

}  // namespace tessera

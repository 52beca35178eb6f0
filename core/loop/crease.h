// Pure sharpness rules: how sharpness decays per level. Semantics of
// OpenSubdiv 3.5's Sdc::Crease. Which vertex rule applies is shared by every
// scheme and the topology (core/mesh/sharpness.h).
#pragma once

#include <cstdint>
#include <span>

#include "core/loop/loop_options.h"
#include "core/mesh/sharpness.h"

namespace tessera {

float decrementSharpness(float s);

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

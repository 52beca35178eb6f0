// Options of the Loop scheme, mirroring OpenSubdiv 3.5's Sdc::Options for the
// subset that Loop uses, so that the same options give the same surface.
#pragma once

#include "core/mesh/sharpness.h"  // BoundaryInterpolation

namespace tessera {

// How semi-sharp edge sharpness decays from one level to the next.
enum class CreaseMethod {
  kUniform,  // s -> s - 1 (DeRose et al. '98); the default
  kChaikin,  // s -> 3/4 s + 1/4 avg(other semi-sharp at the vertex) - 1 (Sdc CREASE_CHAIKIN)
};

struct LoopOptions {
  CreaseMethod creaseMethod = CreaseMethod::kUniform;
  BoundaryInterpolation boundary = BoundaryInterpolation::kEdgeOnly;
};

}  // namespace tessera

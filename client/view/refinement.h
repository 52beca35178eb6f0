// Client-side refinement in tessera-view (docs/VIEWER.md, "Client-side
// refinement", after Kähler, Haber & Seidel, "Dynamic Refinement of
// Deformable Triangle Meshes for Rendering"): every frame the received
// regions are refined afresh, each on its own with the border normals of all
// (core/render), and streamed to the GPU. Nothing is kept between frames.
#pragma once

#include <cstdint>

#include "client/view/renderer.h"

namespace tessera::view {

struct RefineTiming {
  int64_t receivedTriangles = 0;
  double refineMs = 0, uploadMs = 0;  // this frame's refinement and its upload
};

// Refines `regions` with at most `splits` splits per edge and streams the
// result to `renderer`. A refinement error is printed and nothing is drawn
// anew (the regions come from the decoder, which checks them).
RefineTiming refineAndStream(const RegionMap& regions, int splits, Renderer& renderer);

}  // namespace tessera::view

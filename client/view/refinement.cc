#include "client/view/refinement.h"

#include <chrono>
#include <cstdio>
#include <vector>

namespace tessera::view {

RefineTiming refineAndStream(const RegionMap& regions, int splits, Renderer& renderer) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  RefineTiming timing;
  std::vector<RefineInput> inputs;
  inputs.reserve(regions.size());
  for (const auto& [id, m] : regions) {
    inputs.push_back({m->positions, m->normals, m->triangles});
    timing.receivedTriangles += static_cast<int64_t>(m->triangles.size());
  }
  auto refined = refineMeshes(inputs, {.maxSplits = splits});
  const auto refinedAt = Clock::now();
  if (!refined.isOk()) {
    std::fprintf(stderr, "tessera-view: refinement: %s\n", refined.status().toString().c_str());
    return timing;
  }
  renderer.stream(regions, *refined);
  timing.refineMs = std::chrono::duration<double, std::milli>(refinedAt - start).count();
  timing.uploadMs = std::chrono::duration<double, std::milli>(Clock::now() - refinedAt).count();
  return timing;
}

}  // namespace tessera::view

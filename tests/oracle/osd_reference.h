// OpenSubdiv 3.5 as the reference oracle: refines the same base topology with
// Far::TopologyRefiner + PrimvarRefiner (double-precision points, float
// weights) and reports results in Tessera's vertex numbering, found by
// following parent-to-child relations level by level (never by assuming both
// number vertices alike).
#pragma once

#include <vector>

#include "core/loop/level_builder.h"
#include "core/loop/loop_options.h"
#include "core/loop/loop_refiner.h"
#include "core/util/vec3.h"

namespace tessera::oracle {

struct OsdLevelResult {
  std::vector<Vec3> points;          // refined control points, Tessera numbering
  std::vector<Vec3> limitPositions;  // PrimvarRefiner::Limit at this level
  std::vector<Vec3> limitTangent1;
  std::vector<Vec3> limitTangent2;
};

// Results for levels 0..levels; limit data for every level when withLimit.
// `ours` supplies Tessera's per-level topology for the vertex mapping.
std::vector<OsdLevelResult> refineWithOpenSubdiv(const BaseTopology& topology,
                                                 std::span<const Vec3> basePoints, const LoopOptions& options,
                                                 const LoopRefiner& ours, bool withLimit);

}  // namespace tessera::oracle

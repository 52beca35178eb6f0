// From-scratch evaluation of a document: every level of the uniform
// hierarchy up to the requested level, with the active edits applied level
// by level. This is the reference semantics of a document; faster
// incremental evaluators must agree with it.
//
// Level l is built as:
//   topology and sharpness refined from level l-1 (level 0: the base mesh)
//   by the document's scheme;
//   predicted points interpolated from level l-1 (level 0: the base points),
//   with, under Loop, the ghost rings of level l-1's interpolating vertices
//   written over them (core/loop/ghost_ring.h);
//   sharpness edits of level l applied and vertex rules recomputed (they
//   govern how level l refines and its limit, not how it was predicted);
//   each vertex offset of level l added in the vertex's local frame
//   computed from the *predicted* points (so frames depend on coarser data
//   only, and detail follows coarse edits).
#pragma once

#include <span>
#include <vector>

#include "core/catmark/polygon_level.h"
#include "core/hierarchy/edit.h"
#include "core/loop/level_builder.h"
#include "core/loop/loop_options.h"
#include "core/topology/level.h"
#include "core/util/status.h"

namespace tessera {

struct Evaluation {
  std::vector<Level> levels;
  std::vector<std::vector<Vec3>> predicted;  // per level, before that level's offsets
  std::vector<std::vector<Vec3>> points;     // per level, with offsets
};

// A Loop document.
Expected<Evaluation> evaluateDocument(const BaseTopology& base, std::span<const Vec3> basePoints,
                                      const LoopOptions& options, std::span<const Edit> edits, int level);
// A Catmull-Clark document: level 1 splits every polygon into quads
// (core/catmark/quad_split.h), whose points follow Catmull-Clark's rules
// with Sdc's creases (core/catmark/interpolate.h); no ghost rings, which
// are Loop's.
Expected<Evaluation> evaluateCatmarkDocument(const PolyTopology& base, std::span<const Vec3> basePoints,
                                             const CreaseOptions& options, std::span<const Edit> edits,
                                             int level);

}  // namespace tessera

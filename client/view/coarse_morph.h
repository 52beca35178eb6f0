// The coarse morph stream in tessera-view (way (b) of docs/PROTOCOL.md
// section 14, "The coarse stream"): while a morph plays, the viewer asks for
// the control points at each frame's t (GetMorphControl, about 12 bytes per
// base vertex) and evaluates the Loop limit surface itself, instead of
// receiving every region of every frame (docs/PERFORMANCE.md, "Streaming a
// morph", measures both). What it shows leaves out the keys' finer edits;
// paused, the viewer subscribes at t and shows the exact surface again.
#pragma once

#include "core/document/document.h"
#include "core/tessellation/region_codec.h"
#include "protocol/tessera.pb.h"

namespace tessera::view {

// The base triangles, tags and options of a MorphControl sent with_topology.
struct CoarseMorphBase {
  BaseTopology topology;
  DocumentOptions options;
};

// Errors name the field that is inconsistent (a malformed reply).
Expected<CoarseMorphBase> coarseMorphBase(const wire::MorphControl& withTopology);

// The limit surface at `level` of the base on a frame's points, as one
// region: limit positions and normals, each vertex named by the id of its
// control vertex at its birth level (as the server's regions name them),
// crease copies by their original's.
Expected<RegionMesh> refineCoarseMorph(const CoarseMorphBase& base, const wire::MorphControl& frame,
                                       int level);

}  // namespace tessera::view

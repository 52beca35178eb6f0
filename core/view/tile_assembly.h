// Closing the cracks between tiles shown at different levels, on the
// receiving side (docs/VIEWS.md "Assembling tiles"): seed
// 000's method (Pulli & Lounsbery, "Hierarchical Editing and Rendering of
// Subdivision Surfaces" §3.2.2), the finer side's vertices moved onto the
// coarser side's edge. Tiles stay independent of their neighbours' levels,
// so each is encoded once and shared by every viewer; the receiver, which
// knows which tiles it shows, does the rest.
//
// Vertices are matched across tiles by id (the same id is the same limit
// point, bit for bit, in every tile). Along each boundary loop of a tile,
// a run of vertices that no other shown tile has, between two that one
// other tile has and joins by an edge, lies on that tile's coarser edge:
// each is put on the segment at its place along the run (the run has 2^k
// edges, so the places are the dyadic points a finer level would put
// there). A vertex on the surface's own boundary has no such neighbour and
// stays.
#pragma once

#include <vector>

#include "core/tessellation/region_codec.h"

namespace tessera {

// `tiles`: the meshes shown. Returns, per tile, its positions with those on
// a coarser neighbour's edge moved there (the others unchanged), and counts
// the vertices moved in `moved` when not null.
std::vector<std::vector<Vec3>> closeCracks(const std::vector<const RegionMesh*>& tiles,
                                           int64_t* moved = nullptr);

}  // namespace tessera

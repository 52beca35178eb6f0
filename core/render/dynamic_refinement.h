// Dynamic refinement for rendering (Kähler, Haber & Seidel, "Dynamic
// Refinement of Deformable Triangle Meshes for Rendering"; docs/VIEWER.md
// "Client-side refinement"): a viewer that subscribed to a coarse LOD splits each edge
// 0, 1 or 2 times where the limit normals at its ends bend apart, places the
// new points on a smooth curve through the ends (edge_split.h), and
// re-triangulates every triangle by table lookup (split_table.h). Nothing
// is kept between frames (the paper's §3): each frame refines what it received.
//
// Input:  one triangle mesh -- positions, unit normals (one per position),
//         counter-clockwise triangles -- such as a decoded RegionMesh, and
//         optionally the BorderEdges of all regions drawn with it.
// Output: the refined mesh: the input vertices first, unchanged and in
//         order, then the new points; triangles counter-clockwise.
//
// Edges are found by position, not by vertex index, because a region holds
// the two sides of a crease as two vertices at one position. Regions
// refined separately fit together without cracks: an edge's decision and
// points depend only on its ends (edge_split.h); where the two sides of an
// edge have different normals (a crease) and lie in different regions, each
// region learns the other's normals from a BorderEdges built over all of
// them. Without it, crease edges on region borders may crack.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/render/border_edges.h"
#include "core/render/edge_split.h"
#include "core/util/status.h"

namespace tessera {

struct RefineInput {
  std::span<const Vec3> positions;
  std::span<const Vec3> normals;
  std::span<const std::array<int, 3>> triangles;
};

struct RefinedMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<std::array<int, 3>> triangles;
  size_t originalVertices = 0;  // positions[0, originalVertices) are the input's
};

// Records the border edges of `mesh` (edges with one triangle in it) in
// `borders`, for refineMesh on its neighbours. Errors: as refineMesh's.
Status addBorderEdges(const RefineInput& mesh, BorderEdges& borders);

// Errors (invalidArgument): maxSplits outside 0..2, thresholds not finite
// or splitTwiceBelow above splitOnceBelow, normals not one per position, a
// triangle index out of range or repeated.
Expected<RefinedMesh> refineMesh(const RefineInput& mesh, const SplitCriterion& criterion,
                                 const BorderEdges* borders = nullptr);

// One frame of a viewer: every mesh (region) refined on its own, with the
// BorderEdges of all of them, so that together they stay crack-free.
Expected<std::vector<RefinedMesh>> refineMeshes(std::span<const RefineInput> meshes,
                                                const SplitCriterion& criterion);

}  // namespace tessera

// The system of "Interactively Morphing Irregularly Shaped Images Employing
// Subdivision Techniques" (§3, §5): morphing two images through a morph of
// 2D meshes in pixel coordinates (x right, y down, pixel (i, j) covering
// [i, i+1] x [j, j+1]).
//
// Frame t: the limit surface of the morph at t, its key-0 and key-1
// counterparts (the same vertices of the same level), and for every pixel of
// the output (A's size) whose centre lies in a triangle of the surface at t,
// the barycentric point of that triangle in key 0 sampled from A and in key 1
// sampled from B (bilinear), blended (1 - t) A + t B. Pixels outside the
// surface -- beside the shape and in its holes -- show the two images'
// backgrounds at that pixel, cross-dissolved the same way. At t = 0 the warp
// is the identity on A, at t = 1 on B.
//
// A surface whose triangles fold over (the paper's named failure: a
// triangle's orientation flips between key 0 and t) is no warp; frames that
// would show one are refused with the count and the first triangle.
#pragma once

#include <array>
#include <vector>

#include "core/document/document.h"
#include "core/io/png_image.h"
#include "core/util/status.h"

namespace tessera {

// A document's limit surface at a level, in the plane (x, y).
struct PlanarMesh {
  std::vector<std::array<double, 2>> points;
  std::vector<std::array<int, 3>> triangles;
};

Expected<PlanarMesh> planarLimitMesh(const Document& doc, int level);

// Triangles whose signed area has the other sign in `at` than in `reference`
// (or is zero), with the first of them.
struct Folds {
  int count = 0;
  int first = -1;
};
Folds foldsBetween(const PlanarMesh& reference, const PlanarMesh& at);

// One frame; the three meshes share their triangles.
Image morphFrame(const Image& a, const Image& b, const PlanarMesh& key0, const PlanarMesh& key1,
                 const PlanarMesh& at, double t);

}  // namespace tessera

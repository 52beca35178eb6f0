// How far one triangle mesh is from another: the geometric difference that
// client-side refinement trades against bytes (docs/VIEWER.md "Client-side
// refinement"), measured by the
// refinement tests and bench/refinement_bench.cc.
//
// Input:  an approximation and a reference (positions and triangles).
// Output: rms -- the area-weighted root mean square of the distance from
//         points spread over the approximation (10 per triangle: corners,
//         edge thirds and centroid) to the nearest point of the reference;
//         max -- the largest distance seen either way, from those points to
//         the reference and from the reference's vertices to the
//         approximation (a two-sided Hausdorff estimate, so missing or extra
//         surface counts too).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/util/vec3.h"

namespace tessera {

struct MeshView {
  std::span<const Vec3> positions;
  std::span<const std::array<int, 3>> triangles;
};

struct SurfaceDistance {
  double rms = 0;
  double max = 0;
};

SurfaceDistance surfaceDistance(const MeshView& approximation, const MeshView& reference);

// The point of triangle abc nearest to p (a corner of a degenerate one).
Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// Nearest-point queries against one mesh, through a uniform grid of cells
// about as wide as its triangles.
class NearestTriangle {
 public:
  // Queries must lie inside [lo, hi], which must hold the mesh.
  NearestTriangle(const MeshView& mesh, const Vec3& lo, const Vec3& hi);
  double distance(const Vec3& p) const;

 private:
  int cellIndex(int x, int y, int z) const { return (z * dims_[1] + y) * dims_[0] + x; }
  int cellOf(double t, int axis) const;

  MeshView mesh_;
  Vec3 lo_;
  double cell_ = 1;
  std::array<int, 3> dims_{};
  std::vector<int> start_;  // CSR: triangles of cell c are items_[start_[c], start_[c + 1])
  std::vector<int> items_;
};

}  // namespace tessera

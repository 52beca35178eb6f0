// Procedural export inputs shared by tests/core/mesh_export_test.cc and
// tests/tools/write_sample_glbs.cc (header-only so the validator tool needs no
// test-support library).
//
// makeTorusSurface(uSegments, vSegments): a closed, manifold torus (major
// radius 1, minor radius 0.35, centred off the origin so bounds are not
// symmetric) with exact unit normals, 2*u*v counter-clockwise triangles and
// u*v vertices. 100 x 50 gives 10,000 triangles.
#pragma once

#include <cmath>
#include <numbers>

#include "core/mesh/surface_mesh.h"

namespace tessera::testing {

inline SurfaceMesh makeTorusSurface(int uSegments, int vSegments) {
  constexpr double kMajor = 1.0;
  constexpr double kMinor = 0.35;
  const Vec3 centre(0.25, -0.5, 2.0);
  SurfaceMesh surface;
  for (int i = 0; i < uSegments; ++i) {
    const double u = 2.0 * std::numbers::pi * i / uSegments;
    for (int j = 0; j < vSegments; ++j) {
      const double v = 2.0 * std::numbers::pi * j / vSegments;
      const Vec3 normal(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
      const Vec3 ring(kMajor * std::cos(u), kMajor * std::sin(u), 0.0);
      surface.positions.push_back(centre + ring + kMinor * normal);
      surface.normals.push_back(normal);
    }
  }
  auto index = [&](int i, int j) { return (i % uSegments) * vSegments + (j % vSegments); };
  for (int i = 0; i < uSegments; ++i) {
    for (int j = 0; j < vSegments; ++j) {
      // d(position)/du x d(position)/dv points outwards, so (i,j) -> (i+1,j)
      // -> (i+1,j+1) is counter-clockwise seen from outside.
      const int a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      surface.triangles.push_back({a, b, c});
      surface.triangles.push_back({a, c, d});
    }
  }
  return surface;
}

}  // namespace tessera::testing

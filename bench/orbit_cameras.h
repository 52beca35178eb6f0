// Phone-sized cameras on orbits of their own around a mesh's bounding
// sphere (docs/PERFORMANCE.md "Views"): camera c of n at step s lies on a
// tilted circle, 0.7 to 3 bounding radii away, and moves a twentieth of a
// turn per step. The view benchmarks share them so that their figures
// describe the same cameras.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/mesh/base_mesh.h"
#include "core/view/view.h"

namespace tessera::bench {

struct OrbitCentre {
  Vec3 centre;
  double radius = 0;
};

// The bounding box's centre and half its diagonal.
inline OrbitCentre orbitCentreOf(const BaseMesh& mesh) {
  Vec3 lo = mesh.positions()[0], hi = lo;
  for (const Vec3& p : mesh.positions()) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  }
  return {0.5 * (lo + hi), 0.5 * (hi - lo).norm()};
}

// 390x844 pixels, 50 degrees high, tolerance 1 px.
inline View orbitCamera(const OrbitCentre& around, int c, int n, int s) {
  const double phase = 2 * std::numbers::pi * c / n + s * 2 * std::numbers::pi / 20;
  const double tilt = 0.6 * std::sin(3.0 * c);
  const double distance = around.radius * (0.7 + 2.3 * ((c * 37) % n) / static_cast<double>(n));
  const Vec3 dir(std::cos(phase) * std::cos(tilt), std::sin(tilt), std::sin(phase) * std::cos(tilt));
  View v;
  v.eye = around.centre + distance * dir;
  v.forward = around.centre - v.eye;
  v.fovYRadians = 50 * std::numbers::pi / 180;
  v.nearDistance = around.radius * 1e-3;
  v.width = 390;
  v.height = 844;
  v.tolerancePixels = 1;
  return v;
}

}  // namespace tessera::bench

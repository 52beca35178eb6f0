// A camera for the tests of view-dependent streaming (core/view/view.h): a
// perspective view from `eye` towards `target`, 50 degrees high, one
// pixel's tolerance, up along y unless the view looks nearly along it.
#pragma once

#include <cmath>
#include <numbers>

#include "core/view/view.h"

namespace tessera::testing {

inline View lookAt(const Vec3& eye, const Vec3& target, int width, int height, double nearDistance = 1e-4) {
  View v;
  v.eye = eye;
  v.forward = target - eye;
  v.up = std::abs(v.forward.normalized()[1]) > 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  v.fovYRadians = 50 * std::numbers::pi / 180;
  v.nearDistance = nearDistance;
  v.width = width;
  v.height = height;
  v.tolerancePixels = 1;
  return v;
}

}  // namespace tessera::testing

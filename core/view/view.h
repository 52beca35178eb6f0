// A viewer's camera, as a view-dependent subscription states it: where the
// eye is and where it looks, the projection, the viewport in pixels and the
// screen-space error it tolerates (docs/VIEWS.md). From it, how
// large a world-space error looks on the screen at a place, and whether a
// place can be seen at all -- the criteria of adaptive subdivision for
// rendering that depend on the viewer: screen size and the view frustum.
//
// The projected error is conservative: a bounding sphere is taken at its
// nearest depth in front of the eye (perspective), so an error anywhere in
// it looks no larger than stated. The frustum test is conservative the
// other way: a sphere is outside only when it lies wholly beyond one plane.
#pragma once

#include <array>
#include <cstdint>

#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera {

enum class Projection { kPerspective, kOrthographic };

// Bounds a view accepts (docs/VIEWS.md).
inline constexpr double kMinTolerancePixels = 0.25;
inline constexpr double kMaxTolerancePixels = 256;
inline constexpr int kMaxViewportPixels = 16384;

struct BoundingSphere {
  Vec3 centre;
  double radius = 0;
};

struct View {
  Vec3 eye;
  Vec3 forward{0, 0, -1};  // need not be unit; not parallel to up
  Vec3 up{0, 1, 0};
  Projection projection = Projection::kPerspective;
  double fovYRadians = 0.8;    // perspective: the vertical field of view, in (0, pi)
  double orthoHeight = 1.0;    // orthographic: the world height the viewport shows
  double nearDistance = 1e-3;  // in front of the eye; nothing nearer is drawn
  int width = 0, height = 0;   // viewport, pixels
  double tolerancePixels = 1.0;

  // Ok when every number is finite and in range; errors name the field and
  // the value: a zero or oversized viewport, a degenerate direction or
  // projection, a tolerance outside [kMinTolerancePixels, kMaxTolerancePixels].
  Status check() const;

  // How many pixels one world unit covers at the sphere's nearest depth in
  // front of the eye (never nearer than nearDistance).
  double pixelsPerUnit(const BoundingSphere& where) const;
  // A world-space error inside the sphere, in pixels.
  double projectedError(double worldError, const BoundingSphere& where) const {
    return worldError * pixelsPerUnit(where);
  }
  // Whether the sphere lies wholly outside the view frustum (behind the
  // near plane, or beyond a side plane). The far side is open.
  bool outside(const BoundingSphere& where) const;
};

}  // namespace tessera

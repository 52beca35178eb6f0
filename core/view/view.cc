#include "core/view/view.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace tessera {

namespace {

std::string text(double x) {
  return std::to_string(x);
}

// The camera's unit frame: f forward, r right, u up.
struct Frame {
  Vec3 f, r, u;
};

Frame frameOf(const View& v) {
  Frame frame;
  frame.f = v.forward.normalized();
  frame.r = cross(frame.f, v.up).normalized();
  frame.u = cross(frame.r, frame.f);
  return frame;
}

}  // namespace

Status View::check() const {
  if (!isFinite(eye)) return invalidArgument("view: the eye is not finite");
  if (!isFinite(forward) || forward.norm() < 1e-12)
    return invalidArgument("view: forward is zero or not finite");
  if (!isFinite(up) || up.norm() < 1e-12) return invalidArgument("view: up is zero or not finite");
  if (cross(forward.normalized(), up.normalized()).norm() < 1e-6)
    return invalidArgument("view: forward and up are parallel");
  if (width <= 0 || height <= 0 || width > kMaxViewportPixels || height > kMaxViewportPixels) {
    return invalidArgument("view: viewport " + std::to_string(width) + " x " + std::to_string(height) +
                           " pixels is outside 1.." + std::to_string(kMaxViewportPixels));
  }
  if (!(tolerancePixels >= kMinTolerancePixels && tolerancePixels <= kMaxTolerancePixels)) {
    return invalidArgument("view: tolerance " + text(tolerancePixels) + " pixels is outside [" +
                           text(kMinTolerancePixels) + ", " + text(kMaxTolerancePixels) + "]");
  }
  if (!(nearDistance > 0 && std::isfinite(nearDistance)))
    return invalidArgument("view: near distance " + text(nearDistance) + " must be positive and finite");
  if (projection == Projection::kPerspective) {
    if (!(fovYRadians > 1e-4 && fovYRadians < std::numbers::pi - 1e-4))
      return invalidArgument("view: vertical field of view " + text(fovYRadians) +
                             " radians is outside (0, pi)");
  } else if (!(orthoHeight > 0 && std::isfinite(orthoHeight))) {
    return invalidArgument("view: orthographic height " + text(orthoHeight) + " must be positive and finite");
  }
  return Status::ok();
}

double View::pixelsPerUnit(const BoundingSphere& where) const {
  if (projection == Projection::kOrthographic) return height / orthoHeight;
  const double depth = dot(where.centre - eye, forward.normalized()) - where.radius;
  return height / (2.0 * std::tan(fovYRadians / 2) * std::max(depth, nearDistance));
}

bool View::outside(const BoundingSphere& where) const {
  const Frame c = frameOf(*this);
  const Vec3 d = where.centre - eye;
  const double z = dot(d, c.f), x = dot(d, c.r), y = dot(d, c.u);
  if (z + where.radius < nearDistance) return true;
  if (projection == Projection::kOrthographic) {
    const double halfY = orthoHeight / 2, halfX = halfY * width / height;
    return std::abs(x) - where.radius > halfX || std::abs(y) - where.radius > halfY;
  }
  // Side planes through the eye: a sphere is beyond one when its centre's
  // distance to the plane exceeds its radius.
  const double ty = std::tan(fovYRadians / 2), tx = ty * width / height;
  const double ny = 1 / std::sqrt(1 + ty * ty), nx = 1 / std::sqrt(1 + tx * tx);
  return (std::abs(y) - ty * z) * ny > where.radius || (std::abs(x) - tx * z) * nx > where.radius;
}

}  // namespace tessera

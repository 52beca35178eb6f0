// OrbitCamera: a camera circling a target point (yaw, pitch, distance), with
// pan, zoom, framing of a bounding box, and the conversions picking needs
// between window pixels (origin top-left, y down) and world space.
#pragma once

#include <algorithm>
#include <optional>
#include <span>

#include "client/view/view_math.h"

namespace tessera::view {

struct Ray {
  V3 origin;
  V3 direction;  // unit
};

class OrbitCamera {
 public:
  void orbit(float dxPixels, float dyPixels);
  void pan(float dxPixels, float dyPixels, int viewportHeight);
  void zoom(float steps);  // > 0 moves closer
  // Fit to view from the current direction: the points' projection is
  // centred in the frame and, from the distance chosen, fills `fill` of it
  // in its tighter dimension (width or height, for this aspect ratio).
  // Nothing changes for no points.
  void fit(std::span<const V3> points, float aspect, float fill = 0.86f);
  // Looks at the XY plane from -Z with world -Y up: an image in pixel
  // coordinates (x right, y down, a 2D morph document's) reads as it does
  // on a screen. Orbiting from there keeps -Y up.
  void lookAtImagePlane() { yaw_ = 3.14159265f, pitch_ = 0, upSign_ = -1; }
  // fit() to the eight corners of a box.
  void frame(V3 lo, V3 hi, float aspect = 4.0f / 3.0f, float fill = 0.86f);

  V3 eye() const;
  V3 target() const { return target_; }
  float distance() const { return distance_; }
  float fovY() const { return kFovY; }
  // The projection's near plane (projection()).
  float nearDistance() const { return std::max(distance_ - 4 * radius_, distance_ * 0.01f); }
  Mat4 view() const;
  Mat4 projection(float aspect) const;
  // Pixels covered by one world unit at view depth 1, for this viewport height.
  float pixelsPerUnit(int height) const { return static_cast<float>(height) / (2 * std::tan(kFovY / 2)); }

  // The ray from the eye through a window pixel.
  Ray rayThrough(float px, float py, int width, int height) const;
  // The window pixel of a world point, or nothing behind the eye.
  std::optional<std::array<float, 2>> project(V3 p, int width, int height) const;

 private:
  V3 target_;
  float yaw_ = 0.6f, pitch_ = 0.45f, distance_ = 4.0f, radius_ = 1.0f;
  float upSign_ = 1;  // world +Y up, or -Y (lookAtImagePlane)
  // 30 degrees, as CAD viewers use: a fit-to-view close enough to fill the
  // frame with a wider angle would show strong perspective (a cube's top
  // seen almost edge-on).
  static constexpr float kFovY = 0.52f;  // radians
};

}  // namespace tessera::view

#include "client/view/camera.h"

#include <algorithm>

namespace tessera::view {

void OrbitCamera::orbit(float dxPixels, float dyPixels) {
  yaw_ -= dxPixels * 0.008f;
  pitch_ = std::clamp(pitch_ + dyPixels * 0.008f, -1.55f, 1.55f);
}

void OrbitCamera::pan(float dxPixels, float dyPixels, int viewportHeight) {
  // One pixel is this much world length at the target's depth.
  const float perPixel =
      2 * distance_ * std::tan(kFovY / 2) / static_cast<float>(std::max(viewportHeight, 1));
  const Mat4 v = view();
  const V3 right{v[0], v[4], v[8]}, up{v[1], v[5], v[9]};
  target_ = target_ - right * (dxPixels * perPixel) + up * (dyPixels * perPixel);
}

void OrbitCamera::zoom(float steps) {
  distance_ = std::clamp(distance_ * std::pow(0.9f, steps), radius_ * 0.01f, radius_ * 100);
}

void OrbitCamera::fit(std::span<const V3> points, float aspect, float fill) {
  if (points.empty()) return;
  V3 lo = points[0], hi = points[0];
  for (const V3& p : points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  radius_ = std::max(length(hi - lo) * 0.5f, 1e-6f);
  const V3 centre = (lo + hi) * 0.5f;
  const Mat4 v = lookAt(
      centre + V3{std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), std::cos(pitch_) * std::cos(yaw_)},
      centre, {0, upSign_, 0});
  const V3 right{v[0], v[4], v[8]}, up{v[1], v[5], v[9]}, back{v[2], v[6], v[10]};
  // The eye sits at centre + right * ex + up * ey + back * d, looking along
  // -back. A point at (x, y, z) in those axes around `centre` is at depth
  // d - z, and inside `fill` of the half-frame across when
  //   x - ex <= k (d - z)  and  x - ex >= -k (d - z),  k = fill * tan * aspect,
  // that is, ex in [max(x + k z) - k d, min(x - k z) + k d]. The interval
  // is not empty from d = (max(x + k z) - min(x - k z)) / (2k) on; there it
  // is one point, where the extreme points touch both sides. Likewise up
  // the frame. The larger d of the two fits; the other axis is centred in
  // its interval. Exact under perspective, where fitting a bounding sphere
  // or centring the box leaves the model small or off-centre.
  const float tanY = std::tan(kFovY / 2) * fill, tanX = tanY * std::max(aspect, 1e-3f);
  // Per axis: max(x + k z) and min(x - k z), and the depth offsets z of the
  // points that reach them.
  struct Extent {
    float hi = -1e30f, lo = 1e30f, zHi = 0, zLo = 0;
    void add(float x, float z, float k) {
      if (x + k * z > hi) hi = x + k * z, zHi = z;
      if (x - k * z < lo) lo = x - k * z, zLo = z;
    }
    float distance(float k) const { return (hi - lo) / (2 * k); }
    // The eye's offset in [hi - k d, lo + k d] that leaves the two extreme
    // points equally far from the frame's edges once projected, slack
    // shared in proportion to their depths.
    float offset(float k, float d) const {
      const float low = hi - k * d, high = lo + k * d;
      const float nearHi = d - zHi, nearLo = d - zLo;
      return low + (high - low) * nearHi / std::max(nearHi + nearLo, 1e-9f);
    }
  } across, upward;
  for (const V3& p : points) {
    const V3 q = p - centre;
    const float z = dot(q, back);
    across.add(dot(q, right), z, tanX);
    upward.add(dot(q, up), z, tanY);
  }
  const float d = std::max({across.distance(tanX), upward.distance(tanY), radius_ * 0.05f});
  const float ex = across.offset(tanX, d), ey = upward.offset(tanY, d);
  target_ = centre + right * ex + up * ey;
  distance_ = d;
}

void OrbitCamera::frame(V3 lo, V3 hi, float aspect, float fill) {
  std::array<V3, 8> corners;
  for (int c = 0; c < 8; ++c)
    corners[c] = {(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z};
  fit(corners, aspect, fill);
}

V3 OrbitCamera::eye() const {
  const V3 offset{std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), std::cos(pitch_) * std::cos(yaw_)};
  return target_ + offset * distance_;
}

Mat4 OrbitCamera::view() const {
  return lookAt(eye(), target_, {0, upSign_, 0});
}

Mat4 OrbitCamera::projection(float aspect) const {
  return perspective(kFovY, aspect, nearDistance(), distance_ + 4 * radius_);
}

Ray OrbitCamera::rayThrough(float px, float py, int width, int height) const {
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1));
  const float ndcX = 2 * px / static_cast<float>(width) - 1, ndcY = 1 - 2 * py / static_cast<float>(height);
  const float t = std::tan(kFovY / 2);
  const Mat4 v = view();
  const V3 right{v[0], v[4], v[8]}, up{v[1], v[5], v[9]}, back{v[2], v[6], v[10]};
  const V3 dir = normalize(right * (ndcX * t * aspect) + up * (ndcY * t) - back);
  return {eye(), dir};
}

std::optional<std::array<float, 2>> OrbitCamera::project(V3 p, int width, int height) const {
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1));
  const auto clip = transform(multiply(projection(aspect), view()), p);
  if (clip[3] <= 0) return std::nullopt;
  const float x = clip[0] / clip[3], y = clip[1] / clip[3];
  return std::array<float, 2>{(x + 1) * 0.5f * static_cast<float>(width),
                              (1 - y) * 0.5f * static_cast<float>(height)};
}

}  // namespace tessera::view

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

void OrbitCamera::frame(V3 lo, V3 hi, float aspect, float fill) {
  target_ = (lo + hi) * 0.5f;
  radius_ = std::max(length(hi - lo) * 0.5f, 1e-6f);
  // A corner at (x, y, z) in the camera's right/up/back axes around the
  // target is at depth d - z from an eye at distance d; it projects inside
  // `fill` of the half-frame when |x| <= fill * (d - z) * tan * aspect and
  // |y| <= fill * (d - z) * tan. The least such d over all corners is exact
  // (a bounding sphere would leave the box much smaller than the frame).
  const Mat4 v = lookAt(
      target_ + V3{std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), std::cos(pitch_) * std::cos(yaw_)},
      target_, {0, 1, 0});
  const V3 right{v[0], v[4], v[8]}, up{v[1], v[5], v[9]}, back{v[2], v[6], v[10]};
  const float t = std::tan(kFovY / 2) * fill;
  float d = 0;
  for (int c = 0; c < 8; ++c) {
    const V3 corner{(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z};
    const V3 p = corner - target_;
    const float x = std::abs(dot(p, right)), y = std::abs(dot(p, up)), z = dot(p, back);
    d = std::max(d, z + std::max(x / (t * std::max(aspect, 1e-3f)), y / t));
  }
  distance_ = std::max(d, radius_ * 0.05f);
}

V3 OrbitCamera::eye() const {
  const V3 offset{std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), std::cos(pitch_) * std::cos(yaw_)};
  return target_ + offset * distance_;
}

Mat4 OrbitCamera::view() const {
  return lookAt(eye(), target_, {0, 1, 0});
}

Mat4 OrbitCamera::projection(float aspect) const {
  return perspective(kFovY, aspect, std::max(distance_ - 4 * radius_, distance_ * 0.01f),
                     distance_ + 4 * radius_);
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

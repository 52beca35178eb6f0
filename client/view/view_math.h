// Small float maths for tessera-view: 3-vectors and column-major 4x4
// matrices in OpenGL's conventions (right-handed, clip z in [-1, 1]).
// Inputs and outputs are plain arrays so they upload with glUniform*fv.
#pragma once

#include <array>
#include <cmath>

namespace tessera::view {

struct V3 {
  float x = 0, y = 0, z = 0;
  V3 operator+(V3 o) const { return {x + o.x, y + o.y, z + o.z}; }
  V3 operator-(V3 o) const { return {x - o.x, y - o.y, z - o.z}; }
  V3 operator*(float s) const { return {x * s, y * s, z * s}; }
};

inline float dot(V3 a, V3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline V3 cross(V3 a, V3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(V3 a) {
  return std::sqrt(dot(a, a));
}
inline V3 normalize(V3 a) {
  const float n = length(a);
  return n > 0 ? a * (1.0f / n) : a;
}

// Column-major: element (row r, column c) is m[c * 4 + r].
using Mat4 = std::array<float, 16>;

inline Mat4 identity() {
  return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
}

inline Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      float s = 0;
      for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[c * 4 + k];
      r[c * 4 + row] = s;
    }
  return r;
}

inline Mat4 perspective(float fovyRadians, float aspect, float zNear, float zFar) {
  const float f = 1.0f / std::tan(fovyRadians / 2);
  Mat4 m{};
  m[0] = f / aspect;
  m[5] = f;
  m[10] = (zFar + zNear) / (zNear - zFar);
  m[11] = -1;
  m[14] = 2 * zFar * zNear / (zNear - zFar);
  return m;
}

inline Mat4 lookAt(V3 eye, V3 center, V3 up) {
  const V3 f = normalize(center - eye);
  const V3 s = normalize(cross(f, up));
  const V3 u = cross(s, f);
  Mat4 m = identity();
  m[0] = s.x, m[4] = s.y, m[8] = s.z;
  m[1] = u.x, m[5] = u.y, m[9] = u.z;
  m[2] = -f.x, m[6] = -f.y, m[10] = -f.z;
  m[12] = -dot(s, eye), m[13] = -dot(u, eye), m[14] = dot(f, eye);
  return m;
}

// Clip coordinates of a point: (x, y, z, w).
inline std::array<float, 4> transform(const Mat4& m, V3 p) {
  std::array<float, 4> r{};
  for (int row = 0; row < 4; ++row) r[row] = m[row] * p.x + m[4 + row] * p.y + m[8 + row] * p.z + m[12 + row];
  return r;
}

}  // namespace tessera::view

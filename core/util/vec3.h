// Vec3: the one 3-vector type of core. A plain struct of three doubles with
// the operations the geometry needs, written out per component so that hot
// subdivision loops compile to straight-line code. It converts implicitly
// to and from OpenMesh::Vec3d, the point type of the base mesh.
#pragma once

#include <cmath>

#include <OpenMesh/Core/Geometry/VectorT.hh>

namespace tessera {

struct Vec3 {
  double v[3] = {0.0, 0.0, 0.0};

  constexpr Vec3() = default;
  constexpr Vec3(double x, double y, double z) : v{x, y, z} {}
  Vec3(const OpenMesh::Vec3d& p) : v{p[0], p[1], p[2]} {}  // NOLINT: implicit by design
  operator OpenMesh::Vec3d() const { return OpenMesh::Vec3d(v[0], v[1], v[2]); }  // NOLINT

  constexpr double& operator[](int i) { return v[i]; }
  constexpr double operator[](int i) const { return v[i]; }
  double* data() { return v; }
  const double* data() const { return v; }

  Vec3& operator+=(const Vec3& o) {
    v[0] += o.v[0], v[1] += o.v[1], v[2] += o.v[2];
    return *this;
  }
  Vec3& operator-=(const Vec3& o) {
    v[0] -= o.v[0], v[1] -= o.v[1], v[2] -= o.v[2];
    return *this;
  }
  Vec3& operator*=(double s) {
    v[0] *= s, v[1] *= s, v[2] *= s;
    return *this;
  }
  Vec3& operator/=(double s) { return *this *= (1.0 / s); }

  double sqrnorm() const { return v[0] * v[0] + v[1] * v[1] + v[2] * v[2]; }
  double norm() const { return std::sqrt(sqrnorm()); }
  Vec3 normalized() const {
    const double n = norm();
    return n > 0.0 ? Vec3(v[0] / n, v[1] / n, v[2] / n) : *this;
  }
  Vec3& minimize(const Vec3& o) {
    for (int i = 0; i < 3; ++i) v[i] = o.v[i] < v[i] ? o.v[i] : v[i];
    return *this;
  }
  Vec3& maximize(const Vec3& o) {
    for (int i = 0; i < 3; ++i) v[i] = o.v[i] > v[i] ? o.v[i] : v[i];
    return *this;
  }
  double max() const { return v[0] > v[1] ? (v[0] > v[2] ? v[0] : v[2]) : (v[1] > v[2] ? v[1] : v[2]); }
  bool operator==(const Vec3& o) const { return v[0] == o.v[0] && v[1] == o.v[1] && v[2] == o.v[2]; }
};

inline Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3 operator-(const Vec3& a) {
  return {-a[0], -a[1], -a[2]};
}
inline Vec3 operator*(double s, const Vec3& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
inline Vec3 operator*(const Vec3& a, double s) {
  return {s * a[0], s * a[1], s * a[2]};
}
inline Vec3 operator/(const Vec3& a, double s) {
  return a * (1.0 / s);
}
// OpenMesh's spelling: | is the dot product, % the cross product.
inline double operator|(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 operator%(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a | b;
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return a % b;
}

inline bool isFinite(const Vec3& p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

}  // namespace tessera

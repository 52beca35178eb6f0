#include "core/morph/image_morph.h"

#include <algorithm>
#include <cmath>

#include "core/loop/limit.h"

namespace tessera {

namespace {

using P2 = std::array<double, 2>;

double cross(const P2& a, const P2& b, const P2& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

// Bilinear sample at pixel coordinates (centres at +0.5), clamped to the image.
std::array<double, 4> sample(const Image& image, double x, double y) {
  const double fx = std::clamp(x - 0.5, 0.0, image.width - 1.0),
               fy = std::clamp(y - 0.5, 0.0, image.height - 1.0);
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const int x1 = std::min(x0 + 1, image.width - 1), y1 = std::min(y0 + 1, image.height - 1);
  const double u = fx - x0, v = fy - y0;
  std::array<double, 4> out{};
  for (int c = 0; c < 4; ++c) {
    const double top = (1 - u) * image.at(x0, y0)[c] + u * image.at(x1, y0)[c];
    const double bottom = (1 - u) * image.at(x0, y1)[c] + u * image.at(x1, y1)[c];
    out[c] = (1 - v) * top + v * bottom;
  }
  return out;
}

void put(Image& out, int x, int y, const std::array<double, 4>& a, const std::array<double, 4>& b, double t) {
  uint8_t* p = out.at(x, y);
  for (int c = 0; c < 4; ++c)
    p[c] = static_cast<uint8_t>(std::clamp(std::lround((1 - t) * a[c] + t * b[c]), 0L, 255L));
}

// Top-left rule (as GPUs rasterise): a pixel centre on an edge shared by two
// triangles belongs to exactly one of them, so the output does not depend on
// the order the triangles are drawn in.
bool topLeft(const P2& a, const P2& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  return (dy == 0 && dx > 0) || dy < 0;
}

}  // namespace

Expected<PlanarMesh> planarLimitMesh(const Document& doc, int level) {
  TESSERA_ASSIGN_OR_RETURN(auto eval, doc.evaluate(level));
  const Level& m = eval->levels[level];
  PlanarMesh mesh;
  mesh.points.resize(m.numVertices);
  for (Index v = 0; v < m.numVertices; ++v) {
    const Vec3 p = limitFrame(m, v, eval->points[level], doc.options().loop.creaseMethod).position;
    mesh.points[v] = {p[0], p[1]};
  }
  for (Index f = 0; f < m.numFaces(); ++f) {
    const auto fv = m.triangleVertices(f);
    mesh.triangles.push_back({fv[0], fv[1], fv[2]});
  }
  return mesh;
}

Folds foldsBetween(const PlanarMesh& reference, const PlanarMesh& at) {
  Folds folds;
  for (size_t f = 0; f < reference.triangles.size(); ++f) {
    const auto& t = reference.triangles[f];
    const double before = cross(reference.points[t[0]], reference.points[t[1]], reference.points[t[2]]);
    const double now = cross(at.points[t[0]], at.points[t[1]], at.points[t[2]]);
    if (before * now > 0) continue;
    if (folds.count++ == 0) folds.first = static_cast<int>(f);
  }
  return folds;
}

Image morphFrame(const Image& a, const Image& b, const PlanarMesh& key0, const PlanarMesh& key1,
                 const PlanarMesh& at, double t) {
  Image out{a.width, a.height, std::vector<uint8_t>(a.rgba.size())};
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x)
      put(out, x, y, sample(a, x + 0.5, y + 0.5), sample(b, x + 0.5, y + 0.5), t);
  }
  for (const auto& tri : at.triangles) {
    P2 p[3] = {at.points[tri[0]], at.points[tri[1]], at.points[tri[2]]};
    int order[3] = {0, 1, 2};
    if (cross(p[0], p[1], p[2]) < 0) std::swap(order[1], order[2]);  // counter-clockwise in y-down pixels
    const P2 v0 = p[order[0]], v1 = p[order[1]], v2 = p[order[2]];
    const double area = cross(v0, v1, v2);
    if (!(area > 0)) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({v0[0], v1[0], v2[0]}) - 0.5)));
    const int x1 = std::min(out.width - 1, static_cast<int>(std::ceil(std::max({v0[0], v1[0], v2[0]}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({v0[1], v1[1], v2[1]}) - 0.5)));
    const int y1 = std::min(out.height - 1, static_cast<int>(std::ceil(std::max({v0[1], v1[1], v2[1]}))));
    const bool tl[3] = {topLeft(v1, v2), topLeft(v2, v0), topLeft(v0, v1)};
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const P2 c = {x + 0.5, y + 0.5};
        const double w[3] = {cross(v1, v2, c), cross(v2, v0, c), cross(v0, v1, c)};
        bool inside = true;
        for (int i = 0; i < 3; ++i) inside = inside && (w[i] > 0 || (w[i] == 0 && tl[i]));
        if (!inside) continue;
        P2 q0{0, 0}, q1{0, 0};
        for (int i = 0; i < 3; ++i) {
          const int vertex = tri[order[i]];
          const double l = w[i] / area;
          q0[0] += l * key0.points[vertex][0], q0[1] += l * key0.points[vertex][1];
          q1[0] += l * key1.points[vertex][0], q1[1] += l * key1.points[vertex][1];
        }
        put(out, x, y, sample(a, q0[0], q0[1]), sample(b, q1[0], q1[1]), t);
      }
    }
  }
  return out;
}

}  // namespace tessera

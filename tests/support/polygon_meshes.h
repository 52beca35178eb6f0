// Polygon meshes for the scheme tests (header only): quads, triangles and
// larger polygons, closed and open, plus random feature tags and jitter from
// fixed seeds, in the manner of procedural_meshes.h for triangles.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/catmark/polygon_level.h"
#include "core/util/vec3.h"

namespace tessera::testing {

struct PolyTestMesh {
  std::string name;
  PolyTopology topology;
  std::vector<Vec3> points;
};

inline PolyTestMesh makePoly(std::string name, std::vector<Vec3> points,
                             const std::vector<std::vector<int>>& faces) {
  PolyTestMesh m;
  m.name = std::move(name);
  m.points = std::move(points);
  m.topology.numVertices = static_cast<int>(m.points.size());
  for (const auto& f : faces) m.topology.addFace(f);
  return m;
}

inline PolyTestMesh quadCube() {
  return makePoly(
      "quad-cube",
      {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},
      {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}});
}

// An open, bumpy nu x nv grid of quads (a boundary with corners).
inline PolyTestMesh quadGrid(int nu, int nv) {
  std::vector<Vec3> p;
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) p.push_back(Vec3(i, j, 0.3 * std::sin(1.3 * i) * std::cos(0.7 * j)));
  }
  std::vector<std::vector<int>> f;
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const int a = j * (nu + 1) + i;
      f.push_back({a, a + 1, a + nu + 2, a + nu + 1});
    }
  }
  return makePoly("quad-grid-" + std::to_string(nu) + "x" + std::to_string(nv), p, f);
}

inline PolyTestMesh quadTorus(int nu, int nv) {
  std::vector<Vec3> p;
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double a = 2 * std::numbers::pi * i / nu, b = 2 * std::numbers::pi * j / nv;
      p.push_back(Vec3((2 + 0.7 * std::cos(b)) * std::cos(a), (2 + 0.7 * std::cos(b)) * std::sin(a),
                       0.7 * std::sin(b)));
    }
  }
  std::vector<std::vector<int>> f;
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const int i1 = (i + 1) % nu, j1 = (j + 1) % nv;
      f.push_back({i * nv + j, i1 * nv + j, i1 * nv + j1, i * nv + j1});
    }
  }
  return makePoly("quad-torus", p, f);
}

// A closed prism of n-gon caps: the caps, n side quads, one of them split
// into two triangles; and a pyramid of triangles on one more side. Every
// face size from 3 to n, valences 3 to 5.
inline PolyTestMesh mixedPrism(int n, bool open) {
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    p.push_back(Vec3(std::cos(a), std::sin(a), -1));
  }
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    p.push_back(Vec3(1.1 * std::cos(a), 1.1 * std::sin(a), 1 + 0.1 * std::sin(2 * a)));
  }
  std::vector<std::vector<int>> f;
  std::vector<int> bottom, top;
  for (int i = n - 1; i >= 0; --i) bottom.push_back(i);
  for (int i = 0; i < n; ++i) top.push_back(n + i);
  f.push_back(bottom);
  if (!open) f.push_back(top);
  // Side i: i, i+1, n+i+1, n+i.
  for (int i = 0; i < n; ++i) {
    const int a = i, b = (i + 1) % n, c = n + (i + 1) % n, d = n + i;
    if (i == 0) {
      f.push_back({a, b, c});
      f.push_back({a, c, d});
    } else if (i == 2) {
      const int apex = static_cast<int>(p.size());
      const double ang = 2 * std::numbers::pi * (i + 0.5) / n;
      p.push_back(Vec3(1.8 * std::cos(ang), 1.8 * std::sin(ang), 0.1));
      f.push_back({a, b, apex});
      f.push_back({b, c, apex});
      f.push_back({c, d, apex});
      f.push_back({d, a, apex});
    } else {
      f.push_back({a, b, c, d});
    }
  }
  return makePoly(std::string(open ? "open-" : "") + "mixed-prism-" + std::to_string(n), p, f);
}

// Random creases (sharpness from {0.5, 1, 2, 2.5, inf, random}) on about
// `edgeFraction` of the edges and random vertex sharpness on about
// `vertexFraction` of the vertices, as procedural_meshes.h's withRandomTags.
inline PolyTestMesh withRandomPolyTags(const PolyTestMesh& mesh, double edgeFraction, double vertexFraction,
                                       uint32_t seed) {
  PolyTestMesh out = mesh;
  out.name = mesh.name + "-tags" + std::to_string(seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const float choices[] = {0.5f, 1.0f, 2.0f, 2.5f, 10.0f};
  auto draw = [&]() -> float {
    const int k = static_cast<int>(unit(rng) * 6);
    return k < 5 ? choices[k] : static_cast<float>(0.2 + 3.6 * unit(rng));
  };
  std::vector<std::pair<int, int>> edges;
  const auto& t = mesh.topology;
  for (int f = 0; f < t.numFaces(); ++f) {
    const int from = t.faceOffsets[f], n = t.faceOffsets[f + 1] - from;
    for (int j = 0; j < n; ++j) {
      const int a = t.indices[from + j], b = t.indices[from + (j + 1) % n];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  out.topology.creases.clear();
  for (const auto& [a, b] : edges) {
    if (unit(rng) < edgeFraction) out.topology.creases.push_back({a, b, draw()});
  }
  out.topology.vertexSharpness.assign(mesh.points.size(), 0.0f);
  for (auto& s : out.topology.vertexSharpness) {
    if (unit(rng) < vertexFraction) s = draw();
  }
  return out;
}

inline PolyTestMesh withPolyJitter(const PolyTestMesh& mesh, double amount, uint32_t seed) {
  PolyTestMesh out = mesh;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-amount, amount);
  for (auto& p : out.points) p += Vec3(d(rng), d(rng), d(rng));
  return out;
}

// The shapes the Catmull-Clark oracle tests share: quads closed and open,
// a torus, and prisms of triangles, quads and n-gons, jittered from fixed
// seeds so that no symmetry hides an error.
inline std::vector<PolyTestMesh> catmarkShapes() {
  return {quadCube(), withPolyJitter(quadGrid(5, 4), 0.05, 7), withPolyJitter(quadTorus(7, 5), 0.05, 3),
          withPolyJitter(mixedPrism(5, false), 0.05, 11), withPolyJitter(mixedPrism(7, true), 0.05, 12)};
}

}  // namespace tessera::testing

#include "support/procedural_meshes.h"

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "core/mesh/base_mesh.h"

namespace tessera::testing {

namespace {

constexpr double kPi = std::numbers::pi;

TestMesh make(std::string name, std::vector<Vec3> points, std::vector<std::array<int, 3>> tris) {
  TestMesh m;
  m.name = std::move(name);
  m.points = std::move(points);
  m.topology.numVertices = static_cast<int>(m.points.size());
  m.topology.triangles = std::move(tris);
  return m;
}

// Two triangles per grid cell with alternating diagonals.
void addQuad(std::vector<std::array<int, 3>>& tris, int a, int b, int c, int d, bool flip) {
  if (flip) {
    tris.push_back({a, b, d});
    tris.push_back({b, c, d});
  } else {
    tris.push_back({a, b, c});
    tris.push_back({a, c, d});
  }
}

}  // namespace

TestMesh icosahedron() {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> p = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  return make("icosahedron", p, f);
}

TestMesh bipyramid(int n) {
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i) {
    double a = 2 * kPi * i / n;
    p.push_back(Vec3(std::cos(a), std::sin(a), 0.1 * std::sin(3 * a)));
  }
  p.push_back(Vec3(0, 0, 1.2));
  p.push_back(Vec3(0, 0, -0.9));
  std::vector<std::array<int, 3>> f;
  for (int i = 0; i < n; ++i) {
    int j = (i + 1) % n;
    f.push_back({i, j, n});
    f.push_back({j, i, n + 1});
  }
  return make("bipyramid" + std::to_string(n), p, f);
}

TestMesh torus(int nu, int nv) {
  std::vector<Vec3> p;
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv;
      double r = 1.0 + 0.35 * std::cos(v);
      p.push_back(Vec3(r * std::cos(u), r * std::sin(u), 0.35 * std::sin(v)));
    }
  }
  std::vector<std::array<int, 3>> f;
  auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) addQuad(f, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), false);
  }
  return make("torus" + std::to_string(nu) + "x" + std::to_string(nv), p, f);
}

TestMesh openGrid(int nu, int nv) {
  std::vector<Vec3> p;
  for (int i = 0; i <= nu; ++i) {
    for (int j = 0; j <= nv; ++j) {
      double x = double(i) / nu, y = double(j) / nv;
      p.push_back(Vec3(x, y, 0.2 * std::sin(3 * x) * std::cos(2 * y)));
    }
  }
  std::vector<std::array<int, 3>> f;
  auto id = [&](int i, int j) { return i * (nv + 1) + j; };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j)
      addQuad(f, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 1);
  }
  return make("grid" + std::to_string(nu) + "x" + std::to_string(nv), p, f);
}

TestMesh diskWithPole(int n) {
  std::vector<Vec3> p = {Vec3(0, 0, 0.3)};
  for (int i = 0; i < n; ++i) {
    double a = 2 * kPi * i / n;
    p.push_back(Vec3(std::cos(a), std::sin(a), 0.05 * std::cos(2 * a)));
  }
  std::vector<std::array<int, 3>> f;
  for (int i = 0; i < n; ++i) f.push_back({0, 1 + i, 1 + (i + 1) % n});
  return make("disk" + std::to_string(n), p, f);
}

TestMesh doubleTorus() {
  // Two tori sharing nothing but glued through a removed quad pair on each.
  TestMesh a = torus(8, 6);
  TestMesh b = torus(8, 6);
  const int offset = static_cast<int>(a.points.size());
  for (auto& q : b.points) q = Vec3(q[0] + 2.6, q[1], q[2]);
  // Remove the outer-facing quad (u=0, v=0) of a and the (u=4, v=0) quad of b.
  auto quadFaces = [](int i, int j) { return 2 * (i * 6 + j); };
  const int ra = quadFaces(0, 0), rb = quadFaces(4, 0);
  std::vector<std::array<int, 3>> f;
  for (int k = 0; k < static_cast<int>(a.topology.triangles.size()); ++k) {
    if (k != ra && k != ra + 1) f.push_back(a.topology.triangles[k]);
  }
  for (int k = 0; k < static_cast<int>(b.topology.triangles.size()); ++k) {
    if (k == rb || k == rb + 1) continue;
    auto t = b.topology.triangles[k];
    f.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  // Hole of a: (0,0),(1,0),(1,1),(0,1) counter-clockwise seen from outside;
  // hole of b: (4,0),(5,0),(5,1),(4,1). Bridge the two loops with a tube.
  auto ida = [](int i, int j) { return i * 6 + j; };
  auto idb = [&](int i, int j) { return offset + i * 6 + j; };
  int la[4] = {ida(0, 0), ida(1, 0), ida(1, 1), ida(0, 1)};
  int lb[4] = {idb(5, 0), idb(4, 0), idb(4, 1), idb(5, 1)};
  for (int k = 0; k < 4; ++k) {
    int a0 = la[k], a1 = la[(k + 1) % 4], b0 = lb[k], b1 = lb[(k + 1) % 4];
    // The hole's neighbours run a1->a0 and b0->b1, so the tube runs a0->a1, b1->b0.
    f.push_back({a0, a1, b1});
    f.push_back({a0, b1, b0});
  }
  std::vector<Vec3> p = a.points;
  p.insert(p.end(), b.points.begin(), b.points.end());
  return make("doubletorus", p, f);
}

TestMesh withRandomFlips(const TestMesh& mesh, int count, uint32_t seed) {
  TriMesh tm;
  for (const auto& q : mesh.points) tm.add_vertex(q);
  for (const auto& t : mesh.topology.triangles) {
    if (!tm.add_face(tm.vertex_handle(t[0]), tm.vertex_handle(t[1]), tm.vertex_handle(t[2])).is_valid()) {
      throw std::runtime_error("withRandomFlips: bad input mesh " + mesh.name);
    }
  }
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(tm.n_edges()) - 1);
  int done = 0;
  for (int attempt = 0; attempt < 20 * count && done < count; ++attempt) {
    auto eh = tm.edge_handle(pick(rng));
    if (!tm.is_flip_ok(eh)) continue;
    // Keep valences >= 3 so every vertex stays a proper subdivision vertex.
    auto h0 = tm.halfedge_handle(eh, 0), h1 = tm.halfedge_handle(eh, 1);
    if (tm.valence(tm.to_vertex_handle(h0)) <= 3 || tm.valence(tm.to_vertex_handle(h1)) <= 3) continue;
    if (tm.is_boundary(tm.to_vertex_handle(h0)) || tm.is_boundary(tm.to_vertex_handle(h1))) continue;
    tm.flip(eh);
    ++done;
  }
  TestMesh out = mesh;
  out.name = mesh.name + "-flips" + std::to_string(seed);
  out.topology.triangles.clear();
  for (auto fh : tm.faces()) {
    std::array<int, 3> t{};
    int k = 0;
    for (auto vh : tm.fv_ccw_range(fh)) t[k++] = vh.idx();
    out.topology.triangles.push_back(t);
  }
  out.topology.creases.clear();
  return out;
}

TestMesh withRandomTags(const TestMesh& mesh, double edgeFraction, double vertexFraction, uint32_t seed) {
  TestMesh out = mesh;
  out.name = mesh.name + "-tags" + std::to_string(seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const float choices[] = {0.5f, 1.0f, 2.0f, 2.5f, kSharpnessInfinite};
  auto drawSharpness = [&]() -> float {
    int k = static_cast<int>(unit(rng) * 6);
    if (k < 5) return choices[k];
    return static_cast<float>(0.2 + 3.6 * unit(rng));
  };
  // Unique undirected edges of the triangles, in first-seen order.
  std::vector<std::array<int, 2>> edges;
  {
    std::vector<std::vector<int>> seen(mesh.points.size());
    for (const auto& t : mesh.topology.triangles) {
      for (int j = 0; j < 3; ++j) {
        int a = std::min(t[j], t[(j + 1) % 3]), b = std::max(t[j], t[(j + 1) % 3]);
        bool found = false;
        for (int x : seen[a]) found = found || x == b;
        if (!found) {
          seen[a].push_back(b);
          edges.push_back({a, b});
        }
      }
    }
  }
  out.topology.creases.clear();
  for (const auto& e : edges) {
    if (unit(rng) < edgeFraction) out.topology.creases.push_back({e[0], e[1], drawSharpness()});
  }
  out.topology.vertexSharpness.assign(mesh.points.size(), 0.0f);
  for (auto& s : out.topology.vertexSharpness) {
    if (unit(rng) < vertexFraction) s = drawSharpness();
  }
  return out;
}

TestMesh withJitter(const TestMesh& mesh, double amount, uint32_t seed) {
  TestMesh out = mesh;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-amount, amount);
  for (auto& q : out.points) q += Vec3(d(rng), d(rng), d(rng));
  return out;
}

}  // namespace tessera::testing

#include "core/catmark/dart_masks.h"

#include <cassert>
#include <cmath>
#include <numbers>

#include "core/catmark/computed_per_size.h"
#include "core/catmark/left_eigenvector.h"
#include "core/catmark/masks.h"

namespace tessera::catmark {
namespace {

// The ring's points: the vertex, neighbours 0..n-1 (0 across the dart
// edge), the opposite corners of faces 0..n-1.
struct RingIndex {
  int n;
  int size() const { return 2 * n + 1; }
  int vertex() const { return 0; }
  int edge(int i) const { return 1 + ((i % n) + n) % n; }
  int face(int i) const { return 1 + n + ((i % n) + n) % n; }
  // Reflection across the dart edge: neighbour i <-> -i, face i <-> -1-i.
  int mirror(int j) const {
    if (j == 0) return 0;
    if (j <= n) return edge(-(j - 1));
    return face(-1 - (j - 1 - n));
  }
};

std::vector<MatrixEntry> dartSubdivision(const RingIndex r) {
  std::vector<MatrixEntry> m;
  const int n = r.n;
  // Face i's point, times `scale`, added to row `row`.
  auto facePoint = [&](int row, int i, double scale) {
    for (int column : {r.vertex(), r.edge(i), r.face(i), r.edge(i + 1)})
      m.push_back({row, column, scale * facePointWeight(4)});
  };
  m.push_back({r.vertex(), r.vertex(), smoothVertexWeight(n)});
  for (int i = 0; i < n; ++i) {
    m.push_back({r.vertex(), r.edge(i), smoothNeighbourWeight(n)});
    facePoint(r.vertex(), i, smoothNeighbourWeight(n));
    facePoint(r.face(i), i, 1.0);
  }
  m.push_back({r.edge(0), r.vertex(), 0.5});  // the dart edge: its midpoint
  m.push_back({r.edge(0), r.edge(0), 0.5});
  for (int i = 1; i < n; ++i) {
    m.push_back({r.edge(i), r.vertex(), kEdgeEndWeight});
    m.push_back({r.edge(i), r.edge(i), kEdgeEndWeight});
    facePoint(r.edge(i), i - 1, kEdgeFaceWeight);
    facePoint(r.edge(i), i, kEdgeFaceWeight);
  }
  return m;
}

DartMask maskOf(const RingIndex r, const std::vector<double>& x, double scale) {
  DartMask mask;
  mask.vertex = scale * x[r.vertex()];
  for (int i = 0; i < r.n; ++i) {
    mask.neighbours.push_back(scale * x[r.edge(i)]);
    mask.faceCorners.push_back(scale * x[r.face(i)]);
  }
  return mask;
}

DartMasks compute(int n) {
  const RingIndex r{n};
  const std::vector<MatrixEntry> matrix = dartSubdivision(r);
  const int size = r.size();
  auto mirrored = [&](std::vector<double>& y, double sign) {
    std::vector<double> out(size);
    for (int j = 0; j < size; ++j) out[j] = 0.5 * (y[j] + sign * y[r.mirror(j)]);
    y = std::move(out);
  };

  // The limit: from the smooth limit mask.
  std::vector<double> start(size, smoothLimitFaceWeight(n));
  start[r.vertex()] = smoothLimitVertexWeight(n);
  for (int i = 0; i < n; ++i) start[r.edge(i)] = smoothLimitNeighbourWeight(n);
  const LeftEigenvector limit = dominantLeftEigenvector(matrix, start, {});
  double sum = 0;
  for (double v : limit.vector) sum += v;

  // The tangents, without the constant part: from the smooth tangent masks
  // turned to the dart edge (cosines) and a quarter turn on (sines).
  const std::vector<double> l0 = [&] {
    std::vector<double> v = limit.vector;
    for (double& w : v) w /= sum;
    return v;
  }();
  auto withoutConstant = [&](std::vector<double>& y) {
    double constant = 0;
    for (double v : y) constant += v;
    for (int j = 0; j < size; ++j) y[j] -= constant * l0[j];
  };
  std::vector<double> cosines(size, 0.0), sines(size, 0.0);
  const double theta = 2.0 * std::numbers::pi / n;
  for (int i = 0; i < n; ++i) {
    cosines[r.edge(i)] = std::cos(i * theta);
    cosines[r.face(i)] = 0.5 * (std::cos(i * theta) + std::cos((i + 1) * theta));
    sines[r.edge(i)] = std::sin(i * theta);
    sines[r.face(i)] = 0.5 * (std::sin(i * theta) + std::sin((i + 1) * theta));
  }
  const LeftEigenvector along = dominantLeftEigenvector(matrix, cosines, [&](std::vector<double>& y) {
    withoutConstant(y);
    mirrored(y, 1.0);
  });
  const LeftEigenvector across =
      dominantLeftEigenvector(matrix, sines, [&](std::vector<double>& y) { mirrored(y, -1.0); });

  DartMasks masks;
  masks.valence = n;
  masks.limit = maskOf(r, limit.vector, 1.0 / sum);
  // Signs: along towards the dart edge, across towards neighbour 1.
  masks.along = maskOf(r, along.vector, along.vector[r.edge(0)] > 0 ? 1.0 : -1.0);
  masks.across = maskOf(r, across.vector, across.vector[r.edge(1)] > 0 ? 1.0 : -1.0);
  masks.alongEigenvalue = along.eigenvalue;
  masks.acrossEigenvalue = across.eigenvalue;
  return masks;
}

}  // namespace

const DartMasks& dartMasks(int valence) {
  assert(hasExactDartMasks(valence));
  static const ComputedPerSize<DartMasks> computed(compute);
  return computed(valence);
}

}  // namespace tessera::catmark

#include "core/catmark/crease_span_tangent.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "core/catmark/computed_per_size.h"
#include "core/catmark/left_eigenvector.h"
#include "core/catmark/masks.h"

namespace tessera::catmark {
namespace {

// The span's points, in this order: the vertex, ring edges 0..k (0 and k
// the crease neighbours), the opposite corners of faces 1..k (face i lies
// between ring edges i - 1 and i).
struct SpanIndex {
  int k;
  int size() const { return 2 * k + 2; }
  int vertex() const { return 0; }
  int edge(int i) const { return 1 + i; }
  int face(int i) const { return k + 1 + i; }
  int mirror(int j) const {
    if (j == 0) return 0;
    if (j <= k + 1) return edge(k - (j - 1));
    return face(k + 1 - (j - k - 1));
  }
};

// One step of subdivision on the span: new point `row` = sum of weight x
// old point `column` (Sdc's crease vertex and edge rules on the crease,
// Catmull-Clark's face and edge points elsewhere).
std::vector<MatrixEntry> spanSubdivision(const SpanIndex& s) {
  std::vector<MatrixEntry> m;
  const int k = s.k;
  m.push_back({s.vertex(), s.vertex(), kCreaseVertexWeight});
  m.push_back({s.vertex(), s.edge(0), kCreaseNeighbourWeight});
  m.push_back({s.vertex(), s.edge(k), kCreaseNeighbourWeight});
  for (int end : {0, k}) {
    m.push_back({s.edge(end), s.vertex(), 0.5});
    m.push_back({s.edge(end), s.edge(end), 0.5});
  }
  auto facePoint = [&](int row, int i, double scale) {
    for (int column : {s.vertex(), s.edge(i - 1), s.face(i), s.edge(i)})
      m.push_back({row, column, scale * facePointWeight(4)});
  };
  for (int i = 1; i <= k; ++i) facePoint(s.face(i), i, 1.0);
  for (int i = 1; i < k; ++i) {
    m.push_back({s.edge(i), s.vertex(), kEdgeEndWeight});
    m.push_back({s.edge(i), s.edge(i), kEdgeEndWeight});
    facePoint(s.edge(i), i, kEdgeFaceWeight);
    facePoint(s.edge(i), i + 1, kEdgeFaceWeight);
  }
  return m;
}

CreaseSpanTangent compute(int k) {
  const SpanIndex s{k};
  const std::vector<MatrixEntry> matrix = spanSubdivision(s);
  const int n = s.size();

  // Limit()'s mask: the start of the iteration, and the length and sign to
  // keep.
  const CreaseTangentWeights w = creaseTangentWeights(k - 1);
  std::vector<double> start(n, 0.0);
  start[s.vertex()] = w.vertex;
  start[s.edge(0)] = start[s.edge(k)] = w.creaseNeighbour;
  for (int i = 1; i < k; ++i) start[s.edge(i)] = w.interiorNeighbour(i);
  for (int i = 1; i <= k; ++i) start[s.face(i)] = w.face(i - 1);

  // The constant part's left eigenvector (the crease limit, 1/6 2/3 1/6),
  // whose right eigenvector is all ones.
  std::vector<double> limit(n, 0.0);
  limit[s.vertex()] = kCreaseLimitVertexWeight;
  limit[s.edge(0)] = limit[s.edge(k)] = kCreaseLimitNeighbourWeight;

  const LeftEigenvector found = dominantLeftEigenvector(matrix, start, [&](std::vector<double>& y) {
    double constant = 0;
    for (double v : y) constant += v;
    for (int j = 0; j < n; ++j) y[j] -= constant * limit[j];
    std::vector<double> mirrored(n);
    for (int j = 0; j < n; ++j) mirrored[j] = 0.5 * (y[j] + y[s.mirror(j)]);
    y = std::move(mirrored);
  });
  const std::vector<double>& x = found.vector;
  const double eigenvalue = found.eigenvalue;

  const double scale = dotOf(start, start) / dotOf(x, start);
  CreaseSpanTangent t;
  t.faces = k;
  t.eigenvalue = eigenvalue;
  t.vertex = scale * x[s.vertex()];
  t.creaseNeighbour = scale * x[s.edge(0)];
  for (int i = 1; i < k; ++i) t.interiorNeighbours.push_back(scale * x[s.edge(i)]);
  for (int i = 1; i <= k; ++i) t.faceCorners.push_back(scale * x[s.face(i)]);
  return t;
}

}  // namespace

const CreaseSpanTangent& creaseSpanTangent(int faces) {
  assert(faces >= 3);
  static const ComputedPerSize<CreaseSpanTangent> computed(compute);
  return computed(faces);
}

}  // namespace tessera::catmark

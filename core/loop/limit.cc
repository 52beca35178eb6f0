#include "core/loop/limit.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "core/loop/masks.h"

namespace tessera {

namespace detail {

// Per-valence smooth limit weights and tangent coefficients, computed once
// per evaluation instead of once per vertex.
class SmoothTables {
 public:
  explicit SmoothTables(int maxValence) : offsets_(maxValence + 2, 0), weight_(maxValence + 1, 0.0) {
    for (int n = 0; n <= maxValence; ++n) offsets_[n + 1] = offsets_[n] + n;
    cos_.resize(offsets_.back());
    sin_.resize(offsets_.back());
    for (int n = 3; n <= maxValence; ++n) {
      weight_[n] = loop::smoothLimitEdgeWeight(n);
      // The first Fourier components of the ring: cos, sin of 2 pi k / n.
      for (int k = 0; k < n; ++k) {
        cos_[offsets_[n] + k] = std::cos(2.0 * std::numbers::pi * k / n);
        sin_[offsets_[n] + k] = std::sin(2.0 * std::numbers::pi * k / n);
      }
    }
  }
  double weight(int n) const { return weight_[n]; }
  const double* cos(int n) const { return cos_.data() + offsets_[n]; }
  const double* sin(int n) const { return sin_.data() + offsets_[n]; }

 private:
  std::vector<int> offsets_;
  std::vector<double> weight_, cos_, sin_;
};

}  // namespace detail

namespace {

using detail::SmoothTables;

// The regular case, valence 6, with its weights written out: cos(k pi/3) is
// +-1 or +-1/2 and sin(k pi/3) is 0 or +-sqrt(3)/2 (loopScheme.h does the same).
LimitFrame regularFrame(std::span<const Index> ring, Index v, std::span<const Vec3> p) {
  const Vec3 &q0 = p[ring[0]], &q1 = p[ring[1]], &q2 = p[ring[2]];
  const Vec3 &q3 = p[ring[3]], &q4 = p[ring[4]], &q5 = p[ring[5]];
  constexpr double kRoot3By2 = 0.86602540378443864676;
  const Vec3 sum = (q0 + q1) + (q2 + q3) + (q4 + q5);
  return {0.5 * p[v] + (1.0 / 12.0) * sum, (q0 - q3) + 0.5 * ((q1 + q5) - (q2 + q4)),
          kRoot3By2 * ((q1 + q2) - (q4 + q5))};
}

LimitFrame smoothFrame(const Level& level, Index v, std::span<const Vec3> p, const SmoothTables& tables) {
  auto ring = level.ringVerticesOf(v);
  const int n = static_cast<int>(ring.size());
  if (n == 6) return regularFrame(ring, v, p);
  const double* c = tables.cos(n);
  const double* s = tables.sin(n);
  Vec3 sum(0, 0, 0), t1(0, 0, 0), t2(0, 0, 0);
  for (int k = 0; k < n; ++k) {
    const Vec3& q = p[ring[k]];
    sum += q;
    t1 += c[k] * q;
    t2 += s[k] * q;
  }
  const double w = tables.weight(n);
  return {(1.0 - n * w) * p[v] + w * sum, t1, t2};
}

// The crease frame for the span of faces from ring edge `from` to ring edge
// `to` (counter-clockwise, indices taken modulo the valence, to > from).
LimitFrame creaseSpanFrame(const Level& level, Index v, std::span<const Vec3> p, int from, int to) {
  auto ring = level.ringVerticesOf(v);
  const int n = static_cast<int>(ring.size());
  auto neighbour = [&](int k) -> const Vec3& { return p[ring[k % n]]; };

  LimitFrame frame{Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 0)};
  frame.position = loop::kCreaseLimitVertexWeight * p[v] +
                   loop::kCreaseLimitNeighbourWeight * (neighbour(from) + neighbour(to));
  // Along the crease, scaled by 3/2 to match interior tangent magnitudes.
  frame.tangent1 = 1.5 * (neighbour(from) - neighbour(to));

  // Across the span (Hoppe et al. '94 / Biermann et al. boundary masks,
  // oriented inward as OpenSubdiv does, so tangent1 x tangent2 points out).
  const int interior = to - from - 1;
  Vec3& t2 = frame.tangent2;
  if (interior == 0) {
    t2 = -6.0 * p[v] + 3.0 * (neighbour(from) + neighbour(to));
  } else if (interior == 1) {
    t2 = -3.0 * p[v] + 3.0 * neighbour(from + 1);
  } else if (interior == 2) {
    const double r3 = std::sqrt(3.0);
    t2 = -r3 * p[v] - 0.5 * r3 * (neighbour(from) + neighbour(to)) + r3 * (neighbour(from + 1) + neighbour(from + 2));
  } else {
    const double theta = std::numbers::pi / (interior + 1);
    const double cw = -3.0 * std::sin(theta);
    const double ew = -3.0 * (2.0 * std::cos(theta) - 2.0);
    t2 = cw * (neighbour(from) + neighbour(to));
    for (int i = 1; i <= interior; ++i) t2 += ew * std::sin(i * theta) * neighbour(from + i);
  }
  return frame;
}

// Ring positions of the sharp edges of v, in ring order.
std::vector<int> sharpRingEdges(const Level& level, Index v) {
  std::vector<int> sharp;
  auto ring = level.ringEdgesOf(v);
  for (int k = 0; k < static_cast<int>(ring.size()); ++k) {
    if (isSharp(level.edgeSharpness[ring[k]])) sharp.push_back(k);
  }
  return sharp;
}

// OpenSubdiv's crease frame: the span from the first to the second sharp edge.
LimitFrame creaseFrame(const Level& level, Index v, std::span<const Vec3> p) {
  const std::vector<int> sharp = sharpRingEdges(level, v);
  return creaseSpanFrame(level, v, p, sharp[0], sharp[1]);
}

LimitFrame cornerFrame(const Level& level, Index v, std::span<const Vec3> p) {
  auto ring = level.ringVerticesOf(v);
  // Differences to the first two ring neighbours, scaled by 3 (OpenSubdiv's
  // magnitude convention): the tangent plane of the first face's sector.
  return {p[v], 3.0 * (p[ring[0]] - p[v]), 3.0 * (p[ring[1]] - p[v])};
}

LimitFrame frameWith(const Level& level, Index v, std::span<const Vec3> points, const SmoothTables& tables) {
  switch (level.vertexRules[v]) {
    case VertexRule::kSmooth:
    case VertexRule::kDart:
      return smoothFrame(level, v, points, tables);
    case VertexRule::kCrease:
      return creaseFrame(level, v, points);
    case VertexRule::kCorner:
      return cornerFrame(level, v, points);
  }
  return cornerFrame(level, v, points);
}

// Normal of a corner sector bounded by ring edges `from` and `to`: the plane
// of the two crease curves leaving the corner, which start along their first
// edges. A reflex sector (wider than a half turn) flips that cross product,
// so it is checked against the sector's faces and replaced by their
// area-weighted normal if it disagrees.
Vec3 cornerSectorNormal(const Level& level, Index v, std::span<const Vec3> p, int from, int to) {
  auto ringV = level.ringVerticesOf(v);
  auto ringF = level.ringFacesOf(v);
  const int n = static_cast<int>(ringV.size());
  Vec3 faces(0, 0, 0);
  for (int k = from; k < to; ++k) {
    const auto& f = level.faceVertices[ringF[k % n]];
    faces += (p[f[1]] - p[f[0]]) % (p[f[2]] - p[f[0]]);
  }
  const Vec3 planes = (p[ringV[from % n]] - p[v]) % (p[ringV[to % n]] - p[v]);
  const Vec3 chosen = dot(planes, faces) > 0.0 ? planes : faces;
  const double len2 = chosen.sqrnorm();
  return len2 > 0.0 ? (1.0 / std::sqrt(len2)) * chosen : Vec3(0, 0, 0);
}

}  // namespace

std::vector<LimitSector> otherLimitSectors(const Level& level, Index v, std::span<const Vec3> points) {
  const VertexRule rule = level.vertexRules[v];
  if (isSmoothLike(rule)) return {};
  const std::vector<int> sharp = sharpRingEdges(level, v);
  const int m = static_cast<int>(sharp.size());
  if (m < 2) return {};  // a cusp: one sector
  const int n = level.valence(v);
  const bool boundary = level.isBoundaryVertex(v);
  // The sector limitFrame() describes: for a crease the span from the first
  // sharp edge; for a corner the one holding ring face 0 (OpenSubdiv's
  // corner tangents use ring edges 0 and 1).
  const int primary = (rule == VertexRule::kCrease || sharp[0] == 0) ? 0 : m - 1;
  std::vector<LimitSector> sectors;
  for (int i = 0; i < m; ++i) {
    if (i == primary) continue;
    const bool wraps = (i + 1 == m);
    if (wraps && boundary) continue;  // no faces past the last boundary edge
    const int from = sharp[i];
    const int to = wraps ? sharp[0] + n : sharp[i + 1];
    LimitSector sector;
    sector.firstFace = from;
    sector.faceCount = to - from;
    sector.normal = rule == VertexRule::kCrease ? creaseSpanFrame(level, v, points, from, to).normal()
                                                : cornerSectorNormal(level, v, points, from, to);
    sectors.push_back(sector);
  }
  return sectors;
}

int limitSideOfRingFace(const Level& level, Index v, int ringFace) {
  if (isSmoothLike(level.vertexRules[v])) return 0;
  const std::vector<int> sharp = sharpRingEdges(level, v);
  const int m = static_cast<int>(sharp.size());
  if (m < 2) return 0;
  // Sector i runs from sharp edge i to sharp edge i + 1; the last wraps
  // past ring edge 0 (ring faces before the first sharp edge lie in it).
  int sector = m - 1;
  for (int i = 0; i < m && sharp[i] <= ringFace; ++i) sector = i;
  // As otherLimitSectors() numbers them: the primary sector first, then
  // the others in ring order (a boundary's wrap, the last, has no faces).
  const int primary = (level.vertexRules[v] == VertexRule::kCrease || sharp[0] == 0) ? 0 : m - 1;
  if (sector == primary) return 0;
  return sector < primary ? sector + 1 : sector;
}

LimitFrame limitFrame(const Level& level, Index v, std::span<const Vec3> points) {
  SmoothTables tables(level.valence(v));
  return frameWith(level, v, points, tables);
}

LimitEvaluator::LimitEvaluator(const Level& level)
    : level_(level), tables_(std::make_unique<const SmoothTables>(level.maxValence)) {}

LimitEvaluator::~LimitEvaluator() = default;

LimitFrame LimitEvaluator::frame(Index v, std::span<const Vec3> points) const {
  return frameWith(level_, v, points, *tables_);
}

void computeLimit(const Level& level, std::span<const Vec3> points, std::span<Vec3> positions,
                  std::span<Vec3> normals) {
  const SmoothTables tables(level.maxValence);
  const bool wantNormals = !normals.empty();
  for (Index v = 0; v < level.numVertices; ++v) {
    const LimitFrame frame = frameWith(level, v, points, tables);
    positions[v] = frame.position;
    if (wantNormals) normals[v] = frame.normal();
  }
}

}  // namespace tessera

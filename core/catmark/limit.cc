#include "core/catmark/limit.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/catmark/crease_span_tangent.h"
#include "core/catmark/dart_masks.h"
#include "core/catmark/masks.h"
#include "core/catmark/semi_sharp_limit.h"
#include "core/loop/exact_limit.h"

namespace tessera {

namespace detail {

// Smooth tangent weights per valence, computed once per evaluation: ring
// neighbour k and face k of valence n at offsets[n] + k.
class CatmarkTangentTables {
 public:
  explicit CatmarkTangentTables(int maxValence) : offsets_(maxValence + 2, 0) {
    for (int n = 0; n <= maxValence; ++n) offsets_[n + 1] = offsets_[n] + n;
    edge_.resize(offsets_.back());
    face_.resize(offsets_.back());
    for (int n = 3; n <= maxValence; ++n) {
      for (int k = 0; k < n; ++k) {
        edge_[offsets_[n] + k] = catmark::smoothTangentNeighbourWeight(n, k);
        face_[offsets_[n] + k] = catmark::smoothTangentFaceWeight(n, k);
      }
    }
  }
  const double* edge(int n) const { return edge_.data() + offsets_[n]; }
  const double* face(int n) const { return face_.data() + offsets_[n]; }

 private:
  std::vector<int> offsets_;
  std::vector<double> edge_, face_;
};

}  // namespace detail

namespace {

using TangentTables = detail::CatmarkTangentTables;

// Opposite corner of v in quad f, v being at corner c.
inline Index opposite(const Level& level, Index f, int c) {
  return level.faceVertices[4 * f + ((c + 2) & 3)];
}

CatmarkLimitFrame cornerFrame(const Level& level, Index v, std::span<const Vec3> p) {
  auto ring = level.ringVerticesOf(v);
  return {p[v], p[ring[0]] - p[v], p[ring[1]] - p[v]};
}

// The regular case, valence 4, written out: the bicubic B-spline's limit
// (4/9, 1/9, 1/36) and tangents (edges 4, 0, -4, 0; faces 1, -1, -1, 1),
// as catmarkScheme.h specialises it.
CatmarkLimitFrame regularFrame(const Level& level, Index v, Index o, std::span<const Vec3> p) {
  const Index* rv = level.ringVertices.data() + o;
  const Index* rf = level.ringFaces.data() + o;
  const LocalIndex* rl = level.ringFaceLocal.data() + o;
  const Vec3 &e0 = p[rv[0]], &e1 = p[rv[1]], &e2 = p[rv[2]], &e3 = p[rv[3]];
  const Vec3& f0 = p[opposite(level, rf[0], rl[0])];
  const Vec3& f1 = p[opposite(level, rf[1], rl[1])];
  const Vec3& f2 = p[opposite(level, rf[2], rl[2])];
  const Vec3& f3 = p[opposite(level, rf[3], rl[3])];
  return {(1.0 / 36.0) * ((f0 + f1) + (f2 + f3)) + (1.0 / 9.0) * ((e0 + e1) + (e2 + e3)) + (4.0 / 9.0) * p[v],
          4.0 * (e0 - e2) + ((f0 - f1) + (f3 - f2)), 4.0 * (e1 - e3) + ((f0 + f1) - (f2 + f3))};
}

CatmarkLimitFrame smoothFrame(const Level& level, Index v, std::span<const Vec3> p,
                              const TangentTables& tables) {
  const int n = level.valence(v);
  if (n == 2) return cornerFrame(level, v, p);
  const Index o = level.ringOffsets[v];
  if (n == 4) return regularFrame(level, v, o, p);
  const double fw = catmark::smoothLimitFaceWeight(n), ew = catmark::smoothLimitNeighbourWeight(n);
  CatmarkLimitFrame frame;
  Vec3 faces(0, 0, 0), edges(0, 0, 0);
  // Tangent weights of neighbour k and face k; the second tangent uses
  // those of k-1 (a rotation by one).
  const double* te = tables.edge(n);
  const double* tf = tables.face(n);
  for (int k = 0; k < n; ++k) {
    const Vec3& q = p[level.ringVertices[o + k]];
    const Vec3& r = p[opposite(level, level.ringFaces[o + k], level.ringFaceLocal[o + k])];
    faces += r;
    edges += q;
    const int km = k ? k - 1 : n - 1;
    frame.tangent1 += tf[k] * r + te[k] * q;
    frame.tangent2 += tf[km] * r + te[km] * q;
  }
  frame.position = fw * faces + ew * edges + catmark::smoothLimitVertexWeight(n) * p[v];
  return frame;
}

// The crease's limit, with its tangent along the crease and the one across
// into the sector of ring faces from sharp ring edge `from` to `to`
// (exclusive, modulo the valence: the other sector of a closed ring is
// from ends[1] to ends[0] + n).
CatmarkLimitFrame creaseSectorFrame(const Level& level, Index v, std::span<const Vec3> p, int from, int to) {
  const int n = level.valence(v);
  const Index o = level.ringOffsets[v];
  auto at = [&](int k) { return o + k % n; };
  const Vec3& a = p[level.ringVertices[at(from)]];
  const Vec3& b = p[level.ringVertices[at(to)]];
  CatmarkLimitFrame frame;
  frame.position = catmark::kCreaseLimitNeighbourWeight * (a + b) + catmark::kCreaseLimitVertexWeight * p[v];
  frame.tangent1 = 0.5 * (a - b);
  const int interior = to - from - 1;
  auto corner = [&](int i) {
    const Index k = at(from + i);
    return p[opposite(level, level.ringFaces[k], level.ringFaceLocal[k])];
  };
  Vec3 t2;
  if (interior >= 2) {  // three faces or more: the span's own eigenvector
    const catmark::CreaseSpanTangent& w = catmark::creaseSpanTangent(interior + 1);
    t2 = w.vertex * p[v] + w.creaseNeighbour * (a + b);
    for (int i = 1; i <= interior; ++i)
      t2 += w.interiorNeighbours[i - 1] * p[level.ringVertices[at(from + i)]];
    for (int i = 0; i <= interior; ++i) t2 += w.faceCorners[i] * corner(i);
  } else {
    const catmark::CreaseTangentWeights w = catmark::creaseTangentWeights(interior);
    t2 = w.vertex * p[v] + w.creaseNeighbour * (a + b);
    for (int i = 1; i <= interior; ++i) t2 += w.interiorNeighbour(i) * p[level.ringVertices[at(from + i)]];
    for (int i = 0; interior > 0 && i <= interior; ++i) t2 += w.face(i) * corner(i);
  }
  frame.tangent2 = t2;
  return frame;
}

CatmarkLimitFrame creaseFrame(const Level& level, Index v, std::span<const Vec3> p) {
  const int n = level.valence(v);
  const Index o = level.ringOffsets[v];
  int ends[2] = {-1, -1};
  for (int k = 0, found = 0; k < n && found < 2; ++k) {
    if (isSharp(level.edgeSharpness[level.ringEdges[o + k]])) ends[found++] = k;
  }
  return creaseSectorFrame(level, v, p, ends[0], ends[1]);
}

// Twice the area-weighted normal of quad f (its diagonals' cross product).
Vec3 quadNormal(const Level& level, Index f, std::span<const Vec3> p) {
  const Index* q = level.faceVertices.data() + 4 * f;
  return (p[q[2]] - p[q[0]]) % (p[q[3]] - p[q[1]]);
}

Vec3 faceNormals(const Level& level, Index v, std::span<const Vec3> p) {
  Vec3 sum(0, 0, 0);
  for (Index f : level.ringFacesOf(v)) {
    if (f != kNoIndex) sum += quadNormal(level, f, p);
  }
  return sum;
}

// A frame's unit normal; where its tangents are parallel (a degenerate
// control net), that of `fallback()`, an area-weighted sum of face normals.
template <typename Fallback>
Vec3 unitNormal(const CatmarkLimitFrame& frame, Fallback fallback) {
  Vec3 n = frame.tangent1 % frame.tangent2;
  const double scale = std::sqrt(frame.tangent1.sqrnorm() * frame.tangent2.sqrnorm());
  if (!(n.norm() > 1e-12 * scale)) n = fallback();
  const double len = n.norm();
  return len > 0.0 ? (1.0 / len) * n : Vec3(0, 0, 0);
}

// A dart's limit and tangents by its own ring's eigenvectors
// (core/catmark/dart_masks.h), where Limit() takes the smooth masks; the
// smooth masks too above kMaxExactDartValence.
CatmarkLimitFrame dartFrame(const Level& level, Index v, std::span<const Vec3> p,
                            const TangentTables& tables) {
  const int n = level.valence(v);
  if (!catmark::hasExactDartMasks(n)) return smoothFrame(level, v, p, tables);
  const Index o = level.ringOffsets[v];
  int dart = 0;
  while (dart < n && !isSharp(level.edgeSharpness[level.ringEdges[o + dart]])) ++dart;
  const catmark::DartMasks& m = catmark::dartMasks(n);
  CatmarkLimitFrame frame{m.limit.vertex * p[v], m.along.vertex * p[v], m.across.vertex * p[v]};
  for (int i = 0; i < n; ++i) {
    const Index k = o + (dart + i) % n;
    const Vec3& q = p[level.ringVertices[k]];
    const Vec3& r = p[opposite(level, level.ringFaces[k], level.ringFaceLocal[k])];
    frame.position += m.limit.neighbours[i] * q + m.limit.faceCorners[i] * r;
    frame.tangent1 += m.along.neighbours[i] * q + m.along.faceCorners[i] * r;
    frame.tangent2 += m.across.neighbours[i] * q + m.across.faceCorners[i] * r;
  }
  return frame;
}

// `mayDecay` false: the caller knows no vertex of the level has a
// semi-sharp feature (CatmarkLimitEvaluator::Scope::kWholeLevel).
CatmarkLimitFrame frameWith(const Level& level, Index v, std::span<const Vec3> points,
                            const TangentTables& tables, const CreaseOptions& options,
                            const FarRingSharpness* far, bool mayDecay = true) {
  if (mayDecay && takesDecayedLimit(level, v, options)) {
    if (auto decayed = decayedLimitFrame(level, v, points, options, far)) return *decayed;
  }
  switch (level.vertexRules[v]) {
    case VertexRule::kSmooth:
      return smoothFrame(level, v, points, tables);
    case VertexRule::kDart:
      return dartFrame(level, v, points, tables);
    case VertexRule::kCrease:
      return creaseFrame(level, v, points);
    case VertexRule::kCorner:
      return cornerFrame(level, v, points);
  }
  return cornerFrame(level, v, points);
}

// catmarkOtherLimitSectors with every sharp-counted edge a bound, as
// Limit()'s masks count them.
std::vector<LimitSector> countedOtherLimitSectors(const Level& level, Index v, std::span<const Vec3> points) {
  std::vector<LimitSector> out;
  const VertexRule rule = level.vertexRules[v];
  if (rule != VertexRule::kCrease && rule != VertexRule::kCorner) return out;
  const std::vector<int> sharp = sharpRingEdges(level, v);
  const int m = static_cast<int>(sharp.size());
  if (m < 2) return out;
  const int n = level.valence(v);
  const Index o = level.ringOffsets[v];
  // As limitSideOfRingFace numbers them (core/loop/limit.h): sector i from
  // sharp edge i to i + 1, the primary one (catmarkLimitFrame's) left out.
  const int primary = (rule == VertexRule::kCrease || sharp[0] == 0) ? 0 : m - 1;
  for (int i = 0; i < m; ++i) {
    if (i == primary) continue;
    const int from = sharp[i], to = i + 1 < m ? sharp[i + 1] : sharp[0] + n;
    LimitSector sector{from, to - from, Vec3(0, 0, 0)};
    std::vector<Index> faces;
    for (int k = from; k < to; ++k) {
      if (level.ringFaces[o + k % n] != kNoIndex) faces.push_back(level.ringFaces[o + k % n]);
    }
    if (faces.empty()) {
      // A boundary's wrap: no face lies in it.
      out.push_back(sector);
      continue;
    }
    // A crease's other side: the same tangent across it, into this side.
    // A corner's side: the tangents along its first face's edges, which
    // are the limit curves' (the edges are sharp) where the side has one
    // face; a wider side is a cone without a tangent plane, and this is
    // its first face's choice, as catmarkLimitFrame's corner makes.
    const CatmarkLimitFrame frame =
        rule == VertexRule::kCrease
            ? creaseSectorFrame(level, v, points, from, to)
            : CatmarkLimitFrame{points[v], points[level.ringVertices[o + from % n]] - points[v],
                                points[level.ringVertices[o + (from + 1) % n]] - points[v]};
    sector.normal = unitNormal(frame, [&] {
      Vec3 sum(0, 0, 0);
      for (Index f : faces) sum += quadNormal(level, f, points);
      return sum;
    });
    out.push_back(sector);
  }
  return out;
}

}  // namespace

std::vector<LimitSector> catmarkOtherLimitSectors(const Level& level, Index v, std::span<const Vec3> points,
                                                  const CreaseOptions& options, const FarRingSharpness* far) {
  if (takesDecayedLimit(level, v, options)) {
    if (auto decayed = decayedOtherLimitSectors(level, v, points, options, far)) return std::move(*decayed);
  }
  return countedOtherLimitSectors(level, v, points);
}

int catmarkLimitSideOfRingFace(const Level& level, Index v, int ringFace, const CreaseOptions& options,
                               const FarRingSharpness* far) {
  if (takesDecayedLimit(level, v, options)) {
    if (auto side = decayedSideOfRingFace(level, v, ringFace, options, far)) return *side;
  }
  return limitSideOfRingFace(level, v, ringFace);
}

CatmarkLimitFrame catmarkLimitFrame(const Level& level, Index v, std::span<const Vec3> points,
                                    const CreaseOptions& options, const FarRingSharpness* far) {
  return frameWith(level, v, points, TangentTables(level.valence(v)), options, far);
}

namespace {

// Whether some vertex of the level may take the decayed limit: a superset
// of hasUndecayedSemiSharpness over its vertices, which reads only the
// vertex's own sharpness and its ring edges'.
bool anySemiSharpness(const Level& level) {
  auto semiSharp = [](float s) { return isSemiSharp(s); };
  return std::any_of(level.edgeSharpness.begin(), level.edgeSharpness.end(), semiSharp) ||
         std::any_of(level.vertexSharpness.begin(), level.vertexSharpness.end(), semiSharp);
}

}  // namespace

CatmarkLimitEvaluator::CatmarkLimitEvaluator(const Level& level, const CreaseOptions& options,
                                             const FarRingSharpness* far, Scope scope)
    : level_(level),
      options_(options),
      far_(far),
      tables_(std::make_unique<const TangentTables>(level.maxValence)),
      mayDecay_(scope == Scope::kSomeVertices || anySemiSharpness(level)) {}

CatmarkLimitEvaluator::~CatmarkLimitEvaluator() = default;

CatmarkLimitFrame CatmarkLimitEvaluator::frame(Index v, std::span<const Vec3> points) const {
  return frameWith(level_, v, points, *tables_, options_, far_, mayDecay_);
}

double catmarkSelfLimitWeight(const Level& level, Index v, const CreaseOptions& options,
                              const FarRingSharpness* far) {
  if (takesDecayedLimit(level, v, options)) {
    if (auto weight = decayedSelfLimitWeight(level, v, options, far)) return *weight;
  }
  switch (level.vertexRules[v]) {
    case VertexRule::kDart:
      if (catmark::hasExactDartMasks(level.valence(v)))
        return catmark::dartMasks(level.valence(v)).limit.vertex;
      [[fallthrough]];  // the smooth masks, as dartFrame takes them
    case VertexRule::kSmooth:
      return level.valence(v) == 2 ? 1.0 : catmark::smoothLimitVertexWeight(level.valence(v));
    case VertexRule::kCrease:
      return catmark::kCreaseLimitVertexWeight;
    case VertexRule::kCorner:
      return 1.0;
  }
  return 1.0;
}

Status computeCatmarkLimit(const Level& level, const CreaseOptions& options, std::span<const Vec3> points,
                           std::span<Vec3> positions, std::span<Vec3> normals) {
  if (!level.allQuads()) {
    return invalidArgument(
        "the Catmull-Clark limit needs a level of quads: this one has other polygons (refine once)");
  }
  if (level.ringOffsets.empty())
    return internalError("the Catmull-Clark limit needs the level's full topology");
  const bool wantNormals = !normals.empty();
  const TangentTables tables(level.maxValence);
  for (Index v = 0; v < level.numVertices; ++v) {
    const CatmarkLimitFrame frame = frameWith(level, v, points, tables, options, nullptr);
    positions[v] = frame.position;
    if (wantNormals) normals[v] = unitNormal(frame, [&] { return faceNormals(level, v, points); });
  }
  return Status::ok();
}

}  // namespace tessera

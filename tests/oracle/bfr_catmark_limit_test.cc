// Catmull-Clark limits against OpenSubdiv's Bfr (Bfr::RefinerSurfaceFactory,
// double precision) at every face corner of levels 0 to 3 of quad meshes:
// the position, and the normal of the limit surface on that face's side
// (core/catmark/limit.h: catmarkLimitFrame for a vertex's first side,
// catmarkOtherLimitSectors for the others, limitSideOfRingFace choosing).
//
// Bfr evaluates regular patches exactly; around an irregular feature it
// refines to an approximation level (2 for smooth features, 6 for sharp ones
// by default) and takes Sdc's limit masks at the last patch's corner. Where
// both are exact -- smooth vertices, crease sides of one or two faces, a
// corner's one-face side -- the test asserts 1e-9 of the diagonal and 1e-6
// rad (docs/LIMITS.md), on the other sides of creases and corners too. A
// crease side of three faces, where Bfr approximates, is held to Bfr's
// convergence as its approximation level rises (checkConvergence); wider
// ones are reported with theirs.
// Darts are held to Bfr's convergence too (checkDartConvergence). A vertex
// whose semi-sharp features have not decayed is classed by the side its
// face lies on once they have (core/catmark/semi_sharp_limit.h), under
// uniform or Chaikin's decay, and held as that side is: exact where it
// decays to smooth, to a crease side of one or two faces or to a corner's
// one-face side; to Bfr's convergence where it decays to a dart of valence
// 4. The rest is reported with its figures, not asserted: wider sides and
// darts of other valences, and the cones (a corner's wider side, a cusp),
// which have no tangent plane.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/catmark/limit.h"
#include "core/document/document.h"
#include "core/loop/exact_limit.h"
#include "core/loop/limit.h"
#include "core/schemes/quad_refiner.h"
#include "oracle/bfr_surfaces.h"
#include "oracle/catmark_cases.h"
#include "oracle/osd_catmark_reference.h"
#include "support/polygon_meshes.h"

namespace tessera {
namespace {

using testing::PolyTestMesh;
using Param = std::array<double, 2>;

// What decides whether Bfr's masks are exact at a face's corner: the
// vertex's rule, and for a crease or corner the size of the face's side.
enum class Kind {
  kSmooth,
  kDartOfValence4,
  kDart,
  kCreaseOneFace,  // both of the face's edges at the vertex lie on the crease
  kCreaseTwoFaces,
  kCreaseThreeFaces,
  kCreaseWider,
  kCornerOneFace,
  kCornerWide,
  kCusp
};

// A corner's class: its kind, and whether its vertex has a semi-sharp
// feature that has not decayed, in which case the kind is that of the side
// it lies on once the feature has.
struct Side {
  Kind kind;
  bool semiSharp = false;
  auto operator<=>(const Side&) const = default;
};

std::string nameOf(Side s) {
  const char* name = "?";
  switch (s.kind) {
    case Kind::kSmooth:
      name = "smooth";
      break;
    case Kind::kDartOfValence4:
      name = "dart, valence 4";
      break;
    case Kind::kDart:
      name = "dart, other valence";
      break;
    case Kind::kCreaseOneFace:
      name = "crease side 1 face";
      break;
    case Kind::kCreaseTwoFaces:
      name = "crease side 2 faces";
      break;
    case Kind::kCreaseThreeFaces:
      name = "crease side 3 faces";
      break;
    case Kind::kCreaseWider:
      name = "crease side 4+ faces";
      break;
    case Kind::kCornerOneFace:
      name = "corner side of 1 face";
      break;
    case Kind::kCornerWide:
      name = "corner side 2+ faces";
      break;
    case Kind::kCusp:
      name = "cusp";
      break;
  }
  return s.semiSharp ? std::string("semi-sharp, ") + name : std::string(name);
}

bool bfrIsExact(Side s) {
  return s.kind == Kind::kSmooth || s.kind == Kind::kCreaseOneFace || s.kind == Kind::kCreaseTwoFaces ||
         s.kind == Kind::kCornerOneFace;
}

// The kind of ring face `ringFace`'s side at a vertex of `rule` whose sides
// are bounded by ring edges `bounds` (ascending positions), of valence n.
Kind kindOf(VertexRule rule, const std::vector<int>& bounds, int n, int ringFace) {
  const int m = static_cast<int>(bounds.size());
  switch (rule) {
    case VertexRule::kSmooth:
      return Kind::kSmooth;
    case VertexRule::kDart:
      return n == 4 ? Kind::kDartOfValence4 : Kind::kDart;
    case VertexRule::kCrease:
    case VertexRule::kCorner: {
      if (m < 2) return Kind::kCusp;
      int i = m - 1;
      for (int j = 0; j < m && bounds[j] <= ringFace; ++j) i = j;
      const int faces = (i + 1 < m ? bounds[i + 1] : bounds[0] + n) - bounds[i];
      if (rule == VertexRule::kCrease)
        return faces == 1 ? Kind::kCreaseOneFace
                          : (faces == 2 ? Kind::kCreaseTwoFaces
                                        : (faces == 3 ? Kind::kCreaseThreeFaces : Kind::kCreaseWider));
      return faces == 1 ? Kind::kCornerOneFace : Kind::kCornerWide;
    }
  }
  return Kind::kCusp;
}

// The side of ring face `ringFace` of a vertex whose semi-sharp features
// have not decayed, once they have, from Sdc's semantics alone: semi-sharp
// values decay to smooth, so the infinitely sharp and boundary edges alone
// bound the sides, and the vertex is a corner if its own sharpness is
// infinite, three such edges meet, or (under the edge and corner boundary
// rule) it is a boundary vertex of one face; a crease if two, a dart if
// one, smooth if none.
Side decayedSideOf(const Level& level, Index v, int ringFace, const CreaseOptions& options) {
  const auto edges = level.ringEdgesOf(v);
  const int n = static_cast<int>(edges.size());
  std::vector<int> bounds;
  for (int k = 0; k < n; ++k) {
    const Index e = edges[k];
    if (isInfinite(level.edgeSharpness[e]) || level.edgeFaces[e][1] == kNoIndex) bounds.push_back(k);
  }
  const int m = static_cast<int>(bounds.size());
  const bool oneFaceBoundary =
      n == 2 && level.edgeFaces[edges[0]][1] == kNoIndex && level.edgeFaces[edges[1]][1] == kNoIndex;
  VertexRule rule = m == 0 ? VertexRule::kSmooth : (m == 1 ? VertexRule::kDart : VertexRule::kCrease);
  if (isInfinite(level.vertexSharpness[v]) || m > 2 ||
      (oneFaceBoundary && options.boundary == BoundaryInterpolation::kEdgeAndCorner))
    rule = VertexRule::kCorner;
  return {kindOf(rule, bounds, n, ringFace), true};
}

Side sideOf(const Level& level, Index v, int ringFace, const CreaseOptions& options) {
  if (hasUndecayedSemiSharpness(level, v)) return decayedSideOf(level, v, ringFace, options);
  return {kindOf(level.vertexRules[v], sharpRingEdges(level, v), level.valence(v), ringFace)};
}

struct Corner {
  int baseFace;
  Param uv;
  Vec3 position, normal;
  Side side;
  bool otherSide = false;  // a normal of catmarkOtherLimitSectors
};

// Every face corner of levels 0..levels of an all-quad base with
// Tessera's limit on that face's side, and where it lies in its base face:
// each child face's corners placed by where its vertices come from (a
// parent corner, the middle of a parent edge, the parent's centre), so the
// split's own numbering is not assumed.
std::vector<Corner> tesseraCorners(const PolyTestMesh& mesh, const CreaseOptions& options, int levels) {
  auto refiner = schemes::QuadRefiner::create(mesh.topology, schemes::QuadScheme::kCatmullClark, options,
                                              {.levels = levels});
  if (!refiner.isOk()) throw std::runtime_error(refiner.status().toString());
  const auto points = refiner->refinePointsPerLevel(mesh.points);
  std::vector<std::array<Param, 4>> params(refiner->level(0).numFaces(),
                                           {Param{0, 0}, Param{1, 0}, Param{1, 1}, Param{0, 1}});
  std::vector<int> base(params.size());
  for (size_t f = 0; f < base.size(); ++f) base[f] = static_cast<int>(f);
  std::vector<Corner> corners;
  for (int l = 0; l <= levels; ++l) {
    const Level& level = refiner->level(l);
    if (l > 0) {
      const Level& parent = refiner->level(l - 1);
      const Index nV = parent.numVertices, nF = parent.numFaces();
      std::vector<std::array<Param, 4>> next(level.numFaces());
      std::vector<int> nextBase(level.numFaces());
      for (Index pf = 0; pf < nF; ++pf) {
        const auto pv = parent.faceVerticesOf(pf);
        const auto& P = params[pf];
        auto cornerOf = [&](Index pvertex) {
          for (int i = 0; i < 4; ++i)
            if (pv[i] == pvertex) return i;
          throw std::runtime_error("a child's vertex is no corner of its parent");
        };
        for (int j = 0; j < 4; ++j) {
          const Index cf = parent.faceBegin(pf) + j;
          nextBase[cf] = base[pf];
          const auto cv = level.faceVerticesOf(cf);
          for (int c = 0; c < 4; ++c) {
            const Index x = cv[c];
            Param at;
            if (x < nV) {
              at = P[cornerOf(x)];
            } else if (x < nV + nF) {
              at = {(P[0][0] + P[2][0]) / 2, (P[0][1] + P[2][1]) / 2};
            } else {
              const auto& ends = parent.edgeVertices[x - nV - nF];
              const Param a = P[cornerOf(ends[0])], b = P[cornerOf(ends[1])];
              at = {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2};
            }
            next[cf][c] = at;
          }
        }
      }
      params = std::move(next);
      base = std::move(nextBase);
    }
    for (Index v = 0; v < level.numVertices; ++v) {
      const CatmarkLimitFrame frame = catmarkLimitFrame(level, v, points[l], options);
      const Vec3 primary = (frame.tangent1 % frame.tangent2).normalized();
      const std::vector<LimitSector> others = catmarkOtherLimitSectors(level, v, points[l], options);
      auto ringF = level.ringFacesOf(v);
      for (int k = 0; k < level.valence(v); ++k) {
        const Index f = ringF[k];
        if (f == kNoIndex) continue;
        const int side = catmarkLimitSideOfRingFace(level, v, k, options);
        const Vec3 normal = side == 0 ? primary : others.at(side - 1).normal;
        const int corner = level.vertexInFace(f, v);
        corners.push_back(
            {base[f], params[f][corner], frame.position, normal, sideOf(level, v, k, options), side > 0});
      }
    }
  }
  return corners;
}

struct Worst {
  double position = 0, normal = 0;
  int count = 0, noNormal = 0, otherSides = 0;
};

std::map<Side, Worst> compare(const PolyTestMesh& mesh, const CreaseOptions& options,
                              const std::vector<Corner>& corners, int approxLevel,
                              std::optional<Side> only = std::nullopt) {
  const oracle::OsdPolyInput input(mesh.topology);
  oracle::BfrSurfaces bfr(
      oracle::createOsdQuadRefiner(input, schemes::QuadScheme::kCatmullClark, options, 0, true), mesh.points,
      approxLevel);
  Vec3 lo = mesh.points[0], hi = lo;
  for (const Vec3& p : mesh.points) lo.minimize(p), hi.maximize(p);
  const double diagonal = (hi - lo).norm();
  std::map<Side, Worst> worst;
  for (const Corner& c : corners) {
    if (only && c.side != *only) continue;
    const oracle::BfrValue b = bfr.at(c.baseFace, c.uv);
    Worst& w = worst[c.side];
    w.position = std::max(w.position, (b.position - c.position).norm() / diagonal);
    ++w.count;
    if (b.degenerate) {
      ++w.noNormal;
      continue;
    }
    const double angle = std::atan2((b.normal % c.normal).norm(), dot(b.normal, c.normal));
    w.normal = std::max(w.normal, angle);
    w.otherSides += c.otherSide ? 1 : 0;
  }
  return worst;
}

struct Exact {
  int corners = 0, otherSides = 0;  // compared where Bfr is exact; of them, normals of other sides
  int threeFaceCreaseSides = 0;     // held to Bfr's convergence
  int darts = 0;                    // of valence 4, held to Bfr's convergence
  int semiSharp = 0;                // of them, at semi-sharp vertices
  int semiSharpWithSharp = 0;       // of those, with an infinitely sharp feature too
  int semiSharpDarts = 0;           // decaying to darts of valence 4, held to Bfr's convergence
};

// Where Bfr approximates, it refines to its approximation level and takes
// Limit()'s masks there; its error then shrinks level by level, and is held
// to that approach: at least `position` and `normal` times closer every two
// levels (a position factor of 0: the position is exact, within 1e-9 of
// the diagonal, at every level), ending within `finalPosition` and
// `finalNormal` at level 10 (the deepest Bfr evaluates here: at 11 it
// crashes in evalIrregularDerivs). An answer off the surface would stop the
// approach at its error.
struct Approach {
  double position, normal, finalPosition, finalNormal;
};

// Across a crease into three faces or more Limit()'s tangent across is not
// the surface's (core/catmark/crease_span_tangent.h). Bfr's normal then
// approaches ours by the ratio of the span's next symmetric eigenvalue to
// the tangent's: 0.25 / 0.5797 at three faces, 5.38 times every two levels.
// Limit()'s own mask stays 0.17 rad away at every level. Wider spans
// converge more slowly (2.8 times every two levels at four faces, 2.0 at
// five: numpy's eigenvalues, docs/LIMITS.md) and are reported.
constexpr Approach kThreeFaceCreaseSide{0, 4, 1e-9, 1e-4};

// At a dart Limit() takes the smooth masks and Tessera the dart's own
// eigenvectors (core/catmark/dart_masks.h). Bfr's position approaches ours
// by the ratio of the dart ring's next eigenvalue to 1, and its normal by
// that of the next to the smaller of the tangents' (numpy, docs/LIMITS.md):
// at valence 4, 0.3197 / 0.5 per level, 2.45 times every two levels.
// Limit()'s smooth masks stay 4.3e-3 of the diagonal and 0.56 rad away at
// every level. Darts of other valences are reported.
constexpr Approach kDartOfValence4{4, 2, 1e-6, std::numeric_limits<double>::infinity()};

// Bfr at levels 6, 8 and 10 on `side`'s corners, printed, and held to
// `approach` if given.
void checkConvergence(const PolyTestMesh& mesh, const CreaseOptions& options,
                      const std::vector<Corner>& corners, Side side, int count,
                      std::optional<Approach> approach) {
  Worst previous;
  for (int level : {6, 8, 10}) {
    const Worst w = compare(mesh, options, corners, level, side).at(side);
    std::printf("  %-28s %-22s corners %6d  Bfr level %d: %.2e diag %.2e rad\n", mesh.name.c_str(),
                nameOf(side).c_str(), count, level, w.position, w.normal);
    if (!approach) continue;
    EXPECT_EQ(w.noNormal, 0);
    if (approach->position == 0) EXPECT_LE(w.position, 1e-9) << "Bfr level " << level;
    if (level > 6) {
      if (approach->position > 0)
        EXPECT_LE(w.position, previous.position / approach->position) << "Bfr level " << level;
      EXPECT_LE(w.normal, previous.normal / approach->normal) << "Bfr level " << level;
    }
    previous = w;
  }
  if (!approach) return;
  EXPECT_LE(previous.position, approach->finalPosition);
  EXPECT_LE(previous.normal, approach->finalNormal);
}

Exact checkAgainstBfr(const PolyTestMesh& mesh, const CreaseOptions& options, int levels) {
  SCOPED_TRACE(mesh.name);
  const std::vector<Corner> corners = tesseraCorners(mesh, options, levels);
  const auto atDefault = compare(mesh, options, corners, 6);
  const auto atDeepest = compare(mesh, options, corners, 10);
  Exact exact;
  for (const auto& [side, w] : atDefault) {
    const Worst& deep = atDeepest.at(side);
    std::printf(
        "  %-28s %-22s corners %6d (%4d without Bfr normal)  Bfr level 6: %.2e diag %.2e rad   level 10: "
        "%.2e diag %.2e rad\n",
        mesh.name.c_str(), nameOf(side).c_str(), w.count, w.noNormal, w.position, w.normal, deep.position,
        deep.normal);
    if (side.kind == Kind::kDartOfValence4 || side.kind == Kind::kDart) {
      const bool held = side.kind == Kind::kDartOfValence4;
      checkConvergence(mesh, options, corners, side, w.count,
                       held ? std::optional(kDartOfValence4) : std::nullopt);
      if (held) (side.semiSharp ? exact.semiSharpDarts : exact.darts) += w.count;
      continue;
    }
    if (side.kind == Kind::kCreaseThreeFaces || side.kind == Kind::kCreaseWider) {
      const bool held = side.kind == Kind::kCreaseThreeFaces;
      checkConvergence(mesh, options, corners, side, w.count,
                       held ? std::optional(kThreeFaceCreaseSide) : std::nullopt);
      if (held) exact.threeFaceCreaseSides += w.count;
      continue;
    }
    if (!bfrIsExact(side)) continue;  // reported: see the top of this file
    // A crease side of one face: the face's corner is straight, both its
    // edges there on the crease's limit curve, so Bfr's two derivatives
    // there are parallel and give no normal; elsewhere Bfr gives one.
    if (side.kind == Kind::kCreaseOneFace) {
      EXPECT_EQ(w.noNormal, w.count) << nameOf(side);
    } else {
      EXPECT_EQ(w.noNormal, 0) << nameOf(side);
    }
    EXPECT_LE(w.position, 1e-9) << nameOf(side);
    EXPECT_LE(w.normal, 1e-6) << nameOf(side);
    exact.corners += w.count;
    exact.otherSides += w.otherSides;
    if (side.semiSharp) exact.semiSharp += w.count;
    if (side.semiSharp && side.kind != Kind::kSmooth) exact.semiSharpWithSharp += w.count;
  }
  return exact;
}

// Infinitely sharp creases and corners only (no semi-sharp value), so that
// every side is one of the exact or approximated categories.
PolyTestMesh withSharpTags(const PolyTestMesh& mesh, double edgeFraction, double vertexFraction,
                           uint32_t seed) {
  PolyTestMesh out = testing::withRandomPolyTags(mesh, edgeFraction, vertexFraction, seed);
  for (auto& c : out.topology.creases) c.sharpness = 10.0f;
  for (float& s : out.topology.vertexSharpness) s = s > 0 ? 10.0f : 0.0f;
  out.name += "-sharp";
  return out;
}

TEST(BfrCatmarkLimit, SmoothQuadShapes) {
  int exact = 0;
  exact += checkAgainstBfr(testing::withPolyJitter(testing::quadTorus(7, 5), 0.05, 3), {}, 3).corners;
  exact += checkAgainstBfr(testing::quadGrid(5, 4), {}, 3).corners;
  exact += checkAgainstBfr(testing::quadCube(), {}, 3).corners;
  EXPECT_GT(exact, 1000);
}

TEST(BfrCatmarkLimit, SharpCreasesAndCornersGiveEachSideItsNormal) {
  Exact all;
  auto add = [&](const Exact& e) {
    all.corners += e.corners, all.otherSides += e.otherSides,
        all.threeFaceCreaseSides += e.threeFaceCreaseSides, all.darts += e.darts;
  };
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    add(checkAgainstBfr(
        withSharpTags(testing::withPolyJitter(testing::quadTorus(8, 6), 0.05, seed), 0.2, 0.1, 20 + seed), {},
        2));
  }
  add(checkAgainstBfr(withSharpTags(testing::quadGrid(6, 5), 0.25, 0.1, 30),
                      {CreaseMethod::kUniform, BoundaryInterpolation::kEdgeAndCorner}, 2));
  std::printf(
      "[ measured ] %d corners where Bfr is exact, %d of them on a crease's or corner's other side; %d "
      "crease "
      "sides of 3 faces and %d dart corners held to Bfr's convergence\n",
      all.corners, all.otherSides, all.threeFaceCreaseSides, all.darts);
  EXPECT_GT(all.corners, 1000);
  EXPECT_GT(all.otherSides, 100);
  EXPECT_GT(all.threeFaceCreaseSides, 50);
  EXPECT_GT(all.darts, 500);
}

// Semi-sharp features that have not decayed (core/catmark/semi_sharp_limit.h),
// under uniform and Chaikin's decay: where none of a vertex's features is
// infinitely sharp, it is smooth once they decay (at most 4 levels here,
// sharpness up to 3.8), and Bfr, which refines them away before its
// approximation level, is exact there: such corners are asserted with the
// exact ones. Counted as sharp, Limit()'s masks, they were 3.8e-2 of the
// diagonal and 1.39 rad away.
TEST(BfrCatmarkLimit, UndecayedSemiSharpFeaturesAreTheSurfacesLimit) {
  int exact = 0;
  for (const CreaseOptions& options : oracle::allCreaseOptions()) {
    SCOPED_TRACE(options.creaseMethod == CreaseMethod::kChaikin ? "chaikin" : "uniform");
    exact += checkAgainstBfr(testing::withRandomPolyTags(
                                 testing::withPolyJitter(testing::quadTorus(8, 6), 0.05, 4), 0.2, 0.1, 40),
                             options, 2)
                 .semiSharp;
    exact += checkAgainstBfr(testing::withRandomPolyTags(
                                 testing::withPolyJitter(testing::quadGrid(6, 5), 0.05, 6), 0.3, 0.1, 41),
                             options, 2)
                 .semiSharp;
  }
  std::printf("[ measured ] %d corners of semi-sharp vertices held to Bfr\n", exact);
  EXPECT_GT(exact, 500);
}

// Every other tag infinitely sharp, the rest as drawn (semi-sharp values
// from 0.2 to 3.8, and 10): many vertices where a semi-sharp feature meets
// an infinitely sharp one.
PolyTestMesh withHalfTheTagsSharp(const PolyTestMesh& mesh, double edgeFraction, uint32_t seed) {
  PolyTestMesh out = testing::withRandomPolyTags(mesh, edgeFraction, 0.1, seed);
  for (size_t i = 0; i < out.topology.creases.size(); i += 2) out.topology.creases[i].sharpness = 10.0f;
  out.name += "-half-sharp";
  return out;
}

// A semi-sharp feature beside an infinitely sharp one: once the semi-sharp
// ones decay, the infinitely sharp edges and the boundary alone bound the
// vertex's sides, so a face's corner takes the normal of its side on the
// decayed ring, not of a side that the semi-sharp edge bounded at this
// level. Counting every sharp edge as a bound at this level (the sides of
// Limit()'s masks), these corners were 1.41 rad (uniform) and 1.46 rad
// (Chaikin) from Bfr's normals. Where the vertex decays to a crease side of
// one or two faces or a corner's one-face side, Bfr is exact and the
// corners are asserted with the exact ones; where it decays to a dart of
// valence 4, held to Bfr's convergence as darts are.
TEST(BfrCatmarkLimit, SemiSharpFeaturesBesideInfinitelySharpOnesGiveEachDecayedSideItsNormal) {
  Exact all;
  for (const CreaseOptions& options : oracle::allCreaseOptions()) {
    SCOPED_TRACE(options.creaseMethod == CreaseMethod::kChaikin ? "chaikin" : "uniform");
    for (const PolyTestMesh& mesh :
         {withHalfTheTagsSharp(testing::withPolyJitter(testing::quadTorus(8, 6), 0.05, 7), 0.35, 50),
          withHalfTheTagsSharp(testing::withPolyJitter(testing::quadGrid(6, 5), 0.05, 8), 0.35, 51)}) {
      const Exact e = checkAgainstBfr(mesh, options, 2);
      all.semiSharpWithSharp += e.semiSharpWithSharp;
      all.semiSharpDarts += e.semiSharpDarts;
    }
  }
  std::printf(
      "[ measured ] %d corners of semi-sharp vertices with an infinitely sharp feature held to Bfr where it "
      "is "
      "exact, %d decaying to darts held to its convergence\n",
      all.semiSharpWithSharp, all.semiSharpDarts);
  EXPECT_GT(all.semiSharpWithSharp, 100);
  EXPECT_GT(all.semiSharpDarts, 20);
}

// One drag of direct manipulation: the vertex, where it lies in base face
// 0, its target, and the cage right after the drag.
struct EndDrag {
  int vertex;
  Param uv;
  Vec3 target;
  std::vector<Vec3> cage;
};

// A jittered torus whose edge from face 0's corner 0 (a) to its corner 1
// (b) has `sharpness`, as a Catmull-Clark document; a, then b, dragged to
// within a twentieth of the diagonal of their limits (random from `seed`).
// b is a's neighbour, so each drag's cage is taken before the next drag.
std::vector<EndDrag> dragBothEnds(float sharpness, uint32_t seed, PolyTestMesh& mesh) {
  mesh = testing::withPolyJitter(testing::quadTorus(8, 6), 0.05, 5);
  const int a = mesh.topology.indices[0], b = mesh.topology.indices[1];
  mesh.topology.creases.push_back({a, b, sharpness});
  auto doc = Document::create(mesh.topology, mesh.points,
                              {.loop = {}, .maxLevel = 2, .scheme = DocumentScheme::kCatmullClark});
  if (!doc.isOk()) throw std::runtime_error(doc.status().toString());
  const double diagonal = oracle::boundingDiagonal(mesh.points);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-0.5, 0.5);
  std::vector<EndDrag> drags;
  for (int v : {a, b}) {
    auto before = doc->surface(0, SurfaceKind::kLimit);
    if (!before.isOk()) throw std::runtime_error(before.status().toString());
    const Vec3 target = before->positions[v] + Vec3(unit(rng), unit(rng), unit(rng)) * (0.1 * diagonal);
    const VertexId id(0, static_cast<uint64_t>(v));
    auto moved = doc->moveToLimit(std::span(&id, 1), target);
    if (!moved.isOk()) throw std::runtime_error(moved.status().toString());
    auto cage = doc->surface(0, SurfaceKind::kControl);
    if (!cage.isOk()) throw std::runtime_error(cage.status().toString());
    drags.push_back({v, v == a ? Param{0, 0} : Param{1, 0}, target, std::move(cage->positions)});
  }
  return drags;
}

// Bfr's limit of a drag's cage at the dragged vertex, at approximation
// level `level`, as a fraction of the diagonal from its target.
double offTarget(const PolyTestMesh& mesh, const EndDrag& drag, int level) {
  const oracle::OsdPolyInput input(mesh.topology);
  oracle::BfrSurfaces bfr(
      oracle::createOsdQuadRefiner(input, schemes::QuadScheme::kCatmullClark, {}, 0, true), drag.cage, level);
  return (bfr.at(0, drag.uv).position - drag.target).norm() / oracle::boundingDiagonal(mesh.points);
}

// Direct manipulation at darts (Pulli & Lounsbery, "Hierarchical Editing
// and Rendering of Subdivision Surfaces" §2.2): one infinitely sharp edge
// makes both its ends darts; each is dragged, and Bfr's limit of the edited
// cage at the vertex must approach the target as at every dart above (at
// least 4 times closer every two levels) and lie within 1e-6 of the
// diagonal at level 10. With Limit()'s smooth masks the drag solved for
// lands about 4e-3 of the diagonal away.
TEST(BfrCatmarkLimit, DraggedDartsLandOnTheLimitSurface) {
  PolyTestMesh mesh;
  for (const EndDrag& drag : dragBothEnds(10.0f, 11, mesh)) {
    double previous = 0;
    for (int level : {6, 8, 10}) {
      const double off = offTarget(mesh, drag, level);
      std::printf("  dart v0:%d dragged: Bfr level %d's limit %.2e of the diagonal from the target\n",
                  drag.vertex, level, off);
      if (level > 6) EXPECT_LE(off, previous / 4) << "v0:" << drag.vertex << ", Bfr level " << level;
      previous = off;
    }
    EXPECT_LE(previous, 1e-6) << "v0:" << drag.vertex;
  }
}

// Direct manipulation where a semi-sharp crease acts: both ends of one edge
// of sharpness 2.5 on a jittered torus are dragged (Document::moveToLimit
// solves with the decayed ring's own weight, catmarkSelfLimitWeight), and
// Bfr's limit of the edited cage at each, exact there (the ends decay to
// smooth), must lie within 1e-9 of the diagonal of its target. Counting the
// crease as sharp (Limit()'s masks), the drags land 3.9e-4 and 4.6e-4 of
// the diagonal away.
TEST(BfrCatmarkLimit, DraggedSemiSharpVerticesLandOnTheLimitSurface) {
  PolyTestMesh mesh;
  for (const EndDrag& drag : dragBothEnds(2.5f, 13, mesh)) {
    const double off = offTarget(mesh, drag, 10);
    std::printf("  semi-sharp v0:%d dragged: Bfr's limit %.2e of the diagonal from the target\n", drag.vertex,
                off);
    EXPECT_LE(off, 1e-9) << "v0:" << drag.vertex;
  }
}

}  // namespace
}  // namespace tessera

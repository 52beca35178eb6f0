// Locally interpolating vertices (docs/INTERPOLATION.md, core/loop/ghost_ring.h),
// checked against their definition: the limit surface passes through the
// vertex's control point at every level and after edits around it, it is
// the plain Loop surface outside the vertex's 2-ring, the tension tightens
// it monotonically, and its normals converge at the vertex (tangent-plane
// continuity). The limits come from the dense reference evaluation (exact
// Loop limit masks on the evaluated levels), not from the code under test's
// own claims about the ghost ring.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/document/document.h"
#include "core/document/document_evaluator.h"
#include "core/hierarchy/incidence.h"
#include "core/loop/ghost_ring.h"
#include "core/loop/limit.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

Document makeDocument(const testing::TestMesh& mesh, int maxLevel) {
  auto doc = Document::create(mesh.topology, mesh.points, {.maxLevel = maxLevel});
  EXPECT_TRUE(doc.isOk()) << doc.status().message();
  return std::move(*doc);
}

LimitFrame limitAt(const Document& doc, int level, uint64_t index) {
  auto eval = doc.evaluate(level);
  EXPECT_TRUE(eval.isOk()) << eval.status().message();
  return limitFrame((*eval)->levels[level], static_cast<Index>(index), (*eval)->points[level],
                    doc.options().loop.creaseMethod);
}

Vec3 controlPoint(const Document& doc, VertexId v) {
  auto eval = doc.evaluate(v.level());
  EXPECT_TRUE(eval.isOk());
  return (*eval)->points[v.level()][v.index()];
}

double size(const testing::TestMesh& mesh) {
  Vec3 lo = mesh.points[0], hi = mesh.points[0];
  for (const Vec3& p : mesh.points) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  }
  return (hi - lo).norm();
}

// The limit of v's descendant at every level from v's own to the deepest
// equals v's control point (relative 1e-12), in the dense reference and in
// the sparse hierarchy.
void expectInterpolates(const Document& doc, VertexId v, double scale, const std::string& where) {
  const Vec3 control = controlPoint(doc, v);
  for (int l = v.level() + 1; l <= doc.options().maxLevel; ++l) {
    const Vec3 limit = limitAt(doc, l, v.index()).position;
    EXPECT_LE((limit - control).norm(), 1e-12 * scale)
        << where << ": level " << l << ", limit " << (limit - control).norm() << " from the control point";
  }
  auto local = doc.hierarchy().completeVertex(VertexId(v.level() + 1, v.index()));
  ASSERT_TRUE(local.isOk()) << local.status().message();
  EXPECT_LE((doc.hierarchy().limitPosition(v.level() + 1, *local) - control).norm(), 1e-12 * scale) << where;
}

// A vertex of `level` with this ghost rule (and, for kInterior, valence
// `valence` if > 0), searched from index `from`.
uint64_t findVertex(const Document& doc, int level, GhostRule rule, int valence = 0, uint64_t from = 0) {
  auto eval = doc.evaluate(level);
  const Level& m = (*eval)->levels[level];
  for (Index v = static_cast<Index>(from); v < m.numVertices; ++v) {
    if (ghostRuleOf(m, v) != rule) continue;
    if (valence > 0 && static_cast<int>(m.ringVerticesOf(v).size()) != valence) continue;
    return static_cast<uint64_t>(v);
  }
  ADD_FAILURE() << "no such vertex at level " << level;
  return 0;
}

TEST(InterpolatingVertex, TheLimitIsTheControlPointAtEveryLevelAndAfterEditsAroundIt) {
  const std::vector<testing::TestMesh> meshes = {
      testing::withJitter(testing::icosahedron(), 0.1, 3), testing::withJitter(testing::torus(6, 4), 0.1, 5),
      testing::withJitter(testing::diskWithPole(9), 0.05, 7), testing::doubleTorus()};
  for (const auto& mesh : meshes) {
    const double scale = size(mesh);
    for (int level = 0; level <= 2; ++level) {
      Document doc = makeDocument(mesh, level + 3);
      // A vertex that descends from a base vertex, and one born on an edge.
      const uint64_t inherited = findVertex(doc, level, GhostRule::kInterior);
      const uint64_t born = level == 0 ? inherited : doc.counts().vertices(level - 1) + 1;
      for (uint64_t index : {inherited, born}) {
        Document d = doc;
        const VertexId v(level, index);
        const std::string where = mesh.name + " " + v.toString();
        auto tag = d.setInterpolation(v, true, 1.0);
        ASSERT_TRUE(tag.isOk()) << where << ": " << tag.status().message();
        expectInterpolates(d, v, scale, where);
        // The vertex itself, one of its ring neighbours, and (below the base)
        // the coarser vertex it came from or lies beside.
        ASSERT_TRUE(d.moveBy(std::span(&v, 1), Vec3(0.05, -0.03, 0.02)).isOk());
        expectInterpolates(d, v, scale, where + " after moving it");
        auto eval = d.evaluate(level);
        const VertexId ring(level, static_cast<uint64_t>(
                                       (*eval)->levels[level].ringVerticesOf(static_cast<Index>(index))[0]));
        ASSERT_TRUE(d.moveBy(std::span(&ring, 1), Vec3(-0.04, 0.06, 0.03)).isOk());
        expectInterpolates(d, v, scale, where + " after moving " + ring.toString());
        if (level > 0) {
          const VertexId coarse(level - 1, 0);
          ASSERT_TRUE(d.moveBy(std::span(&coarse, 1), Vec3(0.1, 0.1, -0.1)).isOk());
          expectInterpolates(d, v, scale, where + " after moving " + coarse.toString());
        }
        // Direct manipulation puts the limit, which is the control point, on the target.
        const Vec3 target = controlPoint(d, v) + Vec3(0.02, 0.01, -0.03);
        ASSERT_TRUE(d.moveToLimit(std::span(&v, 1), target).isOk());
        EXPECT_LE((limitAt(d, level + 2, index).position - target).norm(), 1e-12 * scale) << where;
        expectInterpolates(d, v, scale, where + " after dragging it");
        // Undone, it is plain Loop again, bit for bit.
        ASSERT_TRUE(d.undo(*tag).isOk());
        Document plain = doc;
        for (const Edit& e : d.edits()) {
          if (e.active) {
            ASSERT_TRUE(plain.replay(Edit{EditId{plain.nextEditId()}, true, e.change}).isOk());
          }
        }
        const auto a = d.evaluate(level + 3), b = plain.evaluate(level + 3);
        EXPECT_EQ((*a)->points[level + 3], (*b)->points[level + 3]) << where;
        if (HasFailure()) return;
      }
    }
  }
}

TEST(InterpolatingVertex, BoundaryAndCreaseVerticesInterpolateAlongTheirTangent) {
  const testing::TestMesh grid = testing::withJitter(testing::openGrid(5, 4), 0.05, 9);
  const double scale = size(grid);
  Document doc = makeDocument(grid, 5);
  const uint64_t b = findVertex(doc, 1, GhostRule::kCrease);
  const VertexId v(1, b);
  Document d = doc;
  ASSERT_TRUE(d.setInterpolation(v, true, 1.0).isOk());
  expectInterpolates(d, v, scale, "boundary " + v.toString());
  // A tangent of one's own: the boundary limit curve leaves the vertex along
  // it. Its two boundary neighbours at level 5 lie on the tangent line up to
  // their (squared) distance.
  const Vec3 tangent = Vec3(1, 0.3, 0.2).normalized();
  Document t = doc;
  ASSERT_TRUE(t.setInterpolation(v, true, 1.0, tangent).isOk());
  expectInterpolates(t, v, scale, "boundary with a tangent");
  auto eval = t.evaluate(5);
  const Level& m = (*eval)->levels[5];
  std::vector<Vec3> sides;
  for (Index e : m.ringEdgesOf(static_cast<Index>(b))) {
    if (isInfinite(m.edgeSharpness[e])) {
      sides.push_back(
          limitFrame(m, m.otherVertex(e, static_cast<Index>(b)), (*eval)->points[5], CreaseMethod::kUniform)
              .position);
    }
  }
  ASSERT_EQ(sides.size(), 2u);
  const Vec3 chord = (sides[1] - sides[0]).normalized();
  EXPECT_GE(std::abs(dot(chord, tangent)), 1 - 1e-4);
  // An interior crease vertex (two infinitely sharp edges) does the same.
  testing::TestMesh creased = testing::withJitter(testing::torus(6, 4), 0.05, 11);
  Document c = makeDocument(creased, 4);
  const VertexId v0(0, 0);
  auto ring = c.evaluate(0);
  const Level& m0 = (*ring)->levels[0];
  const auto verts = m0.ringVerticesOf(0);
  ASSERT_TRUE(c.setEdgeSharpness(*c.edgeBetween(v0, VertexId(0, verts[0])), kSharpnessInfinite).isOk());
  ASSERT_TRUE(c.setEdgeSharpness(*c.edgeBetween(v0, VertexId(0, verts[3])), kSharpnessInfinite).isOk());
  auto creaseTag = c.setInterpolation(v0, true, 2.0);
  ASSERT_TRUE(creaseTag.isOk()) << creaseTag.status().message();
  expectInterpolates(c, v0, size(creased), "crease vertex");
}

// Faces of level l touching v or one of its ring neighbours: the 2-ring.
std::vector<uint8_t> twoRingFaces(const Level& m, Index v) {
  std::vector<uint8_t> near(m.numFaces(), 0);
  std::vector<Index> closed = {v};
  for (Index u : m.ringVerticesOf(v)) closed.push_back(u);
  for (Index u : closed) {
    for (Index f : m.ringFacesOf(u)) {
      if (f >= 0) near[f] = 1;
    }
  }
  return near;
}

TEST(InterpolatingVertex, OutsideItsTwoRingTheSurfaceIsExactlyPlainLoop) {
  for (const auto& mesh : {testing::withJitter(testing::torus(8, 6), 0.1, 13), testing::doubleTorus()}) {
    const int level = 1, deep = 3;
    Document plain = makeDocument(mesh, deep);
    const uint64_t index = findVertex(plain, level, GhostRule::kInterior);
    Document tagged = plain;
    ASSERT_TRUE(tagged.setInterpolation(VertexId(level, index), true, 2.5).isOk());
    const auto a = plain.evaluate(deep), b = tagged.evaluate(deep);
    const Level& fine = (*a)->levels[deep];
    const std::vector<uint8_t> near = twoRingFaces((*a)->levels[level], static_cast<Index>(index));
    int outside = 0, inside = 0, changedInside = 0;
    for (Index f = 0; f < fine.numFaces(); ++f) {
      const bool isNear = near[f >> (2 * (deep - level))] != 0;
      for (Index w : fine.triangleVertices(f)) {
        const LimitFrame p = limitFrame(fine, w, (*a)->points[deep], CreaseMethod::kUniform);
        const LimitFrame q = limitFrame((*b)->levels[deep], w, (*b)->points[deep], CreaseMethod::kUniform);
        if (!isNear) {
          ++outside;
          ASSERT_EQ(p.position, q.position) << mesh.name << " face " << f << " vertex " << w;
          ASSERT_EQ(p.normal(), q.normal()) << mesh.name << " face " << f << " vertex " << w;
        } else {
          ++inside;
          changedInside += (p.position - q.position).norm() > 1e-9 ? 1 : 0;
        }
      }
    }
    EXPECT_GT(outside, 0);
    EXPECT_GT(changedInside, inside / 4) << mesh.name << ": the tag should change its 2-ring";
  }
}

// The mean distance from the vertex of the limits of its ring one level
// down: how far the surface spreads around the vertex.
double spreadAround(const Document& doc, VertexId v) {
  const int l = v.level() + 1;
  auto eval = doc.evaluate(l);
  const Level& m = (*eval)->levels[l];
  const Vec3 centre = controlPoint(doc, v);
  double sum = 0;
  const auto ring = m.ringVerticesOf(static_cast<Index>(v.index()));
  for (Index u : ring)
    sum += (limitFrame(m, u, (*eval)->points[l], CreaseMethod::kUniform).position - centre).norm();
  return sum / static_cast<double>(ring.size());
}

TEST(InterpolatingVertex, TensionTightensTheSurfaceMonotonicallyAndIsBounded) {
  const testing::TestMesh mesh = testing::withJitter(testing::diskWithPole(7), 0.05, 17);
  Document doc = makeDocument(mesh, 4);
  const VertexId v(0, findVertex(doc, 0, GhostRule::kInterior, 7));
  double previous = std::numeric_limits<double>::infinity();
  for (double tension : {kMinTension, 0.25, 0.5, 1.0, 2.0, 4.0, 16.0, kMaxTension}) {
    Document d = doc;
    ASSERT_TRUE(d.setInterpolation(v, true, tension).isOk()) << tension;
    expectInterpolates(d, v, size(mesh), "tension " + std::to_string(tension));
    const double spread = spreadAround(d, v);
    EXPECT_LT(spread, previous) << "tension " << tension;
    previous = spread;
  }
  for (double bad :
       {0.0, -1.0, kMinTension / 2, kMaxTension * 2, std::nan(""), std::numeric_limits<double>::infinity()}) {
    Document d = doc;
    auto refused = d.setInterpolation(v, true, bad);
    ASSERT_FALSE(refused.isOk()) << bad;
    EXPECT_NE(refused.status().message().find("tension must be in"), std::string::npos)
        << refused.status().message();
    EXPECT_NE(refused.status().message().find(v.toString()), std::string::npos) << refused.status().message();
  }
}

TEST(InterpolatingVertex, NormalsAroundTheVertexConvergeToItsNormal) {
  const testing::TestMesh mesh = testing::withJitter(testing::diskWithPole(9), 0.05, 19);
  Document doc = makeDocument(mesh, 7);
  const VertexId v(0, findVertex(doc, 0, GhostRule::kInterior, 9));
  ASSERT_TRUE(doc.setInterpolation(v, true, 1.5).isOk());
  const Vec3 normal = limitAt(doc, 1, v.index()).normal();
  double previous = M_PI;
  for (int l = 1; l <= 7; ++l) {
    auto eval = doc.evaluate(l);
    const Level& m = (*eval)->levels[l];
    EXPECT_LE((limitAt(doc, l, v.index()).normal() - normal).norm(), 1e-9) << "level " << l;
    double worst = 0;
    for (Index u : m.ringVerticesOf(static_cast<Index>(v.index()))) {
      const Vec3 n = limitFrame(m, u, (*eval)->points[l], CreaseMethod::kUniform).normal();
      worst = std::max(worst, std::acos(std::clamp(dot(n, normal), -1.0, 1.0)));
    }
    EXPECT_LT(worst, previous) << "level " << l;
    previous = worst;
  }
  EXPECT_LT(previous, 0.02) << "ring normals at level 7 are " << previous << " rad from the vertex normal";
}

TEST(InterpolatingVertex, WhatCannotInterpolateIsRefusedByName) {
  const testing::TestMesh mesh = testing::withJitter(testing::torus(6, 4), 0.05, 23);
  Document doc = makeDocument(mesh, 3);
  const VertexId v0(0, 0);
  auto eval = doc.evaluate(0);
  const auto ring = (*eval)->levels[0].ringVerticesOf(0);
  // At the deepest level there is no next level for the ghost ring.
  auto deepest = doc.setInterpolation(VertexId(3, 0), true);
  ASSERT_FALSE(deepest.isOk());
  EXPECT_NE(deepest.status().message().find("deepest level 3"), std::string::npos)
      << deepest.status().message();
  // A dart, a corner and a semi-sharp edge each say why.
  Document dart = doc;
  ASSERT_TRUE(dart.setEdgeSharpness(*dart.edgeBetween(v0, VertexId(0, ring[0])), kSharpnessInfinite).isOk());
  auto refused = dart.setInterpolation(v0, true);
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("v0:0 cannot interpolate: it is a dart"), std::string::npos)
      << refused.status().message();
  Document corner = doc;
  ASSERT_TRUE(corner.setVertexSharpness(v0, kSharpnessInfinite).isOk());
  refused = corner.setInterpolation(v0, true);
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("already interpolates"), std::string::npos)
      << refused.status().message();
  Document semi = doc;
  ASSERT_TRUE(semi.setEdgeSharpness(*semi.edgeBetween(v0, VertexId(0, ring[1])), 1.5f).isOk());
  refused = semi.setInterpolation(v0, true);
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("semi-sharp"), std::string::npos) << refused.status().message();
  // A tangent on an interior vertex means nothing.
  Document interior = doc;
  refused = interior.setInterpolation(v0, true, 1.0, Vec3(1, 0, 0));
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("tangent applies only"), std::string::npos);

  // Once it interpolates: finer moves in its ghost ring and sharpness at it
  // are refused, naming it; a finer move elsewhere is fine.
  Document d = doc;
  ASSERT_TRUE(d.setInterpolation(v0, true).isOk());
  const VertexId child(1, 0), onEdge = doc.counts().childOf(*doc.edgeBetween(v0, VertexId(0, ring[2])));
  for (VertexId moved : {child, onEdge, VertexId(2, 0)}) {
    auto m = d.moveBy(std::span(&moved, 1), Vec3(0, 0, 0.1));
    ASSERT_FALSE(m.isOk()) << moved.toString();
    EXPECT_NE(m.status().message().find("conflicts with interpolating vertex v0:0"), std::string::npos)
        << m.status().message();
  }
  auto crease = d.setEdgeSharpness(*d.edgeBetween(child, onEdge), 2.0f);
  ASSERT_FALSE(crease.isOk());
  EXPECT_NE(crease.status().message().find("conflicts with interpolating vertex v0:0"), std::string::npos);
  ASSERT_FALSE(d.setVertexSharpness(VertexId(2, 0), 1.0f).isOk());
  const VertexId far(1, 14);  // a vertex child: never next to another one
  auto farMove = d.moveBy(std::span(&far, 1), Vec3(0, 0, 0.1));
  ASSERT_TRUE(farMove.isOk()) << farMove.status().message();
  // The other way round: a finer move made first blocks the tag, and a move
  // undone before the tag cannot be redone while it holds.
  Document e = doc;
  auto early = e.moveBy(std::span(&onEdge, 1), Vec3(0, 0.1, 0));
  ASSERT_TRUE(early.isOk());
  refused = e.setInterpolation(v0, true);
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find(early->toString()), std::string::npos)
      << refused.status().message();
  ASSERT_TRUE(e.undo(*early).isOk());
  ASSERT_TRUE(e.setInterpolation(v0, true).isOk());
  Status redo = e.redo(*early);
  ASSERT_FALSE(redo.isOk());
  EXPECT_NE(redo.message().find("conflicts with interpolating vertex v0:0"), std::string::npos)
      << redo.message();

  // Two ghost rings may not share points: no interpolating neighbour at the
  // same level, nor one at or next to its descendant below.
  for (VertexId near : {VertexId(0, static_cast<uint64_t>(ring[1])), onEdge, VertexId(2, 0)}) {
    auto both = d.setInterpolation(near, true);
    ASSERT_FALSE(both.isOk()) << near.toString();
    EXPECT_NE(both.status().message().find("next to interpolating vertex v0:0"), std::string::npos)
        << both.status().message();
  }
  // Undoing an "off" would make it interpolate again: refused while a finer
  // move sits in its ghost ring.
  Document u = doc;
  ASSERT_TRUE(u.setInterpolation(v0, true).isOk());
  auto off = u.setInterpolation(v0, false);
  ASSERT_TRUE(off.isOk());
  ASSERT_TRUE(u.moveBy(std::span(&onEdge, 1), Vec3(0, 0.1, 0)).isOk());
  Status undoOff = u.undo(*off);
  ASSERT_FALSE(undoOff.isOk());
  EXPECT_NE(undoOff.message().find("it would make v0:0 interpolate again"), std::string::npos)
      << undoOff.message();
  EXPECT_FALSE(u.remove(*off).isOk());
}

}  // namespace
}  // namespace tessera

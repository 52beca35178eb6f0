// Morphing between keys of one connectivity (docs/INTERPOLATION.md, core/morph/morph.h),
// checked against definitions: each key's own surface at its time, an
// interpolating vertex on its interpolated path at every time, a surface
// continuous in t, Kochanek-Bartels paths against the Catmull-Rom formula,
// and clear refusals of keys that cannot be morphed.
#include <gtest/gtest.h>

#include "core/document/document.h"
#include "core/loop/limit.h"
#include "core/morph/morph.h"
#include "support/procedural_meshes.h"

namespace tessera {
namespace {

constexpr int kLevel = 3;

// Limit positions of every vertex at kLevel.
std::vector<Vec3> limits(const Document& doc) {
  auto eval = doc.evaluate(kLevel);
  EXPECT_TRUE(eval.isOk()) << eval.status().message();
  const Level& m = (*eval)->levels[kLevel];
  std::vector<Vec3> out;
  for (Index v = 0; v < m.numVertices; ++v) {
    out.push_back(limitFrame(m, v, (*eval)->points[kLevel], doc.options().loop.creaseMethod).position);
  }
  return out;
}

double farthest(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

// Two keys of the jittered torus: the second moved and edited differently.
std::vector<Document> twoKeys() {
  const testing::TestMesh mesh = testing::withJitter(testing::torus(8, 6), 0.05, 31);
  auto a = Document::create(mesh.topology, mesh.points, {.maxLevel = kLevel});
  std::vector<Vec3> moved = mesh.points;
  for (size_t v = 0; v < moved.size(); ++v)
    moved[v] += Vec3(0.3 * std::sin(double(v)), 0.2, 0.1 * std::cos(3.0 * v));
  auto b = Document::create(mesh.topology, moved, {.maxLevel = kLevel});
  EXPECT_TRUE(a.isOk() && b.isOk());
  const VertexId tagged(0, 5), fine(2, 100);
  EXPECT_TRUE(a->setInterpolation(tagged, true, 0.5).isOk());
  EXPECT_TRUE(b->setInterpolation(tagged, true, 4.0).isOk());
  EXPECT_TRUE(a->moveBy(std::span(&fine, 1), Vec3(0, 0, 0.1)).isOk());
  // A semi-sharp edge far from the tagged vertex, smooth in the second key.
  const EdgeId edge(1, 300);
  auto sa = a->setEdgeSharpness(edge, 2.5f);
  EXPECT_TRUE(sa.isOk()) << sa.status().message();
  EXPECT_TRUE(b->setEdgeSharpness(edge, 0).isOk());
  return {std::move(*a), std::move(*b)};
}

TEST(Morph, EachKeyIsReproducedAtItsTime) {
  std::vector<Document> keys = twoKeys();
  const std::vector<Vec3> k0 = limits(keys[0]), k1 = limits(keys[1]);
  auto morph = Morph::create(keys);
  ASSERT_TRUE(morph.isOk()) << morph.status().message();
  auto at0 = morph->at(0), at1 = morph->at(1), half = morph->at(0.5);
  ASSERT_TRUE(at0.isOk() && at1.isOk() && half.isOk()) << at0.status().message() << at1.status().message();
  // Equal up to the order of floating-point sums (a key's moves are summed
  // per vertex in the morph): within 1e-12 of the torus's size (~3).
  EXPECT_LE(farthest(limits(*at0), k0), 3e-12);
  EXPECT_LE(farthest(limits(*at1), k1), 3e-12);
  EXPECT_GT(farthest(limits(*half), k0), 0.05);
  EXPECT_GT(farthest(limits(*half), k1), 0.05);
}

TEST(Morph, AnInterpolatingVertexFollowsItsInterpolatedPosition) {
  auto morph = Morph::create(twoKeys());
  ASSERT_TRUE(morph.isOk());
  for (int i = 0; i <= 20; ++i) {
    const double t = i / 20.0;
    auto doc = morph->at(t);
    ASSERT_TRUE(doc.isOk());
    const Vec3 expected = (1 - t) * morph->key(0).basePoints()[5] + t * morph->key(1).basePoints()[5];
    EXPECT_LE((limits(*doc)[5] - expected).norm(), 1e-12) << "t = " << t;
    ASSERT_TRUE(doc->interpolationOf(VertexId(0, 5)).has_value());
    EXPECT_NEAR(doc->interpolationOf(VertexId(0, 5))->tension, (1 - t) * 0.5 + t * 4.0, 1e-15);
  }
}

TEST(Morph, TheSurfaceIsContinuousInTime) {
  auto morph = Morph::create(twoKeys());
  ASSERT_TRUE(morph.isOk());
  for (double t : {0.0, 0.37, 0.9}) {
    const std::vector<Vec3> base = limits(*morph->at(t));
    double previousRate = 0;
    for (double h : {1e-2, 1e-3, 1e-4, 1e-5}) {
      const double d = farthest(limits(*morph->at(t + h)), base);
      EXPECT_GT(d, 0) << "t " << t << " h " << h;
      // Lipschitz: the change shrinks with the step at a bounded rate.
      if (previousRate > 0) {
        EXPECT_LE(d / h, 2 * previousRate) << "t " << t << " h " << h;
      }
      previousRate = d / h;
    }
  }
}

TEST(Morph, KochanekBartelsPathsFollowTheirDefinition) {
  const testing::TestMesh mesh = testing::icosahedron();
  std::vector<Document> keys;
  for (int k = 0; k < 4; ++k) {
    std::vector<Vec3> p = mesh.points;
    for (Vec3& x : p) x += Vec3(k * k * 0.1, std::sin(k * 1.3), 0.2 * k);
    keys.push_back(*Document::create(mesh.topology, p, {.maxLevel = kLevel}));
  }
  auto morph = Morph::create(keys);
  ASSERT_TRUE(morph.isOk());
  ASSERT_TRUE(morph->setPath(0, {}).isOk());
  ASSERT_TRUE(morph->setPath(1, {.tension = 1}).isOk());
  auto P = [&](int k, int v) { return keys[k].basePoints()[v]; };
  for (int k = 0; k < 4; ++k) {
    for (int v : {0, 1, 2}) EXPECT_EQ(morph->pointAt(v, k / 3.0), P(k, v)) << "key " << k;
  }
  // Catmull-Rom (T = C = B = 0) through keys 0..3 at the middle of segment 1..2.
  const Vec3 cr = 0.5 * (2 * P(1, 0) + 0.5 * (P(2, 0) - P(0, 0)) +
                         0.25 * (2 * P(0, 0) - 5 * P(1, 0) + 4 * P(2, 0) - P(3, 0)) +
                         0.125 * (-1 * P(0, 0) + 3 * P(1, 0) - 3 * P(2, 0) + P(3, 0)));
  EXPECT_LE((morph->pointAt(0, 0.5) - cr).norm(), 1e-14);
  // Tension 1: zero tangents, so the middle is the mean of the two keys.
  EXPECT_LE((morph->pointAt(1, 0.5) - 0.5 * (P(1, 1) + P(2, 1))).norm(), 1e-14);
  // Without a path: linear between the two keys around t.
  EXPECT_LE((morph->pointAt(2, 0.5) - 0.5 * (P(1, 2) + P(2, 2))).norm(), 1e-15);
  EXPECT_FALSE(morph->setPath(0, {.bias = 2}).isOk());
  EXPECT_EQ(morph->setPath(99, {}).code(), ErrorCode::kNotFound);
}

TEST(Morph, KeysThatCannotBeMorphedAreRefusedSayingWhere) {
  const testing::TestMesh mesh = testing::withJitter(testing::torus(6, 4), 0.05, 3);
  auto a = *Document::create(mesh.topology, mesh.points, {.maxLevel = 3});
  BaseTopology turned = mesh.topology;
  std::rotate(turned.triangles[7].begin(), turned.triangles[7].begin() + 1, turned.triangles[7].end());
  auto b = *Document::create(turned, mesh.points, {.maxLevel = 3});
  auto refused = Morph::create({a, b});
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("triangle 7 is ("), std::string::npos)
      << refused.status().message();
  EXPECT_NE(refused.status().message().find("in key 0 but ("), std::string::npos)
      << refused.status().message();
  const testing::TestMesh other = testing::torus(6, 5);
  refused = Morph::create({a, *Document::create(other.topology, other.points, {.maxLevel = 3})});
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("key 1 has 30 vertices, key 0 has 24"), std::string::npos)
      << refused.status().message();
  refused = Morph::create({a, *Document::create(mesh.topology, mesh.points, {.maxLevel = 4})});
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("other document options"), std::string::npos);
  EXPECT_FALSE(Morph::create({a}).isOk());
  // An interpolating tag in one key only cannot be interpolated.
  Document tagged = a;
  ASSERT_TRUE(tagged.setInterpolation(VertexId(1, 3), true).isOk());
  auto morph = Morph::create({a, tagged});
  ASSERT_TRUE(morph.isOk());
  auto at = morph->at(0.5);
  ASSERT_FALSE(at.isOk());
  EXPECT_NE(at.status().message().find("v1:3 has an interpolating tag in key 1 but not in key 0"),
            std::string::npos)
      << at.status().message();
}

}  // namespace
}  // namespace tessera

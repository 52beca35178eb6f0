// The sparse hierarchy's levels under Catmull-Clark's quad split
// (core/hierarchy/sparse_level.h, sparse_quad_split.cc), against the
// uniform quad split (core/catmark/quad_split.h), whose points the oracle
// tests hold to OpenSubdiv Far: a level refined whole must be the uniform
// level element for element, and any sparse level, built at once or grown
// in place, must hold each present element with the uniform level's
// relations, read through canonical ids. Meshes: polygon meshes with
// boundaries, triangles and n-gons, and random creases from fixed seeds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <set>

#include "core/catmark/limit.h"
#include "core/catmark/quad_split.h"
#include "core/catmark/semi_sharp_limit.h"
#include "core/hierarchy/incidence.h"
#include "core/hierarchy/level_limits.h"
#include "core/hierarchy/sparse_far_rings.h"
#include "core/hierarchy/sparse_level.h"
#include "support/polygon_meshes.h"
#include "support/sparse_levels.h"

namespace tessera {
namespace {

using testing::PolyTestMesh;

std::vector<PolyTestMesh> meshes() {
  using namespace testing;
  return {quadCube(), withRandomPolyTags(quadGrid(4, 3), 0.3, 0.2, 7),
          withRandomPolyTags(quadTorus(6, 4), 0.25, 0.1, 11),
          withRandomPolyTags(mixedPrism(5, false), 0.3, 0.2, 3),
          withRandomPolyTags(mixedPrism(6, true), 0.3, 0.2, 5)};
}

struct Uniform {
  std::vector<Level> levels;
  LevelCounts counts;
};

Uniform uniformLevels(const PolyTestMesh& mesh, const LoopOptions& options, int depth) {
  auto base = buildPolyLevel(mesh.topology, options);
  EXPECT_TRUE(base.isOk()) << base.status().toString();
  Uniform u{{}, testing::quadCountsOf(*base, depth)};
  u.levels.push_back(std::move(*base));
  for (int l = 0; l < depth; ++l)
    u.levels.push_back(splitToQuads(u.levels.back(), options, SplitDetail::kFull));
  return u;
}

// A present face's canonical id, or the uniform level's marker.
int64_t faceIdOr(const SparseLevel& s, Index f) {
  return f >= 0 ? static_cast<int64_t>(s.faceIds[f]) : f;
}

// Every element `s` holds is the uniform level's element of its id, with
// the same relations through ids: corners and edges of faces, ends and
// faces of edges, sharpness and rules, and the whole ring of each complete
// vertex; an incomplete vertex lists exactly its present faces.
void expectMatchesUniform(const SparseLevel& s, const Level& u, const std::string& where) {
  const Level& m = s.mesh;
  ASSERT_EQ(m.regularFaceSize, 4) << where;
  for (Index f = 0; f < m.numFaces(); ++f) {
    const auto uf = static_cast<Index>(s.faceIds[f]);
    ASSERT_LT(uf, u.numFaces()) << where;
    ASSERT_EQ(s.findFace(s.faceIds[f]), f) << where;
    for (int k = 0; k < 4; ++k) {
      ASSERT_EQ(s.vertexIds[m.faceVerticesOf(f)[k]], static_cast<uint64_t>(u.faceVerticesOf(uf)[k]))
          << where << " face f" << s.depth << ":" << uf << " corner " << k;
      ASSERT_EQ(s.edgeIds[m.faceEdgesOf(f)[k]], static_cast<uint64_t>(u.faceEdgesOf(uf)[k]))
          << where << " face f" << s.depth << ":" << uf << " edge " << k;
    }
  }
  for (Index e = 0; e < m.numEdges(); ++e) {
    const auto ue = static_cast<Index>(s.edgeIds[e]);
    ASSERT_EQ(s.findEdge(s.edgeIds[e]), e) << where;
    for (int k = 0; k < 2; ++k) {
      ASSERT_EQ(s.vertexIds[m.edgeVertices[e][k]], static_cast<uint64_t>(u.edgeVertices[ue][k])) << where;
      const Index sf = m.edgeFaces[e][k], uf = u.edgeFaces[ue][k];
      if (uf == kNoIndex) {
        ASSERT_EQ(sf, kNoIndex) << where << " edge e" << s.depth << ":" << ue;
      } else if (sf == kAbsentFace) {
        ASSERT_EQ(s.findFace(static_cast<uint64_t>(uf)), kNoIndex) << where << " an absent face is present";
      } else {
        ASSERT_EQ(faceIdOr(s, sf), uf) << where << " edge e" << s.depth << ":" << ue << " face " << k;
        ASSERT_EQ(m.edgeFaceLocal[e][k], u.edgeFaceLocal[ue][k]) << where;
      }
    }
    ASSERT_EQ(m.edgeSharpness[e], u.edgeSharpness[ue]) << where << " edge e" << s.depth << ":" << ue;
  }
  int complete = 0;
  for (Index v = 0; v < m.numVertices; ++v) {
    const auto uv = static_cast<Index>(s.vertexIds[v]);
    ASSERT_EQ(s.findVertex(s.vertexIds[v]), v) << where;
    ASSERT_EQ(m.vertexSharpness[v], u.vertexSharpness[uv]) << where << " vertex v" << s.depth << ":" << uv;
    ASSERT_EQ(m.vertexRules[v], u.vertexRules[uv]) << where << " vertex v" << s.depth << ":" << uv;
    ASSERT_EQ(m.valence(v), u.valence(uv)) << where << " row of v" << s.depth << ":" << uv;
    std::set<uint64_t> uniformPresent;
    for (Index uf : u.ringFacesOf(uv)) {
      if (uf != kNoIndex && s.findFace(static_cast<uint64_t>(uf)) != kNoIndex) uniformPresent.insert(uf);
    }
    const int uniformFaces = u.numRingFaces(uv);
    ASSERT_EQ(s.isComplete(v), static_cast<int>(uniformPresent.size()) == uniformFaces)
        << where << " v" << s.depth << ":" << uv;
    if (!s.isComplete(v)) {
      std::set<uint64_t> listed;
      for (Index f : m.ringFacesOf(v)) {
        if (f >= 0) listed.insert(s.faceIds[f]);
      }
      ASSERT_EQ(listed, uniformPresent) << where << " incomplete v" << s.depth << ":" << uv;
      continue;
    }
    ++complete;
    for (int k = 0; k < m.valence(v); ++k) {
      const Index at = m.ringOffsets[v] + k, uat = u.ringOffsets[uv] + k;
      ASSERT_EQ(s.edgeIds[m.ringEdges[at]], static_cast<uint64_t>(u.ringEdges[uat])) << where;
      ASSERT_EQ(s.vertexIds[m.ringVertices[at]], static_cast<uint64_t>(u.ringVertices[uat])) << where;
      ASSERT_EQ(faceIdOr(s, m.ringFaces[at]), u.ringFaces[uat]) << where;
      if (u.ringFaces[uat] != kNoIndex) ASSERT_EQ(m.ringFaceLocal[at], u.ringFaceLocal[uat]) << where;
    }
  }
  EXPECT_GT(complete, 0) << where;
}

Buffer<uint8_t> flags(const SparseLevel& level, const std::vector<Index>& faces) {
  Buffer<uint8_t> out(level.mesh.numFaces(), 0);
  for (Index f : faces) out[f] = 1;
  return out;
}

TEST(SparseQuadLevel, CountsAndParentsAreTheUniformSplits) {
  for (const PolyTestMesh& mesh : meshes()) {
    const Uniform u = uniformLevels(mesh, {}, 3);
    for (int l = 0; l <= 3; ++l) {
      EXPECT_EQ(u.counts.vertices(l), static_cast<uint64_t>(u.levels[l].numVertices)) << mesh.name << l;
      EXPECT_EQ(u.counts.edges(l), static_cast<uint64_t>(u.levels[l].numEdges())) << mesh.name << l;
      EXPECT_EQ(u.counts.faces(l), static_cast<uint64_t>(u.levels[l].numFaces())) << mesh.name << l;
      EXPECT_EQ(u.counts.corners(l), static_cast<uint64_t>(u.levels[l].numCorners())) << mesh.name << l;
    }
    // Children of face f are counts.childFace(f, j); each names f as parent
    // and its base face as the root it descends from.
    for (int l = 0; l < 3; ++l) {
      for (Index f = 0; f < u.levels[l].numFaces(); ++f) {
        const FaceId id(l, static_cast<uint64_t>(f));
        ASSERT_EQ(u.counts.faceSize(id), u.levels[l].faceSize(f));
        for (int j = 0; j < u.levels[l].faceSize(f); ++j) {
          const FaceId child = u.counts.childFace(id, j);
          ASSERT_EQ(u.counts.parentFace(child), id) << mesh.name;
          ASSERT_EQ(u.counts.baseFace(child), u.counts.baseFace(id)) << mesh.name;
          // Child j holds face f's corner j as a corner.
          const auto corners = u.levels[l + 1].faceVerticesOf(static_cast<Index>(child.index()));
          ASSERT_NE(std::find(corners.begin(), corners.end(), u.levels[l].faceVerticesOf(f)[j]),
                    corners.end());
        }
        const VertexId center = u.counts.faceVertexOf(id);
        ASSERT_EQ(u.counts.originOf(center), LevelCounts::Origin::kFace);
        ASSERT_EQ(u.counts.parentFaceOfVertex(center), id);
      }
      for (Index e = 0; e < u.levels[l].numEdges(); ++e) {
        const VertexId mid = u.counts.childOf(EdgeId(l, static_cast<uint64_t>(e)));
        ASSERT_EQ(u.counts.originOf(mid), LevelCounts::Origin::kEdge);
        ASSERT_EQ(u.counts.parentEdge(mid), EdgeId(l, static_cast<uint64_t>(e)));
        // The vertex on edge e is on both halves of it.
        ASSERT_EQ(u.levels[l + 1].edgeVertices[u.counts.corners(l) + 2 * e][0],
                  static_cast<Index>(mid.index()));
      }
    }
    // A face's ancestor at each level is its parent's parent and so on.
    for (Index f = 0; f < u.levels[3].numFaces(); ++f) {
      FaceId up(3, static_cast<uint64_t>(f));
      for (int k = 3; k >= 0; --k) {
        ASSERT_EQ(u.counts.ancestorAt(FaceId(3, static_cast<uint64_t>(f)), k), up)
            << mesh.name << " level " << k;
        if (k > 0) up = u.counts.parentFace(up);
      }
    }
  }
}

// Ids resolve by arithmetic from the base level alone (incidence.h), as
// the hierarchy needs before it holds a part of a level: a face holding
// every vertex and edge, the ends of every edge, and the edge between two
// vertices, all as the uniform split has them.
TEST(SparseQuadLevel, IdsResolveToTheirFacesEndsAndEdgesByArithmetic) {
  for (const PolyTestMesh& mesh : meshes()) {
    const Uniform u = uniformLevels(mesh, {}, 3);
    const Level& base = u.levels[0];
    for (int l = 0; l <= 3; ++l) {
      const Level& w = u.levels[l];
      const std::string where = mesh.name + " level " + std::to_string(l);
      for (Index v = 0; v < w.numVertices; ++v) {
        const FaceId f = incidentFace(base, u.counts, VertexId(l, static_cast<uint64_t>(v)));
        ASSERT_EQ(f.level(), l);
        ASSERT_GE(w.vertexInFace(static_cast<Index>(f.index()), v), 0) << where << " vertex " << v;
      }
      for (Index e = 0; e < w.numEdges(); ++e) {
        const EdgeId id(l, static_cast<uint64_t>(e));
        const auto fe = w.faceEdgesOf(static_cast<Index>(incidentFace(base, u.counts, id).index()));
        ASSERT_NE(std::find(fe.begin(), fe.end(), e), fe.end()) << where << " edge " << e;
        const auto ends = edgeEnds(base, u.counts, id);
        ASSERT_EQ(ends[0].index(), static_cast<uint64_t>(w.edgeVertices[e][0])) << where << " edge " << e;
        ASSERT_EQ(ends[1].index(), static_cast<uint64_t>(w.edgeVertices[e][1])) << where << " edge " << e;
        for (const auto& [a, b] : {std::pair(ends[0], ends[1]), std::pair(ends[1], ends[0])}) {
          const auto between = edgeBetween(base, u.counts, a, b);
          ASSERT_TRUE(between.isOk()) << where << " " << between.status().toString();
          ASSERT_EQ(*between, id) << where;
        }
      }
      // Opposite corners of a quad are joined by no edge.
      if (l > 0) {
        const auto fv = w.faceVerticesOf(0);
        const auto apart = edgeBetween(base, u.counts, VertexId(l, static_cast<uint64_t>(fv[0])),
                                       VertexId(l, static_cast<uint64_t>(fv[2])));
        ASSERT_FALSE(apart.isOk()) << where;
        EXPECT_NE(apart.status().message().find("are not joined by an edge of level"), std::string::npos)
            << apart.status().toString();
      }
    }
  }
}

TEST(SparseQuadLevel, RefinedWholeIsTheUniformLevel) {
  for (const PolyTestMesh& mesh : meshes()) {
    for (CreaseMethod method : {CreaseMethod::kUniform, CreaseMethod::kChaikin}) {
      const LoopOptions options{.creaseMethod = method};
      const Uniform u = uniformLevels(mesh, options, 3);
      std::vector<SparseLevel> levels;
      levels.push_back(sparseBaseLevel(u.levels[0]));
      for (int l = 0; l < 3; ++l) {
        const Buffer<uint8_t> all(levels[l].mesh.numFaces(), 1);
        levels.push_back(refineSparse(levels[l], all, u.counts, options));
        const SparseLevel& s = levels.back();
        const Level& w = u.levels[l + 1];
        const std::string where = mesh.name + " level " + std::to_string(l + 1);
        // Refined whole, local indices are the uniform ones.
        ASSERT_EQ(s.mesh.numVertices, w.numVertices) << where;
        for (Index v = 0; v < w.numVertices; ++v)
          ASSERT_EQ(s.vertexIds[v], static_cast<uint64_t>(v)) << where;
        for (Index e = 0; e < w.numEdges(); ++e) ASSERT_EQ(s.edgeIds[e], static_cast<uint64_t>(e)) << where;
        for (Index f = 0; f < w.numFaces(); ++f) ASSERT_EQ(s.faceIds[f], static_cast<uint64_t>(f)) << where;
        EXPECT_TRUE(s.vertexOrder.empty() && s.edgeOrder.empty() && s.faceOrder.empty()) << where;
        EXPECT_EQ(std::vector<Index>(s.mesh.faceVertices.begin(), s.mesh.faceVertices.end()),
                  std::vector<Index>(w.faceVertices.begin(), w.faceVertices.end()))
            << where;
        EXPECT_EQ(s.mesh.maxValence, w.maxValence) << where;
        expectMatchesUniform(s, w, where);
        for (Index f = 0; f < w.numFaces(); ++f) {
          ASSERT_EQ(s.parentOfFace(f), static_cast<Index>(u.counts.parentFace(FaceId(l + 1, f)).index()));
        }
      }
    }
  }
}

TEST(SparseQuadLevel, SparseLevelsHoldTheUniformRelationsBuiltAtOnceOrGrown) {
  std::mt19937 rng(2026);
  for (const PolyTestMesh& mesh : meshes()) {
    const LoopOptions options{.creaseMethod = CreaseMethod::kChaikin};
    const Uniform u = uniformLevels(mesh, options, 3);
    for (int trial = 0; trial < 4; ++trial) {
      // Two sparse hierarchies: one built at once from the union of two
      // random selections, one built from the first and grown by the second.
      std::vector<SparseLevel> once, grown;
      once.push_back(sparseBaseLevel(u.levels[0]));
      grown.push_back(sparseBaseLevel(u.levels[0]));
      for (int l = 0; l < 3; ++l) {
        const double fraction = l == 0 ? 0.5 : 0.6;
        std::vector<Index> first = testing::refinableFaces(once[l], fraction, rng);
        std::vector<Index> second = testing::refinableFaces(once[l], fraction, rng);
        std::set<Index> both(first.begin(), first.end());
        both.insert(second.begin(), second.end());
        if (both.empty()) break;
        once.push_back(refineSparse(once[l], flags(once[l], {both.begin(), both.end()}), u.counts, options));
        // The grown copy's parent has the same local order as once's up to
        // its own growth; map the faces through ids.
        auto local = [&](Index f) { return grown[l].findFace(once[l].faceIds[f]); };
        std::vector<Index> a, b;
        for (Index f : first) a.push_back(local(f));
        for (Index f : both) {
          if (std::find(first.begin(), first.end(), f) == first.end()) b.push_back(local(f));
        }
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        grown.push_back(refineSparse(grown[l], flags(grown[l], a), u.counts, options));
        const LevelExtension ext = extendSparse(grown[l], grown[l + 1], b, u.counts, options);
        const std::string where =
            mesh.name + " trial " + std::to_string(trial) + " level " + std::to_string(l + 1);
        expectMatchesUniform(once.back(), u.levels[l + 1], where + " at once");
        expectMatchesUniform(grown.back(), u.levels[l + 1], where + " grown");
        ASSERT_EQ(once.back().mesh.numVertices, grown.back().mesh.numVertices) << where;
        ASSERT_EQ(once.back().mesh.numEdges(), grown.back().mesh.numEdges()) << where;
        ASSERT_EQ(once.back().mesh.numFaces(), grown.back().mesh.numFaces()) << where;
        // What the growth completed is what it reports.
        for (Index v = 0; v < grown.back().mesh.numVertices; ++v) {
          const bool listed = std::binary_search(ext.completed.begin(), ext.completed.end(), v);
          if (listed) ASSERT_TRUE(grown.back().isComplete(v)) << where;
        }
        for (Index f = 0; f < grown.back().mesh.numFaces(); ++f) {
          const Index parent = grown.back().parentOfFace(f);
          ASSERT_EQ(grown[l].faceIds[parent],
                    u.counts.parentFace(FaceId(l + 1, grown.back().faceIds[f])).index())
              << where;
        }
      }
    }
  }
}

// Chaikin's decay reads the sharpness of every edge at the far end of a
// semi-sharp edge, which a sparse level holds whole only at its complete
// vertices; SparseFarRings derives the rest from the parent
// (core/hierarchy/sparse_far_rings.h). On random sparse levels, the edges it
// gives at every present vertex (their non-smooth sharpness, which is all
// the decay reads) are the uniform level's, and the limit of every complete
// vertex with an undecayed semi-sharp feature, and its own weight, are the
// ones the uniform level gives from the same points
// (core/catmark/semi_sharp_limit.h).
TEST(SparseQuadLevel, FarRingsAndSemiSharpLimitsAreTheUniformLevels) {
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> unit(-1, 1);
  int derived = 0, semiSharpLimits = 0, acrossIncomplete = 0;
  auto nonSmooth = [](std::vector<float> s) {
    s.erase(std::remove(s.begin(), s.end(), kSharpnessSmooth), s.end());
    std::sort(s.begin(), s.end());
    return s;
  };
  for (const PolyTestMesh& mesh : meshes()) {
    const LoopOptions options{.creaseMethod = CreaseMethod::kChaikin};
    const Uniform u = uniformLevels(mesh, options, 3);
    for (int trial = 0; trial < 16; ++trial) {
      std::vector<SparseLevel> levels;
      levels.push_back(sparseBaseLevel(u.levels[0]));
      for (int l = 0; l < 3; ++l) {
        const std::vector<Index> faces = testing::refinableFaces(levels[l], l == 0 ? 0.5 : 0.6, rng);
        if (faces.empty()) break;
        levels.push_back(refineSparse(levels[l], flags(levels[l], faces), u.counts, options));
        const SparseLevel& s = levels.back();
        const Level& w = u.levels[l + 1];
        const std::string where =
            mesh.name + " trial " + std::to_string(trial) + " level " + std::to_string(l + 1);
        const SparseFarRings far(s, &levels[l], options);
        std::vector<float> got;
        std::vector<bool> complete(static_cast<size_t>(s.mesh.numVertices));
        for (Index v = 0; v < s.mesh.numVertices; ++v) {
          const auto id = static_cast<Index>(s.vertexIds[v]);
          complete[static_cast<size_t>(v)] = s.isComplete(v);
          far.edgesAt(v, got);
          std::vector<float> whole(static_cast<size_t>(w.valence(id)));
          w.ringSharpness(id, whole.data());
          ASSERT_EQ(nonSmooth(got), nonSmooth(whole)) << where << " edges at v" << l + 1 << ":" << id;
          derived += s.isComplete(v) ? 0 : 1;
        }
        if (!LevelLimits::hasLimits(s.mesh, SplitKind::kQuads)) continue;
        std::vector<Vec3> wholePoints(static_cast<size_t>(w.numVertices));
        for (Vec3& p : wholePoints) p = Vec3(unit(rng), unit(rng), unit(rng));
        std::vector<Vec3> points(static_cast<size_t>(s.mesh.numVertices));
        for (Index v = 0; v < s.mesh.numVertices; ++v)
          points[static_cast<size_t>(v)] = wholePoints[static_cast<size_t>(s.vertexIds[v])];
        const LevelLimits limits(s, &levels[l], options, SplitKind::kQuads);
        for (Index v = 0; v < s.mesh.numVertices; ++v) {
          if (!s.isComplete(v) || !takesDecayedLimit(s.mesh, v, options)) continue;
          const auto id = static_cast<Index>(s.vertexIds[v]);
          const LimitFrame sparse = limits.frame(v, points);
          const CatmarkLimitFrame dense = catmarkLimitFrame(w, id, wholePoints, options);
          ASSERT_LE((sparse.position - dense.position).norm(), 1e-12)
              << where << " limit of v" << l + 1 << ":" << id;
          ASSERT_LE((sparse.tangent1 - dense.tangent1).norm(), 1e-12)
              << where << " tangent of v" << l + 1 << ":" << id;
          ASSERT_LE((sparse.tangent2 - dense.tangent2).norm(), 1e-12)
              << where << " tangent of v" << l + 1 << ":" << id;
          const SparseFarRings farOfV(s, &levels[l], options);
          ASSERT_NEAR(catmarkSelfLimitWeight(s.mesh, v, options, &farOfV),
                      catmarkSelfLimitWeight(w, id, options), 1e-14)
              << where << " own weight of v" << l + 1 << ":" << id;
          ++semiSharpLimits;
          for (Index x : s.mesh.ringVerticesOf(v))
            acrossIncomplete += complete[static_cast<size_t>(x)] ? 0 : 1;
        }
      }
    }
  }
  std::printf(
      "edges derived at %d incomplete vertices; %d semi-sharp limits, %d of their neighbours incomplete\n",
      derived, semiSharpLimits, acrossIncomplete);
  EXPECT_GT(derived, 100);
  EXPECT_GT(semiSharpLimits, 50);
  EXPECT_GT(acrossIncomplete, 50);
}

}  // namespace
}  // namespace tessera

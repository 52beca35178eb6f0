// A document at level N written to .usda as a subdivision cage
// (core/document/document_cage.h, docs/FORMATS.md "USD") and read back, then
// refined k more levels by OpenSubdiv 3.5 (Far, the scheme, boundary rule,
// crease method and tags the file states), gives the document's own level
// N + k: every one of Far's points is a different one of the document's
// within 1e-9. The documents are Loop and Catmull-Clark tori with base
// semi-sharp creases and corners, sharpness edits and moves at levels 1 to
// N, under both crease methods. Points are matched by position: neither
// numbering is assumed to be the other's.
#include <gtest/gtest.h>

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include "core/document/document.h"
#include "core/document/document_cage.h"
#include "core/io/mesh_export.h"
#include "core/io/mesh_import.h"
#include "core/schemes/polygon_reader.h"
#include "core/util/file_io.h"
#include "oracle/osd_catmark_reference.h"
#include "support/polygon_meshes.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

// A torus of nu x nv quads, or of their halves, as a hand-made usda layer
// with semi-sharp creases around one ring and one along, and two corners.
std::string torusUsda(bool triangles) {
  const testing::PolyTestMesh torus = testing::quadTorus(8, 6);
  std::ostringstream s;
  s.precision(17);
  s << "#usda 1.0\n(\n    upAxis = \"Z\"\n)\n\ndef Xform \"World\"\n{\n    def Mesh \"Torus\"\n    {\n";
  s << "        uniform token subdivisionScheme = \"" << (triangles ? "loop" : "catmullClark") << "\"\n";
  std::vector<int> counts, indices;
  const auto& t = torus.topology;
  for (int f = 0; f < t.numFaces(); ++f) {
    const int* q = &t.indices[t.faceOffsets[f]];
    if (triangles) {
      counts.insert(counts.end(), {3, 3});
      indices.insert(indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
    } else {
      counts.push_back(4);
      indices.insert(indices.end(), q, q + 4);
    }
  }
  auto list = [&s](const std::vector<int>& v) {
    s << "[";
    for (size_t k = 0; k < v.size(); ++k) s << (k ? ", " : "") << v[k];
    s << "]\n";
  };
  s << "        int[] faceVertexCounts = ";
  list(counts);
  s << "        int[] faceVertexIndices = ";
  list(indices);
  s << "        point3f[] points = [";
  for (size_t v = 0; v < torus.points.size(); ++v)
    s << (v ? ", " : "") << "(" << torus.points[v][0] << ", " << torus.points[v][1] << ", "
      << torus.points[v][2] << ")";
  s << "]\n";
  // The ring i = 0 (vertices 0..5, closed) at 2.5 per edge, and a chain
  // along j = 0 (vertices 0, 6, 12, 18) at 1.25 for the whole chain.
  s << "        int[] creaseIndices = [0, 1, 2, 3, 4, 5, 0, 6, 12, 18]\n";
  s << "        int[] creaseLengths = [7, 3]\n";
  s << "        float[] creaseSharpnesses = [2.5, 2.5, 2.5, 2.5, 2.5, 2.5, 1.25, 1.25]\n";
  s << "        int[] cornerIndices = [27, 40]\n";
  s << "        float[] cornerSharpnesses = [1.5, 10]\n";
  s << "    }\n}\n";
  return s.str();
}

Expected<Document> documentOf(bool triangles, CreaseMethod method, int maxLevel) {
  DocumentOptions options;
  options.loop.creaseMethod = method;
  options.maxLevel = maxLevel;
  const std::string text = torusUsda(triangles);
  if (triangles) {
    TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, importMeshFromBytes(text, ".usda", "torus.usda"));
    options.scheme = DocumentScheme::kLoop;
    return Document::create(mesh, options);
  }
  TESSERA_ASSIGN_OR_RETURN(schemes::PolygonMesh mesh,
                           schemes::importPolygonMeshFromBytes(text, ".usda", "torus.usda"));
  options.scheme = DocumentScheme::kCatmullClark;
  return Document::create(std::move(mesh.topology), std::move(mesh.points), options);
}

// Edits at levels 1..n: moves, an edge's and a vertex's sharpness.
void edit(Document& doc, int n) {
  for (int l = 1; l <= n; ++l) {
    const VertexId v(l, 3 + 5 * l);
    ASSERT_TRUE(doc.moveBy(std::span(&v, 1), Vec3(0.05 * l, -0.03, 0.08)).isOk());
    const VertexId w(l, 17 + l);
    ASSERT_TRUE(doc.moveBy(std::span(&w, 1), Vec3(-0.04, 0.02 * l, 0.01)).isOk());
  }
  ASSERT_TRUE(doc.setEdgeSharpness(EdgeId(1, 30), 1.7f).isOk());
  ASSERT_TRUE(doc.setVertexSharpness(VertexId(1, 33), 2.2f).isOk());
  if (n >= 2) ASSERT_TRUE(doc.setEdgeSharpness(EdgeId(2, 101), 0.6f).isOk());
}

// OpenSubdiv's refinement of the cage as the file states it, k levels.
std::vector<oracle::OsdDoublePoint> refineStated(const PolygonSoup& soup, int k) {
  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(soup.boundary == "edge-only" ? Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                                                               : Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  sdc.SetCreasingMethod(soup.creaseMethod == "chaikin" ? Sdc::Options::CREASE_CHAIKIN
                                                       : Sdc::Options::CREASE_UNIFORM);
  const Sdc::SchemeType type = soup.scheme == "loop" ? Sdc::SCHEME_LOOP : Sdc::SCHEME_CATMARK;
  std::vector<int> sizes, creasePairs, corners;
  std::vector<float> creaseWeights, cornerWeights;
  for (int f = 0; f < soup.numFaces(); ++f) sizes.push_back(soup.faceOffsets[f + 1] - soup.faceOffsets[f]);
  for (const SoupTag& t : soup.tags) {
    if (t.crease) {
      creasePairs.insert(creasePairs.end(), {t.v0, t.v1});
      creaseWeights.push_back(t.sharpness);
    } else {
      corners.push_back(t.v0);
      cornerWeights.push_back(t.sharpness);
    }
  }
  Far::TopologyDescriptor d;
  d.numVertices = static_cast<int>(soup.points.size());
  d.numFaces = soup.numFaces();
  d.numVertsPerFace = sizes.data();
  d.vertIndicesPerFace = soup.indices.data();
  d.numCreases = static_cast<int>(creaseWeights.size());
  d.creaseVertexIndexPairs = creasePairs.data();
  d.creaseWeights = creaseWeights.data();
  d.numCorners = static_cast<int>(cornerWeights.size());
  d.cornerVertexIndices = corners.data();
  d.cornerWeights = cornerWeights.data();
  std::unique_ptr<Far::TopologyRefiner> refiner(Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Create(
      d, Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Options(type, sdc)));
  if (!refiner) return {};
  refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(k));
  std::vector<oracle::OsdDoublePoint> base;
  for (const Vec3& p : soup.points) base.push_back({p[0], p[1], p[2]});
  return oracle::interpolateOsdDouble(*refiner, base, k);
}

struct Case {
  bool triangles;
  CreaseMethod method;
  int level, more;
};

void checkCase(const Case& c) {
  SCOPED_TRACE(std::string(c.triangles ? "loop" : "catmull-clark") +
               (c.method == CreaseMethod::kChaikin ? " chaikin" : " uniform") + ", cage at level " +
               std::to_string(c.level) + ", " + std::to_string(c.more) + " more");
  auto doc = documentOf(c.triangles, c.method, c.level + c.more);
  ASSERT_TRUE(doc.isOk()) << doc.status().toString();
  edit(*doc, c.level);
  auto cage = documentCage(*doc, c.level);
  ASSERT_TRUE(cage.isOk()) << cage.status().toString();
  const std::string dir = testing::makeTempDir("usda-cage");
  const std::string path = dir + "/cage.usda";
  ASSERT_TRUE(exportMesh(*cage, path).isOk());
  auto text = readFile(path);
  ASSERT_TRUE(text.isOk());
  auto soup = importPolygonSoup(*text, ".usda", path);
  ASSERT_TRUE(soup.isOk()) << soup.status().toString();
  std::filesystem::remove_all(dir);
  EXPECT_EQ(soup->scheme, c.triangles ? "loop" : "catmull-clark");
  EXPECT_EQ(soup->creaseMethod, c.method == CreaseMethod::kChaikin ? "chaikin" : "uniform");
  // Decayed semi-sharp values are in the file: some tag is neither 10 nor
  // one of the base's values.
  bool decayed = false;
  for (const SoupTag& t : soup->tags)
    decayed =
        decayed || (t.sharpness > 0 && t.sharpness < 10 && t.sharpness != 2.5f && t.sharpness != 1.25f &&
                    t.sharpness != 1.5f && t.sharpness != 1.7f && t.sharpness != 2.2f && t.sharpness != 0.6f);
  EXPECT_TRUE(decayed);

  const auto far = refineStated(*soup, c.more);
  auto eval = doc->evaluate(c.level + c.more);
  ASSERT_TRUE(eval.isOk());
  const std::vector<Vec3>& ours = (*eval)->points[c.level + c.more];
  ASSERT_EQ(far.size(), ours.size());
  std::set<size_t> matched;
  double worst = 0;
  for (const auto& p : far) {
    const Vec3 q(p.x, p.y, p.z);
    size_t best = 0;
    double bestDistance = HUGE_VAL;
    for (size_t v = 0; v < ours.size(); ++v) {
      const double d = (ours[v] - q).norm();
      if (d < bestDistance) bestDistance = d, best = v;
    }
    worst = std::max(worst, bestDistance);
    matched.insert(best);
  }
  EXPECT_LE(worst, 1e-9);
  EXPECT_EQ(matched.size(), far.size()) << "Far's points are not each a different one of ours";
}

TEST(UsdaCageOracle, OpenSubdivRefinesTheWrittenCageToTheDocumentsFinerLevels) {
  for (bool triangles : {true, false})
    for (CreaseMethod method : {CreaseMethod::kUniform, CreaseMethod::kChaikin})
      for (const auto& [level, more] : {std::pair{1, 1}, std::pair{1, 2}, std::pair{2, 1}})
        checkCase({triangles, method, level, more});
}

}  // namespace
}  // namespace tessera

// Subdivision tags in OBJ, in OpenSubdiv's dialect (docs/FORMATS.md "Tags in
// OBJ"; core/io/obj_off_reader.cc): `t crease`, `t corner`,
// `t interpolateboundary` and `t creasemethod` read into the polygon mesh
// and the triangle mesh alike, by the file's 0-based vertex numbers; every
// malformed or unsupported tag refused naming the file, the line and the tag.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <tuple>

#include "core/io/mesh_import.h"
#include "core/schemes/polygon_reader.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

const std::string kCube =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

std::string write(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(ObjTags, CreasesCornersAndOptionsAreReadIntoPolygonsAndTriangles) {
  const std::string dir = testing::makeTempDir("tessera-obj-tags");
  const std::string path = write(dir, "tagged.obj",
                                 kCube +
                                     "t crease 2/1/0 0 1 2.5\n"
                                     "t crease 4/2/0 4 5 5 6 1 inf\n"  // two pairs, one sharpness each
                                     "t corner 1/1/0 7 3\n"
                                     "t interpolateboundary 1/0/0 1\n"
                                     "t creasemethod 0/0/1 chaikin\n");
  auto polygons = schemes::importPolygonMesh(path, "");
  ASSERT_TRUE(polygons.isOk()) << polygons.status().toString();
  std::set<std::tuple<int, int, float>> creases;
  for (const auto& c : polygons->topology.creases)
    creases.insert({std::min(c.v0, c.v1), std::max(c.v0, c.v1), c.sharpness});
  EXPECT_EQ(creases, (std::set<std::tuple<int, int, float>>{{0, 1, 2.5f}, {4, 5, 1.0f}, {5, 6, INFINITY}}));
  ASSERT_EQ(polygons->topology.vertexSharpness.size(), 8u);
  EXPECT_EQ(polygons->topology.vertexSharpness[7], 3.0f);
  EXPECT_EQ(polygons->topology.vertexSharpness[0], 0.0f);
  EXPECT_EQ(polygons->boundary, "edge-and-corner");
  EXPECT_EQ(polygons->creaseMethod, "chaikin");

  // The triangle import (the quads triangulated) sets the same edges.
  auto triangles = importMeshWithReport(path, {.triangulate = true});
  ASSERT_TRUE(triangles.isOk()) << triangles.status().toString();
  EXPECT_EQ(triangles->report.tagsInFile, 4);
  EXPECT_EQ(triangles->report.boundary, "edge-and-corner");
  EXPECT_EQ(triangles->report.creaseMethod, "chaikin");
  const BaseMesh& mesh = triangles->mesh;
  const auto& m = mesh.mesh();
  auto edgeSharpness = [&](int a, int b) {
    return mesh.edgeSharpness(m.edge_handle(m.find_halfedge(m.vertex_handle(a), m.vertex_handle(b))));
  };
  EXPECT_EQ(edgeSharpness(0, 1), 2.5f);
  EXPECT_EQ(edgeSharpness(4, 5), 1.0f);
  EXPECT_GE(edgeSharpness(5, 6), 10.0f);  // infinitely sharp
  EXPECT_EQ(edgeSharpness(1, 2), 0.0f);
  EXPECT_EQ(mesh.vertexSharpness(m.vertex_handle(7)), 3.0f);
}

TEST(ObjTags, BadOrUnsupportedTagsAreRefusedNamingTheLineAndTheTag) {
  const std::string dir = testing::makeTempDir("tessera-obj-tags");
  struct Case {
    std::string line, expected;
  };
  // Line 15 is the tag (8 vertices and 6 faces before it).
  for (const Case& c : std::vector<Case>{
           {"t crease 2/1/0 0 1", "bad.obj:15: t crease: 3 values announced, 2 given"},
           {"t crease 3/1/0 0 1 2 1", "bad.obj:15: t crease: expected pairs of vertices"},
           {"t crease 2/1/0 0 -1 1", "bad.obj:15: t crease: integer 2 is not a vertex number: '-1'"},
           {"t crease 2/1/0 0 1 nan", "bad.obj:15: t crease: sharpness 1 is not a number >= 0: 'nan'"},
           {"t crease 2/1 0 1 1", "bad.obj:15: t crease: expected counts I/F/S, found '2/1'"},
           {"t corner 2/3/0 0 1 1 1 1", "bad.obj:15: t corner: expected vertices and 1 sharpness"},
           {"t hole 1/0/0 3", "bad.obj:15: t hole: this tag is not supported"},
           {"t interpolateboundary 1/0/0 0", "bad.obj:15: t interpolateboundary: 0: only 1"},
           {"t creasemethod 0/0/1 smooth",
            "bad.obj:15: t creasemethod: expected normal or chaikin, found 'smooth'"},
           {"t crease 2/1/0 0 6 1", "vertices 0 and 6 share no edge"},
           {"t corner 1/1/0 8 1", "vertex 8 does not exist"},
       }) {
    const std::string path = write(dir, "bad.obj", kCube + c.line + "\n");
    auto polygons = schemes::importPolygonMesh(path, "");
    ASSERT_FALSE(polygons.isOk()) << c.line;
    const std::string message = polygons.status().message();
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.line << ": " << message;
    EXPECT_NE(message.find(dir), std::string::npos) << "names the file: " << message;
    auto triangles = importMesh(path, {.triangulate = true});
    ASSERT_FALSE(triangles.isOk()) << c.line;
    EXPECT_NE(triangles.status().message().find("bad.obj:15: "), std::string::npos)
        << c.line << ": " << triangles.status().message();
  }
}

}  // namespace
}  // namespace tessera

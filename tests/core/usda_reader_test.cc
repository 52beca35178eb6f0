// USD's text format (docs/FORMATS.md "USD"; core/io/usda_parser.h,
// usda_reader.cc, usda_writer.h): a hand-written layer's Mesh prim read with
// its tags and options, the schema's fallbacks, the choice among several
// meshes, every refusal naming the line and column and the attribute, and
// read -> write -> read giving the same mesh, tags and scheme.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <tuple>

#include "core/io/mesh_export.h"
#include "core/io/mesh_import.h"
#include "core/util/file_io.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

// A cube of quads under an Xform, with what real layers carry besides the
// mesh: layer metadata, a doc string, comments of both kinds, an xform op,
// primvars, a relationship, attribute metadata.
const std::string kLayer = R"(#usda 1.0
(
    defaultPrim = "World"
    upAxis = "Y"
    doc = """A cube,
of quads"""
    customLayerData = {
        string creator = "hand"
    }
)

def Xform "World" (
    kind = "component"
)
{
    double3 xformOp:translate = (0, 1, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]

    def Mesh "Cube" (
        prepend apiSchemas = ["MaterialBindingAPI"]
    )
    {
        uniform bool doubleSided = 0
        float3[] extent = [(-1, -1, -1), (1, 1, 1)]
        int[] faceVertexCounts = [4, 4, 4, 4, 4, 4]
        int[] faceVertexIndices = [0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4,
            1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7]
        point3f[] points = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
            (-1, -1, 1), (1, -1, 1), (1, 1, 1), (0.1, 1e-1, 1.0000000000000002)]
        normal3f[] normals = [(0, 0, 1)] (
            interpolation = "constant"
        )
        uniform token subdivisionScheme = "loop"   # stated, and read as such
        token interpolateBoundary = "edgeOnly"
        custom uniform token tessera:creaseMethod = "chaikin"
        /* a chain of three edges with one sharpness, and one edge */
        int[] creaseIndices = [4, 5, 6, 7, 0, 1]
        int[] creaseLengths = [4, 2]
        float[] creaseSharpnesses = [2.5, 12]  // 12: infinitely sharp
        int[] cornerIndices = [3]
        float[] cornerSharpnesses = [1.5]
        int[] holeIndices = []
        texCoord2f[] primvars:st = [(0, 0), (1, 0)] (
            interpolation = "faceVarying"
        )
        int[] primvars:st:indices = [0, 1]
        rel material:binding = </World/Looks/Mat>
    }

    def Scope "Looks"
    {
        def Material "Mat"
        {
        }
    }
}
)";

Expected<PolygonSoup> read(const std::string& text, const std::string& prim = {}) {
  return importPolygonSoup(text, ".usda", "t.usda", prim);
}

using Tag = std::tuple<bool, int, int, float>;

// Tags as a set: an edge by its two vertices in either order.
std::set<Tag> tagsOf(const PolygonSoup& soup) {
  std::set<Tag> tags;
  for (const SoupTag& t : soup.tags)
    tags.insert(t.crease ? Tag{true, std::min(t.v0, t.v1), std::max(t.v0, t.v1), t.sharpness}
                         : Tag{false, t.v0, -1, t.sharpness});
  return tags;
}

TEST(UsdaReader, AMeshPrimWithItsTagsAndOptions) {
  auto soup = read(kLayer);
  ASSERT_TRUE(soup.isOk()) << soup.status().toString();
  ASSERT_EQ(soup->points.size(), 8u);
  EXPECT_EQ(soup->points[1], Vec3(1, -1, -1));
  // Every digit of the text is kept (as ASCII PLY's are): 1.0000000000000002
  // is the double after 1, which float could not hold.
  EXPECT_EQ(soup->points[7], Vec3(0.1, 0.1, 1.0000000000000002));
  EXPECT_EQ(soup->faceOffsets, (std::vector<int>{0, 4, 8, 12, 16, 20, 24}));
  EXPECT_EQ(soup->indices,
            (std::vector<int>{0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7}));
  EXPECT_EQ(soup->scheme, "loop");
  EXPECT_EQ(soup->boundary, "edge-only");
  EXPECT_EQ(soup->creaseMethod, "chaikin");
  // The chain 4-5-6-7 is three edges at 2.5; 12 is kept as written (10 and
  // more are infinitely sharp when applied, as for every tag source).
  EXPECT_EQ(tagsOf(*soup), (std::set<Tag>{{true, 4, 5, 2.5f},
                                          {true, 5, 6, 2.5f},
                                          {true, 6, 7, 2.5f},
                                          {true, 0, 1, 12.0f},
                                          {false, 3, -1, 1.5f}}));
}

TEST(UsdaReader, OneSharpnessPerEdgeAndTheSchemasFallbacks) {
  const std::string layer =
      "#usda 1.0\ndef Mesh \"Quad\" {\n"
      "  int[] faceVertexCounts = [4]\n  int[] faceVertexIndices = [0, 1, 2, 3]\n"
      "  point3f[] points = [(0,0,0), (1,0,0), (1,1,0), (0,1,0)]\n"
      "  int[] creaseIndices = [0, 1, 2]\n  int[] creaseLengths = [3]\n"
      "  float[] creaseSharpnesses = [1, 10]\n}\n";
  auto soup = read(layer);
  ASSERT_TRUE(soup.isOk()) << soup.status().toString();
  EXPECT_EQ(tagsOf(*soup), (std::set<Tag>{{true, 0, 1, 1.0f}, {true, 1, 2, 10.0f}}));
  // UsdGeomMesh's fallbacks: catmullClark, edgeAndCorner.
  EXPECT_EQ(soup->scheme, "catmull-clark");
  EXPECT_EQ(soup->boundary, "edge-and-corner");
  EXPECT_EQ(soup->creaseMethod, "");
  // Through the triangle import too, tags applied: 10 is infinitely sharp.
  auto mesh = importMeshFromBytes(layer, ".usda", "q.usda", {.triangulate = true});
  ASSERT_TRUE(mesh.isOk()) << mesh.status().toString();
}

TEST(UsdaReader, SeveralMeshesAreChosenByPathOrNameOrRefusedWithTheirNames) {
  const std::string two = kLayer +
                          "def Mesh \"Cube\" {\n  int[] faceVertexCounts = [3]\n"
                          "  int[] faceVertexIndices = [0, 1, 2]\n"
                          "  point3f[] points = [(0,0,0), (1,0,0), (0,1,0)]\n}\n";
  auto refused = read(two);
  ASSERT_FALSE(refused.isOk());
  EXPECT_EQ(refused.status().message(),
            "t.usda: 2 Mesh prims (/World/Cube, /Cube): name one (--usd-prim PATH)");
  auto ambiguous = read(two, "Cube");
  ASSERT_FALSE(ambiguous.isOk());
  EXPECT_NE(ambiguous.status().message().find("ambiguous"), std::string::npos);
  auto byPath = read(two, "/Cube");
  ASSERT_TRUE(byPath.isOk()) << byPath.status().toString();
  EXPECT_EQ(byPath->points.size(), 3u);
  auto nested = read(two, "/World/Cube");
  ASSERT_TRUE(nested.isOk());
  EXPECT_EQ(nested->points.size(), 8u);
  auto missing = read(two, "Sphere");
  ASSERT_FALSE(missing.isOk());
  EXPECT_EQ(missing.status().message(), "t.usda: no Mesh prim 'Sphere' (the layer has /World/Cube, /Cube)");
}

// kLayer with `from` replaced by `to` (the first occurrence).
std::string edited(const std::string& from, const std::string& to) {
  std::string text = kLayer;
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

void expectRefused(const std::string& text, ErrorCode code, const std::string& message) {
  auto soup = read(text);
  ASSERT_FALSE(soup.isOk()) << message;
  EXPECT_EQ(soup.status().code(), code) << soup.status().message();
  EXPECT_EQ(soup.status().message(), message);
}

TEST(UsdaReader, WhatTheSubsetDoesNotCoverIsRefusedByNameAtItsLineAndColumn) {
  const std::string subset = " (Tessera reads one layer's own meshes; docs/FORMATS.md \"USD\")";
  expectRefused(edited("    kind = \"component\"", "    prepend references = @cube.usda@"),
                ErrorCode::kUnsupported, "t.usda:13:13: 'references': references are not supported" + subset);
  expectRefused(edited("    kind = \"component\"", "    payload = @cube.usda@</Cube>"),
                ErrorCode::kUnsupported, "t.usda:13:5: 'payload': payloads are not supported" + subset);
  expectRefused(edited("    kind = \"component\"", "    inherits = </Base>"), ErrorCode::kUnsupported,
                "t.usda:13:5: 'inherits': inherits are not supported" + subset);
  expectRefused(edited("    kind = \"component\"", "    specializes = </Base>"), ErrorCode::kUnsupported,
                "t.usda:13:5: 'specializes': specializes are not supported" + subset);
  expectRefused(edited("    kind = \"component\"", "    variants = {\n string shape = \"a\"\n }"),
                ErrorCode::kUnsupported,
                "t.usda:13:5: 'variants': variants and variant sets are not supported" + subset);
  expectRefused(
      edited("    def Scope \"Looks\"", "    variantSet \"shape\" = {\n }\n    def Scope \"Looks\""),
      ErrorCode::kUnsupported,
      "t.usda:50:5: 'variantSet': variants and variant sets are not supported" + subset);
  expectRefused(edited("    upAxis = \"Y\"", "    subLayers = [@base.usda@]"), ErrorCode::kUnsupported,
                "t.usda:4:5: 'subLayers': sublayers are not supported" + subset);
  expectRefused(
      edited("def Xform \"World\"", "over \"World\""), ErrorCode::kUnsupported,
      "t.usda:12:1: 'over' prims are not supported: they compose over other prims (only 'def' is read; "
      "docs/FORMATS.md \"USD\")");
  expectRefused(
      edited("point3f[] points = [", "point3f[] points.timeSamples = {1: ["), ErrorCode::kUnsupported,
      "t.usda:28:26: attribute 'points': .timeSamples is not supported (Tessera reads default values "
      "only; docs/FORMATS.md \"USD\")");
  expectRefused(
      std::string("PXR-USDC\x00\x00\x00\x00", 12), ErrorCode::kUnsupported,
      "t.usda: a binary USD file (usdc, 'PXR-USDC'): Tessera reads the text format (usda); convert it "
      "with `usdcat -o mesh.usda`");
  expectRefused(
      edited("int[] holeIndices = []", "int[] holeIndices = [2]"), ErrorCode::kUnsupported,
      "t.usda:42:15: holeIndices: 1 holes: holes are not supported (a dropped hole would change the "
      "surface unsaid)");
  expectRefused(
      edited("\"edgeOnly\"", "\"none\""), ErrorCode::kUnsupported,
      "t.usda:34:15: interpolateBoundary: 'none' (edgeOnly and edgeAndCorner are supported; none, which "
      "leaves boundary faces out, is not)");
  expectRefused(
      edited("\"loop\"", "\"bicubic\""), ErrorCode::kUnsupported,
      "t.usda:33:23: subdivisionScheme: 'bicubic' (catmullClark, loop, bilinear and none are read)");
  expectRefused(edited("uniform bool doubleSided = 0", "uniform token orientation = \"leftHanded\""),
                ErrorCode::kUnsupported,
                "t.usda:23:23: orientation: 'leftHanded' is not supported (faces are read counter-clockwise: "
                "rightHanded)");
}

TEST(UsdaReader, MalformedValuesAreErrorsNamingTheAttributeAndElement) {
  expectRefused(edited("#usda 1.0", "#usda 2.0"), ErrorCode::kParseError,
                "t.usda:1: header: expected '#usda 1.0', found '#usda 2.0'");
  expectRefused(edited("int[] faceVertexCounts", "float[] faceVertexCounts"), ErrorCode::kParseError,
                "t.usda:25:17: attribute 'faceVertexCounts': type int[] expected, found float[]");
  expectRefused(edited("[4, 4, 4, 4, 4, 4]", "[4, 4, 4.5, 4, 4, 4]"), ErrorCode::kParseError,
                "t.usda:25:41: attribute 'faceVertexCounts'[2]: expected an integer, found '4.5'");
  expectRefused(edited("[4, 4, 4, 4, 4, 4]", "[4, 4, 2, 4, 4, 4]"), ErrorCode::kInvalidMesh,
                "t.usda:25:15: faceVertexCounts[2]: 2 corners, a face needs at least 3");
  expectRefused(edited("[0, 3, 2, 1,", "[0, 3, 20, 1,"), ErrorCode::kInvalidMesh,
                "t.usda:26:15: faceVertexIndices[2]: 20 names no point (8 points)");
  expectRefused(edited("[4, 4, 4, 4, 4, 4]", "[4, 4, 4, 4, 4]"), ErrorCode::kParseError,
                "t.usda:26:15: faceVertexIndices: 24 indices, faceVertexCounts uses 20");
  expectRefused(
      edited("[2.5, 12]", "[2.5]"), ErrorCode::kParseError,
      "t.usda:39:17: creaseSharpnesses: 1 values for 2 creases of 4 edges (one per crease, or one per "
      "edge)");
  expectRefused(edited("[2.5, 12]", "[2.5, -1]"), ErrorCode::kInvalidArgument,
                "t.usda:39:17: creaseSharpnesses[1]: sharpness must be a number >= 0");
  expectRefused(edited("[4, 5, 6, 7, 0, 1]", "[4, 5, 6, 7, 0, 11]"), ErrorCode::kInvalidMesh,
                "t.usda:37:15: creaseIndices[5]: 11 names no point (8 points)");
  expectRefused(edited("[1.5]", "[1.5, 2]"), ErrorCode::kParseError,
                "t.usda:41:17: cornerSharpnesses: 2 values for 1 cornerIndices");
  expectRefused(edited("(1, -1, -1), (1, 1, -1)", "(1, -1, -1), (1, nan, -1)"), ErrorCode::kInvalidMesh,
                "t.usda:28:60: attribute 'points'[2]: coordinate nan is not finite or outside float range");
  expectRefused(edited("(1, -1, -1), (1, 1, -1)", "(1, -1, -1), (1, 1)"), ErrorCode::kParseError,
                "t.usda:28:61: expected ',', found ')'");
  expectRefused(kLayer.substr(0, kLayer.find("int[] holeIndices")), ErrorCode::kParseError,
                "t.usda:42:9: expected a property of prim /World/Cube, found the end of the file");
  expectRefused(edited("string creator = \"hand\"", "string creator = \"hand"), ErrorCode::kParseError,
                "t.usda:8:26: a string is never closed");
  expectRefused("#usda 1.0\ndef Xform \"W\" {\n}\n", ErrorCode::kNotFound,
                "t.usda: no Mesh prim in the layer");
  expectRefused("#usda 1.0\ndef Mesh \"M\" {\n  int[] faceVertexCounts = [3]\n}\n", ErrorCode::kParseError,
                "t.usda: Mesh /M: no points");
}

// Nesting is bounded (the parser recurses per prim): 256 levels of prims
// are read, the 257th is refused at its line.
TEST(UsdaReader, PrimsNestDeepButNotWithoutBound) {
  auto nested = [](int depth) {
    std::string text = "#usda 1.0\n";
    for (int d = 0; d < depth - 1; ++d) text += "def Xform \"X\" {\n";
    text +=
        "def Mesh \"M\" {\n int[] faceVertexCounts = [3]\n int[] faceVertexIndices = [0, 1, 2]\n"
        " point3f[] points = [(0,0,0), (1,0,0), (0,1,0)]\n}\n";
    for (int d = 0; d < depth - 1; ++d) text += "}\n";
    return text;
  };
  auto deep = read(nested(256));
  ASSERT_TRUE(deep.isOk()) << deep.status().toString();
  EXPECT_EQ(deep->points.size(), 3u);
  expectRefused(nested(257), ErrorCode::kUnsupported, "t.usda:258:1: prims nested deeper than 256");
}

// Read, write, read: the same points (every bit), faces, tags, scheme,
// boundary rule and crease method.
TEST(UsdaReader, ReadWriteReadGivesTheSameMeshTagsAndScheme) {
  auto first = read(kLayer);
  ASSERT_TRUE(first.isOk()) << first.status().toString();
  SurfaceMesh surface;
  surface.positions = first->points;
  for (int f = 0; f < first->numFaces(); ++f)
    surface.addPolygon(
        std::span<const int>(first->indices.data() + first->faceOffsets[f],
                             static_cast<size_t>(first->faceOffsets[f + 1] - first->faceOffsets[f])));
  for (const SoupTag& t : first->tags) {
    if (t.crease) {
      surface.creases.push_back({t.v0, t.v1, t.sharpness});
    } else {
      surface.corners.push_back({t.v0, t.sharpness});
    }
  }
  surface.scheme = first->scheme;
  surface.boundary = first->boundary;
  surface.creaseMethod = first->creaseMethod;
  const std::string dir = testing::makeTempDir("usda-round-trip");
  const std::string path = dir + "/cube.usda";
  ASSERT_TRUE(exportMesh(surface, path).isOk());
  auto text = readFile(path);
  ASSERT_TRUE(text.isOk());
  std::filesystem::remove_all(dir);
  auto second = read(*text);
  ASSERT_TRUE(second.isOk()) << second.status().toString() << "\n" << *text;
  EXPECT_EQ(second->points, first->points);
  EXPECT_EQ(second->faceOffsets, first->faceOffsets);
  EXPECT_EQ(second->indices, first->indices);
  EXPECT_EQ(tagsOf(*second), tagsOf(*first));
  EXPECT_EQ(second->scheme, "loop");
  EXPECT_EQ(second->boundary, "edge-only");
  EXPECT_EQ(second->creaseMethod, "chaikin");
}

TEST(UsdaReader, ALimitSurfaceIsWrittenAsAPolygonMeshWithVertexNormals) {
  SurfaceMesh surface;
  surface.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  surface.normals.assign(4, Vec3(0, 0, 1));
  const int quad[] = {0, 1, 2, 3};
  surface.addPolygon(quad);
  const std::string dir = testing::makeTempDir("usda-limit");
  const std::string path = dir + "/limit.usda";
  ASSERT_TRUE(exportMesh(surface, path).isOk());
  auto text = readFile(path);
  ASSERT_TRUE(text.isOk());
  std::filesystem::remove_all(dir);
  EXPECT_NE(text->find("uniform token subdivisionScheme = \"none\""), std::string::npos) << *text;
  EXPECT_NE(text->find("normal3f[] normals = [(0, 0, 1), (0, 0, 1), (0, 0, 1), (0, 0, 1)] (\n        "
                       "interpolation = \"vertex\"\n    )"),
            std::string::npos)
      << *text;
  EXPECT_EQ(text->find("interpolateBoundary"), std::string::npos);
  auto back = read(*text);
  ASSERT_TRUE(back.isOk()) << back.status().toString();
  EXPECT_EQ(back->scheme, "none");
  EXPECT_EQ(back->boundary, "");
  EXPECT_EQ(back->points, surface.positions);
  EXPECT_TRUE(back->tags.empty());
}

}  // namespace
}  // namespace tessera

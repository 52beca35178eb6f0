#include "core/io/usda_writer.h"

#include <span>

namespace tessera::io_detail {
namespace {

// "[a, b, c]" with a line break every few values, so that a large array
// stays readable in an editor.
template <typename T, typename Append>
void appendArray(FileWriter& out, std::span<const T> values, Append&& appendOne) {
  out.append('[');
  for (size_t k = 0; k < values.size(); ++k) {
    if (k > 0) out.append(k % 8 == 0 ? ",\n        " : ", ");
    appendOne(values[k]);
  }
  out.append(']');
}

void appendInts(FileWriter& out, const char* declaration, std::span<const int> values) {
  out.append("    ");
  out.append(declaration);
  out.append(" = ");
  appendArray(out, values, [&out](int v) { out.appendNumber(static_cast<long long>(v)); });
  out.append('\n');
}

void appendFloats(FileWriter& out, const char* declaration, std::span<const float> values) {
  out.append("    ");
  out.append(declaration);
  out.append(" = ");
  appendArray(out, values, [&out](float v) { out.appendNumber(static_cast<double>(v)); });
  out.append('\n');
}

void appendVectors(FileWriter& out, const char* declaration, std::span<const Vec3> values) {
  out.append("    ");
  out.append(declaration);
  out.append(" = ");
  appendArray(out, values, [&out](const Vec3& v) {
    out.append('(');
    for (int k = 0; k < 3; ++k) {
      if (k > 0) out.append(", ");
      out.appendNumber(v[k]);
    }
    out.append(')');
  });
}

const char* usdScheme(const std::string& scheme) {
  if (scheme == "loop") return "loop";
  if (scheme == "bilinear") return "bilinear";
  if (scheme == "catmull-clark") return "catmullClark";
  return "none";
}

}  // namespace

void writeUsda(const SurfaceMesh& surface, FileWriter& out) {
  out.append(
      "#usda 1.0\n(\n    defaultPrim = \"Surface\"\n    doc = \"Tessera surface export (docs/FORMATS.md, "
      "USD)\"\n)\n\n"
      "def Mesh \"Surface\"\n{\n");
  const bool cage = !surface.scheme.empty() && surface.scheme != "none";
  out.append("    uniform token subdivisionScheme = \"");
  out.append(cage ? usdScheme(surface.scheme) : "none");
  out.append("\"\n");
  if (cage) {
    out.append("    token interpolateBoundary = \"");
    out.append(surface.boundary == "edge-and-corner" ? "edgeAndCorner" : "edgeOnly");
    out.append("\"\n");
    if (!surface.creaseMethod.empty()) {
      out.append("    custom uniform token tessera:creaseMethod = \"");
      out.append(surface.creaseMethod == "chaikin" ? "chaikin" : "uniform");
      out.append("\"\n");
    }
  }
  std::vector<int> counts, indices;
  if (surface.polygonOffsets.empty()) {
    counts.assign(surface.triangles.size(), 3);
    for (const auto& t : surface.triangles) indices.insert(indices.end(), t.begin(), t.end());
  } else {
    for (size_t f = 0; f + 1 < surface.polygonOffsets.size(); ++f)
      counts.push_back(surface.polygonOffsets[f + 1] - surface.polygonOffsets[f]);
    indices = surface.polygonCorners;
  }
  appendInts(out, "int[] faceVertexCounts", counts);
  appendInts(out, "int[] faceVertexIndices", indices);
  appendVectors(out, "point3f[] points", surface.positions);
  out.append('\n');
  if (!surface.normals.empty()) {
    appendVectors(out, "normal3f[] normals", surface.normals);
    out.append(" (\n        interpolation = \"vertex\"\n    )\n");
  }
  if (cage && !surface.creases.empty()) {
    std::vector<int> creaseIndices, creaseLengths(surface.creases.size(), 2);
    std::vector<float> creaseSharpnesses;
    for (const SurfaceMesh::Crease& c : surface.creases) {
      creaseIndices.push_back(c.v0);
      creaseIndices.push_back(c.v1);
      creaseSharpnesses.push_back(c.sharpness);
    }
    appendInts(out, "int[] creaseIndices", creaseIndices);
    appendInts(out, "int[] creaseLengths", creaseLengths);
    appendFloats(out, "float[] creaseSharpnesses", creaseSharpnesses);
  }
  if (cage && !surface.corners.empty()) {
    std::vector<int> cornerIndices;
    std::vector<float> cornerSharpnesses;
    for (const SurfaceMesh::Corner& c : surface.corners) {
      cornerIndices.push_back(c.v);
      cornerSharpnesses.push_back(c.sharpness);
    }
    appendInts(out, "int[] cornerIndices", cornerIndices);
    appendFloats(out, "float[] cornerSharpnesses", cornerSharpnesses);
  }
  out.append("}\n");
}

}  // namespace tessera::io_detail

#include "core/io/mesh_writers.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>

#include <nlohmann/json.hpp>

#include "core/io/export_common.h"

namespace tessera::io_detail {
namespace {

void appendTriple(FileWriter& out, const char* tag, const Vec3& v) {
  out.append(tag);
  for (int k = 0; k < 3; ++k) {
    out.append(' ');
    out.appendNumber(v[k]);
  }
  out.append('\n');
}

void appendFloat3(FileWriter& out, const std::array<float, 3>& v) {
  for (float c : v) out.appendBytes(c);
}

// The faces the polygon formats (OBJ, OFF, PLY) write: the surface's
// polygons where it has them, its triangles otherwise.
size_t numFaces(const SurfaceMesh& s) {
  return s.polygonOffsets.empty() ? s.triangles.size() : s.numPolygons();
}

template <typename Visit>
void forEachFace(const SurfaceMesh& s, Visit&& visit) {
  if (s.polygonOffsets.empty()) {
    for (const auto& t : s.triangles) visit(std::span<const int>(t.data(), 3));
    return;
  }
  for (size_t f = 0; f + 1 < s.polygonOffsets.size(); ++f)
    visit(std::span<const int>(s.polygonCorners.data() + s.polygonOffsets[f],
                               static_cast<size_t>(s.polygonOffsets[f + 1] - s.polygonOffsets[f])));
}

}  // namespace

void writeObj(const SurfaceMesh& surface, FileWriter& out) {
  out.append("# Tessera surface export\n");
  for (const Vec3& p : surface.positions) appendTriple(out, "v", p);
  for (const Vec3& n : surface.normals) appendTriple(out, "vn", n);
  const bool withNormals = !surface.normals.empty();
  forEachFace(surface, [&](std::span<const int> face) {
    out.append('f');
    for (int v : face) {
      // OBJ indices are 1-based; `a//a` names position a and normal a.
      out.append(' ');
      out.appendNumber(static_cast<long long>(v) + 1);
      if (withNormals) {
        out.append("//");
        out.appendNumber(static_cast<long long>(v) + 1);
      }
    }
    out.append('\n');
  });
  // A cage's tags in OpenSubdiv's dialect (docs/FORMATS.md "Tags in OBJ"):
  // `t NAME I/F/S` and the values, vertices 0-based.
  if (!surface.boundary.empty())
    out.append(surface.boundary == "edge-and-corner" ? "t interpolateboundary 1/0/0 1\n"
                                                     : "t interpolateboundary 1/0/0 2\n");
  if (!surface.creaseMethod.empty())
    out.append(surface.creaseMethod == "chaikin" ? "t creasemethod 0/0/1 chaikin\n"
                                                 : "t creasemethod 0/0/1 normal\n");
  for (const SurfaceMesh::Crease& c : surface.creases) {
    out.append("t crease 2/1/0 ");
    out.appendNumber(static_cast<long long>(c.v0));
    out.append(' ');
    out.appendNumber(static_cast<long long>(c.v1));
    out.append(' ');
    out.appendNumber(static_cast<double>(c.sharpness));
    out.append('\n');
  }
  for (const SurfaceMesh::Corner& c : surface.corners) {
    out.append("t corner 1/1/0 ");
    out.appendNumber(static_cast<long long>(c.v));
    out.append(' ');
    out.appendNumber(static_cast<double>(c.sharpness));
    out.append('\n');
  }
}

void writeOff(const SurfaceMesh& surface, FileWriter& out) {
  out.append("OFF\n");
  out.appendNumber(static_cast<long long>(surface.positions.size()));
  out.append(' ');
  out.appendNumber(static_cast<long long>(numFaces(surface)));
  out.append(" 0\n");
  for (const Vec3& p : surface.positions) {
    out.appendNumber(p[0]);
    out.append(' ');
    out.appendNumber(p[1]);
    out.append(' ');
    out.appendNumber(p[2]);
    out.append('\n');
  }
  forEachFace(surface, [&](std::span<const int> face) {
    out.appendNumber(static_cast<long long>(face.size()));
    for (int v : face) {
      out.append(' ');
      out.appendNumber(static_cast<long long>(v));
    }
    out.append('\n');
  });
}

void writePly(const SurfaceMesh& surface, FileWriter& out) {
  const bool withNormals = !surface.normals.empty();
  out.append("ply\nformat binary_little_endian 1.0\ncomment Tessera surface export\n");
  out.append("element vertex " + std::to_string(surface.positions.size()) + "\n");
  out.append("property float x\nproperty float y\nproperty float z\n");
  if (withNormals) out.append("property float nx\nproperty float ny\nproperty float nz\n");
  out.append("element face " + std::to_string(numFaces(surface)) + "\n");
  out.append("property list uchar int vertex_indices\nend_header\n");
  for (std::size_t i = 0; i < surface.positions.size(); ++i) {
    appendFloat3(out, toFloat3(surface.positions[i]));
    if (withNormals) appendFloat3(out, toFloat3(surface.normals[i]));
  }
  forEachFace(surface, [&](std::span<const int> face) {
    out.append(static_cast<char>(face.size()));  // at most 255 (validateSurfaceMesh)
    for (int v : face) out.appendBytes(static_cast<std::int32_t>(v));
  });
}

void writeStl(const SurfaceMesh& surface, FileWriter& out) {
  std::string header = "Tessera surface export";
  header.resize(80, ' ');
  out.append(header);
  out.appendBytes(static_cast<std::uint32_t>(surface.triangles.size()));
  for (const auto& t : surface.triangles) {
    const Vec3& a = surface.positions[t[0]];
    const Vec3 n = ((surface.positions[t[1]] - a) % (surface.positions[t[2]] - a)).normalized();
    appendFloat3(out, toFloat3(n));  // the facet's own normal: STL has no vertex normals
    for (int v : t) appendFloat3(out, toFloat3(surface.positions[v]));
    out.appendBytes(static_cast<std::uint16_t>(0));
  }
}

void writePlainGlb(const SurfaceMesh& surface, FileWriter& out) {
  const std::size_t n = surface.positions.size();
  const bool withNormals = !surface.normals.empty();
  // glTF 2.0, 3.7.2.1: an index must not be the largest value of its type.
  const bool shortIndices = n <= std::numeric_limits<std::uint16_t>::max();
  std::array<float, 3> lo, hi;
  lo.fill(std::numeric_limits<float>::max());
  hi.fill(std::numeric_limits<float>::lowest());
  for (const Vec3& p : surface.positions) {
    const std::array<float, 3> f = toFloat3(p);
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], f[k]), hi[k] = std::max(hi[k], f[k]);
  }
  const std::size_t vertexBytes = n * 12;
  const std::size_t indexBytes = surface.triangles.size() * 3 * (shortIndices ? 2 : 4);
  const std::size_t indexOffset = vertexBytes * (withNormals ? 2 : 1);
  const std::size_t binBytes = (indexOffset + indexBytes + 3) & ~std::size_t{3};

  using nlohmann::json;
  json views =
      json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", vertexBytes}, {"target", 34962}}});
  json accessors = json::array({{{"bufferView", 0},
                                 {"componentType", 5126},
                                 {"count", n},
                                 {"type", "VEC3"},
                                 {"min", {lo[0], lo[1], lo[2]}},
                                 {"max", {hi[0], hi[1], hi[2]}}}});
  json attributes = {{"POSITION", 0}};
  if (withNormals) {
    views.push_back(
        {{"buffer", 0}, {"byteOffset", vertexBytes}, {"byteLength", vertexBytes}, {"target", 34962}});
    accessors.push_back({{"bufferView", 1}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}});
    attributes["NORMAL"] = 1;
  }
  const int indexView = withNormals ? 2 : 1;
  views.push_back(
      {{"buffer", 0}, {"byteOffset", indexOffset}, {"byteLength", indexBytes}, {"target", 34963}});
  accessors.push_back({{"bufferView", indexView},
                       {"componentType", shortIndices ? 5123 : 5125},
                       {"count", surface.triangles.size() * 3},
                       {"type", "SCALAR"}});
  const json gltf = {
      {"asset", {{"version", "2.0"}, {"generator", "Tessera"}}},
      {"buffers", json::array({{{"byteLength", binBytes}}})},
      {"bufferViews", views},
      {"accessors", accessors},
      {"meshes",
       json::array({{{"primitives",
                      json::array({{{"attributes", attributes}, {"indices", indexView}, {"mode", 4}}})}}})},
      {"nodes", json::array({{{"mesh", 0}}})},
      {"scenes", json::array({{{"nodes", {0}}}})},
      {"scene", 0}};
  std::string text = gltf.dump();
  text.resize((text.size() + 3) & ~std::size_t{3}, ' ');  // the JSON chunk is padded with spaces

  // GLB: header, JSON chunk, BIN chunk (glTF 2.0, 4.4).
  out.appendBytes(std::uint32_t{0x46546C67});  // "glTF"
  out.appendBytes(std::uint32_t{2});
  out.appendBytes(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + binBytes));
  out.appendBytes(static_cast<std::uint32_t>(text.size()));
  out.appendBytes(std::uint32_t{0x4E4F534A});  // "JSON"
  out.append(text);
  out.appendBytes(static_cast<std::uint32_t>(binBytes));
  out.appendBytes(std::uint32_t{0x004E4942});  // "BIN\0"
  for (const Vec3& p : surface.positions) appendFloat3(out, toFloat3(p));
  if (withNormals) {
    for (const Vec3& v : surface.normals) appendFloat3(out, unitFloat3(v));
  }
  for (const auto& t : surface.triangles) {
    for (int v : t) {
      if (shortIndices)
        out.appendBytes(static_cast<std::uint16_t>(v));
      else
        out.appendBytes(static_cast<std::uint32_t>(v));
    }
  }
  for (std::size_t pad = indexOffset + indexBytes; pad < binBytes; ++pad) out.append('\0');
}

}  // namespace tessera::io_detail

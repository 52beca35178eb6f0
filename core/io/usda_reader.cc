// A usda Mesh prim into a PolygonSoup, by the UsdGeomMesh schema's
// definitions ("Subdivision Surfaces" and "Creases and corners" in the
// UsdGeomMesh documentation): unauthored attributes take the schema's
// fallbacks (catmullClark, edgeAndCorner, rightHanded), a crease is a chain
// of creaseLengths[i] vertices with one sharpness per chain or per edge,
// and a sharpness of 10 or more is infinitely sharp, as OpenSubdiv's
// Sdc::Crease::SHARPNESS_INFINITE and Tessera's kSharpnessInfinite.
#include <algorithm>
#include <cmath>

#include "core/io/text_mesh_readers.h"
#include "core/io/text_scan.h"
#include "core/io/usda_parser.h"

namespace tessera::io_detail {
namespace {

std::string where(const std::string& src, const UsdaToken& t, const std::string& element) {
  return src + ":" + std::to_string(t.line) + ":" + std::to_string(t.column) + ": " + element + ": ";
}

std::string indexed(const char* name, size_t index) {
  return std::string(name) + "[" + std::to_string(index) + "]";
}

Expected<const UsdaMeshPrim*> chooseMesh(const std::vector<UsdaMeshPrim>& meshes, const std::string& src,
                                         const std::string& wanted) {
  std::string list;
  for (const UsdaMeshPrim& m : meshes) list += (list.empty() ? "" : ", ") + m.path;
  if (meshes.empty()) return notFound(src + ": no Mesh prim in the layer");
  if (wanted.empty()) {
    if (meshes.size() == 1) return &meshes[0];
    return invalidArgument(src + ": " + std::to_string(meshes.size()) + " Mesh prims (" + list +
                           "): name one (--usd-prim PATH)");
  }
  const UsdaMeshPrim* found = nullptr;
  for (const UsdaMeshPrim& m : meshes) {
    const std::string name = m.path.substr(m.path.rfind('/') + 1);
    if (m.path == wanted) return &m;
    if (name == wanted) {
      if (found != nullptr)
        return invalidArgument(src + ": Mesh prim name '" + wanted + "' is ambiguous (" + list +
                               "): give its path");
      found = &m;
    }
  }
  if (found == nullptr) return notFound(src + ": no Mesh prim '" + wanted + "' (the layer has " + list + ")");
  return found;
}

Status checkIndex(int v, size_t points, const std::string& src, const UsdaToken& t,
                  const std::string& element) {
  if (v < 0 || static_cast<size_t>(v) >= points)
    return invalidMesh(where(src, t, element) + std::to_string(v) + " names no point (" +
                       std::to_string(points) + " points)");
  return Status::ok();
}

Status checkSharpness(double s, const std::string& src, const UsdaToken& t, const std::string& element) {
  if (!(s >= 0)) return invalidArgument(where(src, t, element) + "sharpness must be a number >= 0");
  return Status::ok();
}

Status readFaces(const UsdaMeshPrim& m, const std::string& src, PolygonSoup& soup) {
  const std::string mesh = src + ": Mesh " + m.path;
  if (!m.points.authored) return parseError(mesh + ": no points");
  if (!m.faceVertexCounts.authored) return parseError(mesh + ": no faceVertexCounts");
  if (!m.faceVertexIndices.authored) return parseError(mesh + ": no faceVertexIndices");
  soup.points = m.points.value;
  const std::vector<int>& counts = m.faceVertexCounts.value;
  const std::vector<int>& indices = m.faceVertexIndices.value;
  size_t at = 0;
  std::vector<int> face;
  for (size_t f = 0; f < counts.size(); ++f) {
    const std::string element = indexed("faceVertexCounts", f);
    if (counts[f] < 3)
      return invalidMesh(where(src, m.faceVertexCounts.where, element) + std::to_string(counts[f]) +
                         " corners, a face needs at least 3");
    if (indices.size() - at < static_cast<size_t>(counts[f]))
      return parseError(where(src, m.faceVertexIndices.where, "faceVertexIndices") +
                        std::to_string(indices.size()) +
                        " indices, fewer than faceVertexCounts asks for (face " + std::to_string(f) + ")");
    face.assign(indices.begin() + static_cast<long>(at), indices.begin() + static_cast<long>(at) + counts[f]);
    for (size_t k = 0; k < face.size(); ++k)
      TESSERA_RETURN_IF_ERROR(checkIndex(face[k], soup.points.size(), src, m.faceVertexIndices.where,
                                         indexed("faceVertexIndices", at + k)));
    soup.addFace(face);
    at += static_cast<size_t>(counts[f]);
  }
  if (at != indices.size())
    return parseError(where(src, m.faceVertexIndices.where, "faceVertexIndices") +
                      std::to_string(indices.size()) + " indices, faceVertexCounts uses " +
                      std::to_string(at));
  return Status::ok();
}

Status readCreases(const UsdaMeshPrim& m, const std::string& src, PolygonSoup& soup) {
  const auto& indices = m.creaseIndices.value;
  const auto& lengths = m.creaseLengths.value;
  const auto& sharpness = m.creaseSharpnesses.value;
  if (!m.creaseIndices.authored && !m.creaseLengths.authored && !m.creaseSharpnesses.authored)
    return Status::ok();
  const UsdaToken& t = m.creaseLengths.authored ? m.creaseLengths.where : m.creaseIndices.where;
  size_t sum = 0, edges = 0;
  for (size_t c = 0; c < lengths.size(); ++c) {
    if (lengths[c] < 2)
      return invalidMesh(where(src, m.creaseLengths.where, indexed("creaseLengths", c)) +
                         std::to_string(lengths[c]) + " vertices, a crease needs at least 2");
    sum += static_cast<size_t>(lengths[c]);
    edges += static_cast<size_t>(lengths[c]) - 1;
  }
  if (sum != indices.size())
    return parseError(where(src, t, "creaseIndices") + std::to_string(indices.size()) +
                      " indices, creaseLengths adds up to " + std::to_string(sum));
  // One sharpness per crease, or one per edge of every crease.
  const bool perEdge = sharpness.size() == edges && sharpness.size() != lengths.size();
  if (sharpness.size() != lengths.size() && !perEdge)
    return parseError(
        where(src, m.creaseSharpnesses.authored ? m.creaseSharpnesses.where : t, "creaseSharpnesses") +
        std::to_string(sharpness.size()) + " values for " + std::to_string(lengths.size()) + " creases of " +
        std::to_string(edges) + " edges (one per crease, or one per edge)");
  size_t at = 0, edge = 0;
  for (size_t c = 0; c < lengths.size(); ++c) {
    for (int k = 0; k < lengths[c]; ++k)
      TESSERA_RETURN_IF_ERROR(checkIndex(indices[at + k], soup.points.size(), src, m.creaseIndices.where,
                                         indexed("creaseIndices", at + k)));
    for (int k = 0; k + 1 < lengths[c]; ++k, ++edge) {
      const size_t s = perEdge ? edge : c;
      TESSERA_RETURN_IF_ERROR(
          checkSharpness(sharpness[s], src, m.creaseSharpnesses.where, indexed("creaseSharpnesses", s)));
      soup.tags.push_back({true, indices[at + k], indices[at + k + 1], static_cast<float>(sharpness[s]),
                           m.creaseIndices.where.line});
    }
    at += static_cast<size_t>(lengths[c]);
  }
  return Status::ok();
}

Status readCorners(const UsdaMeshPrim& m, const std::string& src, PolygonSoup& soup) {
  const auto& indices = m.cornerIndices.value;
  const auto& sharpness = m.cornerSharpnesses.value;
  if (indices.size() != sharpness.size())
    return parseError(where(src,
                            m.cornerSharpnesses.authored ? m.cornerSharpnesses.where : m.cornerIndices.where,
                            "cornerSharpnesses") +
                      std::to_string(sharpness.size()) + " values for " + std::to_string(indices.size()) +
                      " cornerIndices");
  for (size_t k = 0; k < indices.size(); ++k) {
    TESSERA_RETURN_IF_ERROR(
        checkIndex(indices[k], soup.points.size(), src, m.cornerIndices.where, indexed("cornerIndices", k)));
    TESSERA_RETURN_IF_ERROR(
        checkSharpness(sharpness[k], src, m.cornerSharpnesses.where, indexed("cornerSharpnesses", k)));
    soup.tags.push_back(
        {false, indices[k], -1, static_cast<float>(sharpness[k]), m.cornerIndices.where.line});
  }
  return Status::ok();
}

// The schema's tokens, named as Tessera's command line names them.
Status readOptions(const UsdaMeshPrim& m, const std::string& src, PolygonSoup& soup) {
  const std::string scheme = m.subdivisionScheme.authored ? m.subdivisionScheme.value : "catmullClark";
  if (scheme == "catmullClark") {
    soup.scheme = "catmull-clark";
  } else if (scheme == "loop" || scheme == "bilinear" || scheme == "none") {
    soup.scheme = scheme;
  } else {
    return unsupported(where(src, m.subdivisionScheme.where, "subdivisionScheme") + "'" + scheme +
                       "' (catmullClark, loop, bilinear and none are read)");
  }
  const bool subdivided = soup.scheme != "none";
  if (m.interpolateBoundary.authored || subdivided) {
    const std::string rule = m.interpolateBoundary.authored ? m.interpolateBoundary.value : "edgeAndCorner";
    if (rule == "edgeAndCorner") {
      soup.boundary = "edge-and-corner";
    } else if (rule == "edgeOnly") {
      soup.boundary = "edge-only";
    } else {
      return unsupported(where(src, m.interpolateBoundary.where, "interpolateBoundary") + "'" + rule +
                         "' (edgeOnly and edgeAndCorner are supported; none, which leaves boundary faces "
                         "out, is not)");
    }
  }
  if (m.creaseMethod.authored) {
    if (m.creaseMethod.value != "uniform" && m.creaseMethod.value != "chaikin")
      return parseError(where(src, m.creaseMethod.where, "tessera:creaseMethod") + "'" +
                        m.creaseMethod.value + "' (uniform or chaikin)");
    soup.creaseMethod = m.creaseMethod.value;
  }
  if (m.orientation.authored && m.orientation.value != "rightHanded")
    return unsupported(where(src, m.orientation.where, "orientation") + "'" + m.orientation.value +
                       "' is not supported (faces are read counter-clockwise: rightHanded)");
  if (m.triangleSubdivisionRule.authored && m.triangleSubdivisionRule.value != "catmullClark")
    return unsupported(where(src, m.triangleSubdivisionRule.where, "triangleSubdivisionRule") + "'" +
                       m.triangleSubdivisionRule.value + "' is not supported (catmullClark is)");
  if (!m.holeIndices.value.empty())
    return unsupported(where(src, m.holeIndices.where, "holeIndices") +
                       std::to_string(m.holeIndices.value.size()) +
                       " holes: holes are not supported (a dropped hole would change the surface unsaid)");
  return Status::ok();
}

}  // namespace

Status readUsda(std::string_view text, const std::string& src, PolygonSoup& soup,
                const TextReadOptions& options) {
  TESSERA_ASSIGN_OR_RETURN(const std::vector<UsdaMeshPrim> meshes, parseUsdaMeshes(text, src));
  TESSERA_ASSIGN_OR_RETURN(const UsdaMeshPrim* mesh, chooseMesh(meshes, src, options.usdPrim));
  TESSERA_RETURN_IF_ERROR(readOptions(*mesh, src, soup));
  TESSERA_RETURN_IF_ERROR(readFaces(*mesh, src, soup));
  TESSERA_RETURN_IF_ERROR(readCreases(*mesh, src, soup));
  return readCorners(*mesh, src, soup);
}

}  // namespace tessera::io_detail

#include "client/python/offline_work.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <span>
#include <utility>
#include <vector>

#include "core/mesh/sharpness.h"
#include "core/util/file_io.h"

namespace tessera::python {

namespace {

ImportOptions importOptions(const ImportArgs& a) {
  return {
      .triangulate = a.triangulate, .dropUnused = a.dropUnused, .creaseAngle = a.creaseAngle.value_or(-1)};
}

Expected<BaseMesh> withTags(Expected<ImportedMesh> imported, const ImportArgs& args) {
  if (!imported.isOk()) return imported.status();
  if (args.tags)
    TESSERA_RETURN_IF_ERROR(applyTagFile(*args.tags, imported->mesh, imported->report.renumbering));
  return std::move(imported->mesh);
}

}  // namespace

Expected<BaseMesh> baseMeshFromFile(const std::string& path, const ImportArgs& args) {
  return withTags(importMeshWithReport(path, importOptions(args)), args);
}

Expected<BaseMesh> baseMeshFromArrays(PolygonSoup soup, const ImportArgs& args) {
  return withTags(importSoupWithReport(std::move(soup), "arrays", importOptions(args)), args);
}

Expected<BaseMesh> baseMeshOf(SchemeSource source, const ImportArgs& args) {
  if (source.path) return baseMeshFromFile(*source.path, args);
  return baseMeshFromArrays(std::move(source.soup), args);
}

Expected<LoopOptions> loopOptionsNamed(const std::string& creaseMethod, const std::string& boundary) {
  LoopOptions o;
  if (creaseMethod == "chaikin")
    o.creaseMethod = CreaseMethod::kChaikin;
  else if (creaseMethod != "uniform")
    return invalidArgument("crease_method must be 'uniform' or 'chaikin'");
  if (boundary == "edge-and-corner")
    o.boundary = BoundaryInterpolation::kEdgeAndCorner;
  else if (boundary != "edge-only")
    return invalidArgument("boundary must be 'edge-only' or 'edge-and-corner'");
  return o;
}

Expected<SurfaceMesh> refineLoop(const BaseMesh& mesh, const LoopOptions& options, int level, bool limit) {
  if (level < 0) return invalidArgument("level must be 0 or more");
  TESSERA_ASSIGN_OR_RETURN(
      LoopRefiner refiner,
      LoopRefiner::create(mesh, options, {.levels = level, .fullTopologyInLastLevel = limit}));
  const std::vector<Vec3> points = refiner.refinePoints(mesh.positions());
  if (limit) return refiner.limitSurface(points);
  return refiner.controlSurface(points);
}

Expected<schemes::Scheme> checkSchemeArguments(const std::string& schemeName, const ImportArgs& args,
                                               bool defaultOptions, int level, bool limit) {
  TESSERA_ASSIGN_OR_RETURN(const schemes::Scheme scheme, schemes::parseScheme(schemeName));
  if (level < 0) return invalidArgument("level must be 0 or more");
  if (scheme == schemes::Scheme::kLoop) return scheme;
  if (!schemes::schemeHasCreases(scheme) && (args.tags || !defaultOptions))
    return invalidArgument(std::string("the ") + schemeName +
                           " scheme has no crease rules: no tags, crease_method or boundary");
  if (const std::string why = schemes::limitUnavailableReason(scheme); limit && !why.empty())
    return invalidArgument("limit: " + why);
  if (schemes::schemeTakesPolygons(scheme) && (args.triangulate || args.dropUnused || args.creaseAngle))
    return invalidArgument(
        std::string("triangulate, drop_unused and crease_angle are not available with the ") + schemeName +
        " scheme, which reads the polygons as they are");
  return scheme;
}

Expected<SurfaceMesh> refineScheme(const std::string& schemeName, SchemeSource source, const ImportArgs& args,
                                   const LoopOptions& options, bool defaultOptions, int level, bool limit) {
  TESSERA_ASSIGN_OR_RETURN(const schemes::Scheme scheme,
                           checkSchemeArguments(schemeName, args, defaultOptions, level, limit));
  if (scheme == schemes::Scheme::kLoop) {
    TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, baseMeshOf(std::move(source), args));
    return refineLoop(mesh, options, level, limit);
  }
  schemes::SchemeRequest request{.scheme = scheme, .levels = level, .limit = limit, .crease = options};
  if (schemes::schemeTakesPolygons(scheme)) {
    if (args.triangulate || args.dropUnused || args.creaseAngle)
      return invalidArgument(
          std::string("triangulate, drop_unused and crease_angle are not available with the ") + schemeName +
          " scheme, which reads the polygons as they are");
    const std::string tags = args.tags.value_or("");
    TESSERA_ASSIGN_OR_RETURN(schemes::PolygonMesh mesh,
                             source.path ? schemes::importPolygonMesh(*source.path, tags)
                                         : schemes::polygonMeshOf(std::move(source.soup), "arrays", tags));
    return schemes::refinePolygons(mesh, request);
  }
  TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, baseMeshOf(std::move(source), args));
  return schemes::refineTriangles(BaseTopology::fromBaseMesh(mesh), mesh.positions(), request);
}

SurfaceMesh surfaceOf(std::vector<Vec3> points, const PolygonSoup& faces, std::vector<Vec3> normals) {
  SurfaceMesh surface;
  surface.positions = std::move(points);
  surface.normals = std::move(normals);
  bool triangles = true;
  for (int f = 0; f < faces.numFaces(); ++f)
    triangles = triangles && faces.faceOffsets[f + 1] - faces.faceOffsets[f] == 3;
  for (int f = 0; f < faces.numFaces(); ++f) {
    const std::span<const int> corners(faces.indices.data() + faces.faceOffsets[f],
                                       static_cast<size_t>(faces.faceOffsets[f + 1] - faces.faceOffsets[f]));
    if (triangles)
      surface.triangles.push_back({corners[0], corners[1], corners[2]});
    else
      surface.addPolygon(corners);
  }
  return surface;
}

Status writeSurface(const SurfaceMesh& surface, const std::string& path, bool draco) {
  return exportMesh(surface, path, {.draco = draco});
}

namespace {

std::string tagName(size_t index, const FeatureTag& tag) {
  std::string name = "tag " + std::to_string(index) + " (";
  if (tag.kind == FeatureTag::Kind::kCorner) return name + "corner " + std::to_string(tag.v0) + ")";
  return name + "crease " + std::to_string(tag.v0) + " " + std::to_string(tag.v1) + ")";
}

// The shortest decimal that reads back to the same float (std::to_chars),
// which the reader's double parse then rounds back to it; `inf` where the
// reader stores kSharpnessInfinite.
std::string sharpnessText(float s) {
  if (isInfinite(s)) return "inf";
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, s);
  return std::string(buffer, end);
}

}  // namespace

Status checkCageNames(const CageArgs& cage) {
  if (!cage.scheme.empty() && cage.scheme != "loop" && cage.scheme != "catmull-clark" &&
      cage.scheme != "bilinear")
    return invalidArgument("scheme must be 'loop', 'catmull-clark' or 'bilinear', not '" + cage.scheme + "'");
  if (!cage.boundary.empty() && cage.boundary != "edge-only" && cage.boundary != "edge-and-corner")
    return invalidArgument("boundary must be 'edge-only' or 'edge-and-corner'");
  if (!cage.creaseMethod.empty() && cage.creaseMethod != "uniform" && cage.creaseMethod != "chaikin")
    return invalidArgument("crease_method must be 'uniform' or 'chaikin'");
  return Status::ok();
}

Status setCage(SurfaceMesh& surface, const CageArgs& cage, const std::string& path) {
  if (!cage.any()) return Status::ok();
  const bool usda = exportStatesScheme(path);
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (!usda && ext != ".obj")
    return unsupported(path +
                       ": tags, scheme, boundary and crease_method are written to .obj and .usda only");
  if (!usda && !cage.scheme.empty())
    return invalidArgument(path + ": OBJ states no scheme (its `t` lines hold tags and options only)");
  if (usda && cage.scheme.empty())
    return invalidArgument(path + ": a .usda cage needs its scheme ('loop', 'catmull-clark' or 'bilinear')");
  TESSERA_RETURN_IF_ERROR(checkCageNames(cage));
  TESSERA_RETURN_IF_ERROR(tagFileText(cage.tags).status());
  // The edges of the faces as written: the polygons where there are some.
  std::set<std::pair<int, int>> edges;
  const auto addFace = [&](std::span<const int> face) {
    for (size_t k = 0; k < face.size(); ++k) edges.insert(std::minmax(face[k], face[(k + 1) % face.size()]));
  };
  if (surface.numPolygons() > 0) {
    for (size_t f = 0; f < surface.numPolygons(); ++f)
      addFace(std::span<const int>(
          surface.polygonCorners.data() + surface.polygonOffsets[f],
          static_cast<size_t>(surface.polygonOffsets[f + 1] - surface.polygonOffsets[f])));
  } else {
    for (const auto& t : surface.triangles) addFace(t);
  }
  const int n = static_cast<int>(surface.positions.size());
  for (size_t i = 0; i < cage.tags.size(); ++i) {
    const FeatureTag& tag = cage.tags[i];
    const bool crease = tag.kind == FeatureTag::Kind::kCrease;
    if (tag.v0 >= n || (crease && tag.v1 >= n))
      return invalidArgument(tagName(i, tag) + ": the surface has " + std::to_string(n) + " vertices");
    if (crease && !edges.contains(std::minmax(tag.v0, tag.v1)))
      return invalidArgument(tagName(i, tag) + ": no face has an edge between these vertices");
    if (crease)
      surface.creases.push_back({tag.v0, tag.v1, canonicalSharpness(tag.sharpness)});
    else
      surface.corners.push_back({tag.v0, canonicalSharpness(tag.sharpness)});
  }
  surface.scheme = cage.scheme;
  surface.boundary = cage.boundary;
  surface.creaseMethod = cage.creaseMethod;
  return Status::ok();
}

Expected<std::vector<FeatureTag>> tagsFromText(const std::string& text, const std::string& sourceName) {
  return parseTags(text, sourceName);
}

Expected<std::vector<FeatureTag>> readTagFile(const std::string& path) {
  TESSERA_ASSIGN_OR_RETURN(const std::string text, readFile(path));
  return tagsFromText(text, path);
}

Expected<std::string> tagFileText(const std::vector<FeatureTag>& tags) {
  // The reader's refusals (docs/FORMATS.md "Tag sidecar files"), said of
  // the tag as the caller numbered it rather than of a line not yet written.
  std::map<std::pair<int, int>, size_t> edges;
  std::map<int, size_t> vertices;
  std::string text;
  for (size_t i = 0; i < tags.size(); ++i) {
    const FeatureTag& tag = tags[i];
    const bool crease = tag.kind == FeatureTag::Kind::kCrease;
    if (tag.v0 < 0 || (crease && tag.v1 < 0))
      return invalidArgument(tagName(i, tag) + ": a vertex number must be 0 or more");
    if (crease && tag.v0 == tag.v1) return invalidArgument(tagName(i, tag) + ": names the same vertex twice");
    if (std::isnan(tag.sharpness) || tag.sharpness < 0)
      return invalidArgument(tagName(i, tag) + ": sharpness must be a number >= 0 or infinity");
    const size_t firstOnIt = crease ? edges.emplace(std::minmax(tag.v0, tag.v1), i).first->second
                                    : vertices.emplace(tag.v0, i).first->second;
    if (firstOnIt != i) {
      return invalidArgument(tagName(i, tag) + ": repeats " + tagName(firstOnIt, tags[firstOnIt]) +
                             " (a tag file has one tag per edge and per vertex)");
    }
    text += crease ? "crease " + std::to_string(tag.v0) + " " + std::to_string(tag.v1)
                   : "corner " + std::to_string(tag.v0);
    text += " " + sharpnessText(tag.sharpness) + "\n";
  }
  return text;
}

Status writeTagFile(const std::string& path, const std::vector<FeatureTag>& tags) {
  TESSERA_ASSIGN_OR_RETURN(const std::string text, tagFileText(tags));
  errno = 0;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return ioError(path + ": cannot open for writing: " + std::strerror(errno));
  out << text;
  out.close();
  if (!out) return ioError(path + ": write failed");
  return Status::ok();
}

}  // namespace tessera::python

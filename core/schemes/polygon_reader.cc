#include "core/schemes/polygon_reader.h"

#include <algorithm>
#include <filesystem>
#include <utility>

#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"
#include "core/util/file_io.h"

namespace tessera::schemes {

namespace {

// Every edge of the faces as (min, max), sorted.
std::vector<std::pair<int, int>> meshEdges(const PolyTopology& t) {
  std::vector<std::pair<int, int>> edges;
  for (int f = 0; f < t.numFaces(); ++f) {
    const int from = t.faceOffsets[f], size = t.faceOffsets[f + 1] - from;
    for (int j = 0; j < size; ++j)
      edges.push_back(std::minmax(t.indices[from + j], t.indices[from + (j + 1) % size]));
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

}  // namespace

Expected<PolygonSoup> readObjPolygons(std::string_view text, const std::string& name) {
  return importPolygonSoup(text, ".obj", name);
}

Expected<PolygonSoup> readOffPolygons(std::string_view text, const std::string& name) {
  return importPolygonSoup(text, ".off", name);
}

namespace {

// Tags from `source` (a tag file, or the mesh file's own `t` lines) onto
// the polygons: errors name the source and the tag's line.
Status applyPolygonFeatureTags(const std::vector<FeatureTag>& tags, const std::string& tagsName,
                               PolygonMesh& mesh) {
  PolyTopology& topology = mesh.topology;
  const int n = topology.numVertices;
  if (topology.vertexSharpness.empty()) topology.vertexSharpness.assign(n, 0.0f);
  const TagNaming naming{
      [&](const FeatureTag& tag) { return tagsName + ":" + std::to_string(tag.line) + ": "; },
      [](const FeatureTag& tag) { return "line " + std::to_string(tag.line); }};
  std::vector<std::pair<int, int>> edges;  // sorted (min, max), built at the first crease
  const TagTarget target{n,
                         [&](int a, int b) {
                           if (edges.empty()) edges = meshEdges(topology);
                           const std::pair<int, int> key = std::minmax(a, b);
                           return std::binary_search(edges.begin(), edges.end(), key);
                         },
                         [&](const FeatureTag& tag) {
                           if (tag.kind == FeatureTag::Kind::kCrease) {
                             topology.creases.push_back({tag.v0, tag.v1, tag.sharpness});
                           } else {
                             topology.vertexSharpness[tag.v0] = tag.sharpness;
                           }
                           return Status::ok();
                         }};
  return applyTags(tags, naming, target);
}

Status applyTagFile(const std::string& tagsPath, PolygonMesh& mesh) {
  if (tagsPath.empty()) return Status::ok();
  TESSERA_ASSIGN_OR_RETURN(const std::string text, readFile(tagsPath));
  return applyPolygonTags(text, tagsPath, mesh);
}

}  // namespace

Status applyPolygonTags(const std::string& text, const std::string& tagsName, PolygonMesh& mesh) {
  TESSERA_ASSIGN_OR_RETURN(const std::vector<FeatureTag> tags, parseTags(text, tagsName));
  return applyPolygonFeatureTags(tags, tagsName, mesh);
}

Expected<PolygonMesh> polygonMeshOf(PolygonSoup soup, const std::string& displayName,
                                    const std::string& tagsPath) {
  PolygonMesh mesh;
  mesh.topology = PolyTopology::fromSoup(soup);
  mesh.points = std::move(soup.points);
  mesh.boundary = soup.boundary;
  mesh.creaseMethod = soup.creaseMethod;
  if (!soup.tags.empty())
    TESSERA_RETURN_IF_ERROR(applyPolygonFeatureTags(featureTagsOf(soup.tags), displayName, mesh));
  TESSERA_RETURN_IF_ERROR(applyTagFile(tagsPath, mesh));
  return mesh;
}

Expected<PolygonMesh> importPolygonMeshFromBytes(std::string_view bytes, const std::string& extension,
                                                 const std::string& displayName) {
  TESSERA_ASSIGN_OR_RETURN(PolygonSoup soup, importPolygonSoup(bytes, extension, displayName));
  return polygonMeshOf(std::move(soup), displayName, "");
}

Expected<PolygonMesh> importPolygonMesh(const std::string& path, const std::string& tagsPath,
                                        const std::string& usdPrim) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (readsPolygonSoup(ext)) {
    TESSERA_ASSIGN_OR_RETURN(const std::string text, readFile(path));
    TESSERA_ASSIGN_OR_RETURN(PolygonSoup soup, importPolygonSoup(text, ext, path, usdPrim));
    return polygonMeshOf(std::move(soup), path, tagsPath);
  }
  TESSERA_ASSIGN_OR_RETURN(BaseMesh base, importMesh(path));
  PolygonMesh mesh;
  mesh.topology = PolyTopology::fromBaseMesh(base);
  mesh.points = base.positions();
  TESSERA_RETURN_IF_ERROR(applyTagFile(tagsPath, mesh));
  return mesh;
}

}  // namespace tessera::schemes

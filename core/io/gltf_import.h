// glTF 2.0 / GLB reading into a PolygonSoup plus feature tags from `extras`
// (format in docs/FORMATS.md). Used by importMesh(); exposed for tests.
//
// Choices:
//  - TRIANGLES primitives only; other modes are an error naming the primitive.
//  - All primitives of all meshes are concatenated in file order. Node
//    transforms are NOT applied: each mesh is read once, in its own space, so
//    that vertex numbers follow the file's accessors (a scene that instances
//    a mesh several times imports it once).
//  - Within one mesh, vertices with exactly equal positions are welded
//    (first occurrence keeps its place): exporters split vertices at UV and
//    normal seams, which would otherwise cut a closed surface into pieces.
//    Vertices of different meshes are never welded.
#pragma once

#include <string>
#include <vector>

#include "core/io/tag_file.h"
#include "core/mesh/polygon_soup.h"
#include "core/util/status.h"

namespace tessera {

struct GltfContent {
  PolygonSoup soup;
  std::vector<FeatureTag> tags;  // vertex indices already mapped to the soup
  TagLocator locate;             // names a tag's place in the file
};

// `data` is the whole file; `path` names it in errors. External buffers (a
// .bin next to a .gltf) are read from `baseDir`; with nullptr nothing is
// read from the filesystem and a file naming external buffers is refused.
// Primitives compressed with KHR_draco_mesh_compression are decoded with
// Draco (gltf_draco.h).
Expected<GltfContent> readGltf(const std::string& path, const std::string& data, const std::string* baseDir);

}  // namespace tessera

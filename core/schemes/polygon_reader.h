// Polygon input for the quad schemes: OBJ and OFF read as polygons, with
// coordinates parsed to full double precision (std::from_chars), strictly:
// every error names the file and the line. Other formats go through the
// triangle importer (core/io/mesh_import.h) and arrive as triangles.
// Feature tags come from a tag file (core/io/tag_file.h's syntax).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/polygon_soup.h"
#include "core/schemes/poly_builder.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera::schemes {

struct PolygonMesh {
  PolyTopology topology;
  std::vector<Vec3> points;
};

// OBJ: `v x y z [w]` and `f a[/t[/n]] ...` (negative indices count back
// from the last vertex); other statements are ignored. OFF: the counts, the
// points and `n i0 .. in-1 [colour]` faces, with `#` comments.
Expected<PolygonSoup> readObjPolygons(std::string_view text, const std::string& name);
Expected<PolygonSoup> readOffPolygons(std::string_view text, const std::string& name);

// Reads `path` (polygons for .obj and .off, the triangle importer otherwise),
// then applies the tag file `tagsPath` unless it is empty. The topology is
// validated when a refiner builds it.
Expected<PolygonMesh> importPolygonMesh(const std::string& path, const std::string& tagsPath);

// Applies parsed tags; errors name the tag's line in `tagsName`.
Status applyPolygonTags(const std::string& text, const std::string& tagsName, PolygonMesh& mesh);

}  // namespace tessera::schemes

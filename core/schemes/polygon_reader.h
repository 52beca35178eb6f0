// Polygon input for the quad schemes: OBJ, OFF and PLY read as polygons by the
// readers every import uses (core/io/mesh_import.h, importPolygonSoup: full
// double precision, strict, every error naming the file and the line),
// other formats through the triangle importer, arriving as triangles.
// Feature tags come from a tag file, applied by core/io/tag_file.h's
// applier.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/catmark/polygon_level.h"
#include "core/mesh/polygon_soup.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera::schemes {

struct PolygonMesh {
  PolyTopology topology;
  std::vector<Vec3> points;
  // The options the file states (OBJ's `t interpolateboundary`,
  // `t creasemethod`), named as on the command line; empty where it does not.
  std::string boundary, creaseMethod;
};

// OBJ and OFF as core/io reads them (text_mesh_readers.h), each face index
// checked against the vertices at its line.
Expected<PolygonSoup> readObjPolygons(std::string_view text, const std::string& name);
Expected<PolygonSoup> readOffPolygons(std::string_view text, const std::string& name);

// The polygons of a soup importPolygonSoup read (core/io/mesh_import.h),
// with the tags the file states and then the tag file `tagsPath` unless it
// is empty; errors name `displayName`.
Expected<PolygonMesh> polygonMeshOf(PolygonSoup soup, const std::string& displayName,
                                    const std::string& tagsPath);

// Reads `path` (polygons for .obj, .off and .ply, the triangle importer otherwise),
// applies the tags an OBJ states (`t crease`, `t corner`), then the tag file
// `tagsPath` unless it is empty. The topology is validated when a refiner
// builds it.
// `usdPrim` names the Mesh prim of a .usda file (empty: its only one).
Expected<PolygonMesh> importPolygonMesh(const std::string& path, const std::string& tagsPath,
                                        const std::string& usdPrim = {});
// The same for an OBJ, OFF or PLY file in memory (`extension` as
// importPolygonSoup takes it), named `displayName` in errors, without a
// tag file (applyPolygonTags applies one).
Expected<PolygonMesh> importPolygonMeshFromBytes(std::string_view bytes, const std::string& extension,
                                                 const std::string& displayName);

// Applies parsed tags; errors name the tag's line in `tagsName`.
Status applyPolygonTags(const std::string& text, const std::string& tagsName, PolygonMesh& mesh);

}  // namespace tessera::schemes

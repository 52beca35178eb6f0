// Mesh import: OBJ, OFF, PLY, STL and USDA (usda_parser.h) through Tessera's own readers
// (text_mesh_readers.h: full double precision, strict, with line numbers),
// glTF/GLB through tinygltf (Draco-compressed primitives through Draco). The
// reader chosen follows the file extension; every error names the file.
// Readers produce a PolygonSoup; then, in order: --drop-unused renumbers it,
// buildBaseMesh() triangulates and validates it, --crease-angle creases the
// edges it names, and glTF extras tags are applied (a tag file given beside
// the mesh is applied by the caller, after, with the same renumbering).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/base_mesh.h"
#include "core/mesh/polygon_soup.h"
#include "core/mesh/unused_vertices.h"
#include "core/util/status.h"

namespace tessera {

struct ImportOptions {
  bool triangulate = false;  // triangulate polygons (polygon_triangulation.h) instead of refusing them
  bool dropUnused = false;   // drop vertices no face uses instead of refusing the file
  // Degrees, 0 to 180; negative: off. Edges whose dihedral angle exceeds it
  // become infinitely sharp (crease_angle.h).
  double creaseAngle = -1;
  // USD: the Mesh prim to read, by path or name; empty: the layer's only
  // Mesh (docs/FORMATS.md "USD").
  std::string usdPrim;
};

// What the import did beyond reading, for the caller to report and to apply
// a tag file with.
struct ImportReport {
  VertexRenumbering renumbering;  // the file's vertex numbers -> the mesh's
  int edgesCreasedByAngle = 0;
  int tagsInFile = 0;  // OBJ's `t crease` and `t corner` pairs and vertices, applied
  // The subdivision options the file states (OBJ's `t interpolateboundary`,
  // `t creasemethod`; polygon_soup.h), empty where it does not.
  std::string boundary, creaseMethod;
  // The scheme the file states (USD's subdivisionScheme; polygon_soup.h).
  std::string scheme;
};

struct ImportedMesh {
  BaseMesh mesh;
  ImportReport report;
};

// One line for people: "dropped 1 unused vertex (--drop-unused); creased 12
// edges sharper than 30 degrees (--crease-angle)"; empty when there is
// nothing to say.
std::string describeImport(const ImportReport& report, const ImportOptions& options);

// Reads, validates and returns the base mesh. glTF input may carry feature
// tags in `extras` (see docs/FORMATS.md); they are applied to the mesh.
Expected<BaseMesh> importMesh(const std::string& path, const ImportOptions& options = {});
Expected<ImportedMesh> importMeshWithReport(const std::string& path, const ImportOptions& options = {});

// The same import from bytes in memory, for meshes that arrive over the
// network (CreateDocument) and for fuzzing. `extension` chooses the reader
// (".obj" or "obj", any case); `displayName` names the input in every error
// ("cube.obj:12: ..."). Never touches the filesystem: a .gltf whose buffers
// are external files is refused (a GLB, or data: URIs, carry their own).
Expected<BaseMesh> importMeshFromBytes(std::string_view bytes, const std::string& extension,
                                       const std::string& displayName, const ImportOptions& options = {});
Expected<ImportedMesh> importMeshFromBytesWithReport(std::string_view bytes, const std::string& extension,
                                                     const std::string& displayName,
                                                     const ImportOptions& options = {});

// The polygons of an OBJ, OFF or PLY file in memory exactly as the file states
// them, for the schemes that refine polygons as they are
// (core/schemes/polygon_reader.h): the readers importMesh uses, and since no
// buildBaseMesh follows, every face index is checked against the vertices at
// its line and a file without vertices or faces is refused. `extension`
// chooses the reader (".obj", "off" or ".ply", any case); other formats are
// unsupported here.
// `usdPrim` names the Mesh prim of a .usda file (ImportOptions::usdPrim).
Expected<PolygonSoup> importPolygonSoup(std::string_view bytes, const std::string& extension,
                                        const std::string& displayName, const std::string& usdPrim = {});

// Whether importPolygonSoup reads `extension` (".obj", "off", ".PLY", ".usda", ...).
bool readsPolygonSoup(const std::string& extension);

// The import's steps after reading (--drop-unused, validation, the crease
// angle, the file's own tags) on a soup importPolygonSoup read, so that a
// caller choosing between polygons and triangles reads the file once.
Expected<ImportedMesh> importSoupWithReport(PolygonSoup soup, const std::string& displayName,
                                            const ImportOptions& options = {});

// Extensions importMesh() accepts, lower case with the dot: ".obj", ...
const std::vector<std::string>& supportedImportExtensions();

}  // namespace tessera

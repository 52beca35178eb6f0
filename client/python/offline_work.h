// The C++ side of the package's offline functions (docs/PYTHON.md
// "Offline"): a base mesh from a file or from arrays, as core imports it,
// its uniform refinement, a surface written as core's exporter writes it,
// and tag files read and written. Free of Python, so that the
// python_offline fuzz target (docs/FUZZING.md) runs exactly what
// tessera.read_mesh, refine, read_tags and write_tags run once their
// arguments are C++.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/io/mesh_export.h"
#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"
#include "core/loop/loop_refiner.h"
#include "core/mesh/base_mesh.h"
#include "core/mesh/polygon_soup.h"
#include "core/mesh/surface_mesh.h"
#include "core/schemes/scheme.h"
#include "core/util/status.h"

namespace tessera::python {

// read_mesh's and refine's keyword arguments.
struct ImportArgs {
  std::optional<std::string> tags;  // a tag file's path (docs/FORMATS.md)
  bool triangulate = false, dropUnused = false;
  std::optional<double> creaseAngle;  // degrees; none: off
};

// The same validation for both (mesh_validation.h), tags applied after.
// Errors name the file (or "arrays"), the line where there is one, and the
// reason.
Expected<BaseMesh> baseMeshFromFile(const std::string& path, const ImportArgs& args);
Expected<BaseMesh> baseMeshFromArrays(PolygonSoup soup, const ImportArgs& args);

// What a function's `source` named: a file, else the arrays.
struct SchemeSource {
  std::optional<std::string> path;
  PolygonSoup soup;
};
// baseMeshFromFile or baseMeshFromArrays, as `source` says.
Expected<BaseMesh> baseMeshOf(SchemeSource source, const ImportArgs& args);

// crease_method "uniform" or "chaikin", boundary "edge-only" or
// "edge-and-corner"; anything else is an InvalidArgument naming the choices.
Expected<LoopOptions> loopOptionsNamed(const std::string& creaseMethod, const std::string& boundary);

// `level` >= 0 uniform steps: the control points of that level (with the
// control mesh's normals), or with `limit` their exact limit positions and
// unit normals.
Expected<SurfaceMesh> refineLoop(const BaseMesh& mesh, const LoopOptions& options, int level, bool limit);

// The other schemes of `tessera refine --scheme` (core/schemes/scheme.h),
// by name: the polygon schemes (catmull-clark, bilinear, doo-sabin) on the
// file's polygons as they are, or the arrays' faces; the triangle schemes
// (butterfly, sqrt3) on the base mesh as baseMeshFrom* imports it. A scheme
// without crease rules refuses tags and a crease option other than the
// defaults, a polygon scheme the triangle importer's options, a scheme
// without a limit `limit`: each an InvalidArgument that says so.
// The scheme named, if it takes these arguments; else an InvalidArgument
// that says why not.
Expected<schemes::Scheme> checkSchemeArguments(const std::string& schemeName, const ImportArgs& args,
                                               bool defaultOptions, int level, bool limit);
Expected<SurfaceMesh> refineScheme(const std::string& schemeName, SchemeSource source, const ImportArgs& args,
                                   const LoopOptions& options, bool defaultOptions, int level, bool limit);

// write_mesh: `points` with `faces` (all triangles: a triangle surface;
// else polygons, which OBJ, OFF, PLY and USDA keep and STL and GLB write as
// fans, core/io/mesh_export.h) and `normals` (none, or one per point), in
// the format of the path's extension. exportMesh's checks name the element
// at fault; nothing is written unless they pass.
SurfaceMesh surfaceOf(std::vector<Vec3> points, const PolygonSoup& faces, std::vector<Vec3> normals);
Status writeSurface(const SurfaceMesh& surface, const std::string& path, bool draco);

// write_mesh(tags=, scheme=, boundary=, crease_method=): the surface as a
// subdivision cage, its sharp features and options in the file, where the
// format has a place for them: OBJ's `t` lines (tags, boundary rule, crease
// method; docs/FORMATS.md "Tags in OBJ") and USDA's subdivision attributes
// (all of them; a cage there needs its scheme). Refused, each an error that
// says why: any of them for another format (Unsupported), a scheme for OBJ,
// which states none, a name that is none of the choices, and a tag that
// tagFileText refuses, that names a vertex the surface does not have, or a
// crease on two vertices no face joins by an edge (InvalidArgument): what
// the readers would refuse.
struct CageArgs {
  std::vector<FeatureTag> tags;
  std::string scheme, boundary, creaseMethod;  // "": not stated
  bool any() const { return !tags.empty() || !scheme.empty() || !boundary.empty() || !creaseMethod.empty(); }
};
// The names alone (the caller's choice: a ValueError in Python).
Status checkCageNames(const CageArgs& cage);
Status setCage(SurfaceMesh& surface, const CageArgs& cage, const std::string& path);

// read_tags: a tag file's tags (docs/FORMATS.md "Tag sidecar files") in the
// file's order, as core's parser reads them (sharpness `inf` is 10,
// kSharpnessInfinite). They are checked against no mesh: read_mesh(tags=)
// and refine(tags=) apply a file to one. `sourceName` names it in errors.
Expected<std::vector<FeatureTag>> tagsFromText(const std::string& text, const std::string& sourceName);
Expected<std::vector<FeatureTag>> readTagFile(const std::string& path);

// write_tags: the text of a tag file stating `tags` in order, one line each,
// that tagsFromText reads back to the same tags: sharpness as the shortest
// decimal that reads back to the same float, `inf` from 10 up. Refused
// (InvalidArgument naming the tag by its position): a negative vertex, a
// crease naming one vertex twice, a negative or NaN sharpness, and a second
// tag on an edge (either direction) or a vertex, which the reader refuses.
Expected<std::string> tagFileText(const std::vector<FeatureTag>& tags);
Status writeTagFile(const std::string& path, const std::vector<FeatureTag>& tags);

}  // namespace tessera::python

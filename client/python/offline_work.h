// The C++ side of the package's offline functions (docs/PYTHON.md
// "Offline"): a base mesh from a file or from arrays, as core imports it,
// and Loop's uniform refinement of it. Free of Python, so that the
// python_offline fuzz target (docs/FUZZING.md) runs exactly what
// tessera.read_mesh and tessera.refine run once their arguments are C++.
#pragma once

#include <optional>
#include <string>

#include "core/io/mesh_import.h"
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

}  // namespace tessera::python

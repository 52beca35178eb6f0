// USD's text format (usda) for a refined surface or a subdivision cage: one
// UsdGeomMesh prim "Surface" (docs/FORMATS.md "USD", what is written).
// Internal to core/io; exportMesh() chooses it for `.usda`.
#pragma once

#include "core/io/file_writer.h"
#include "core/mesh/surface_mesh.h"

namespace tessera::io_detail {

// A surface with `scheme` set is a cage: its subdivisionScheme, boundary
// rule, crease method (as Tessera's own `tessera:creaseMethod`, which
// UsdGeomMesh lacks) and tags are written, infinitely sharp as 10. One
// without (a limit surface) is a polygon mesh: subdivisionScheme "none" and
// its normals with interpolation "vertex". Points and normals are typed
// point3f and normal3f as the schema declares them, printed as the
// shortest decimals that read back to the same doubles (USD reads them as
// float; Tessera's reader keeps every digit).
void writeUsda(const SurfaceMesh& surface, FileWriter& out);

}  // namespace tessera::io_detail

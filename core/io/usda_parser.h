// The layer structure of a usda file as far as meshes need it: the prims,
// nested, and of each Mesh prim the attributes that define its control
// mesh and subdivision tags (UsdGeomMesh, "Subdivision Surfaces" of the
// UsdGeom schema), with the token where each was authored. Internal to
// core/io; usda_reader.cc turns a Mesh into a PolygonSoup.
//
// Strict: anything that composes other layers or varies a value (references,
// payloads, inherits, specializes, variants and variant sets, sublayers,
// time samples, connections, `over` and `class` prims) is refused by name,
// since reading the layer alone would give a mesh that is not the one USD
// composes (docs/FORMATS.md "USD").
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/io/usda_lexer.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera::io_detail {

template <typename T>
struct UsdaAttribute {
  bool authored = false;
  UsdaToken where;  // the attribute's name
  T value{};
};

struct UsdaMeshPrim {
  std::string path;  // "/World/Cube"
  int line = 0;
  UsdaAttribute<std::vector<Vec3>> points;
  UsdaAttribute<std::vector<int>> faceVertexCounts, faceVertexIndices;
  UsdaAttribute<std::vector<int>> creaseIndices, creaseLengths, cornerIndices, holeIndices;
  UsdaAttribute<std::vector<double>> creaseSharpnesses, cornerSharpnesses;
  UsdaAttribute<std::string> subdivisionScheme, interpolateBoundary, orientation, triangleSubdivisionRule;
  // Tessera's own: OpenSubdiv's crease method, which UsdGeomMesh does not
  // carry (docs/FORMATS.md "USD").
  UsdaAttribute<std::string> creaseMethod;
};

// Parses the whole layer (after checking the `#usda 1.0` header); every
// error names `source`, the line, the column and the attribute or statement.
Expected<std::vector<UsdaMeshPrim>> parseUsdaMeshes(std::string_view text, const std::string& source);

}  // namespace tessera::io_detail

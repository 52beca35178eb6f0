// The subdivision schemes `tessera refine --scheme` offers, by name, and one
// call per input kind that refines uniformly and returns the surface to
// write. Loop keeps its own path (core/loop/loop_refiner.h).
//
//   scheme          input      creases  --limit
//   loop            triangles  yes      positions and normals (LoopRefiner)
//   catmull-clark   polygons   yes      positions and normals (OpenSubdiv's Limit())
//   bilinear        polygons   no       refused: the limit is the control mesh
//   butterfly       triangles  no       refused: interpolating, vertices lie on the limit
//   sqrt3           triangles  no       positions (Kobbelt's limit mask), no normals
//   doo-sabin       polygons   no       refused: limit points belong to faces (doo_sabin.h)
#pragma once

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/catmark/polygon_level.h"
#include "core/loop/level_builder.h"
#include "core/mesh/surface_mesh.h"
#include "core/schemes/polygon_reader.h"
#include "core/util/status.h"

namespace tessera::schemes {

enum class Scheme { kLoop, kCatmullClark, kBilinear, kButterfly, kSqrt3, kDooSabin };

// "loop", "catmull-clark", "bilinear", "butterfly", "sqrt3", "doo-sabin".
const std::vector<std::string>& schemeNames();
Expected<Scheme> parseScheme(const std::string& name);
const char* schemeName(Scheme scheme);

bool schemeTakesPolygons(Scheme scheme);  // otherwise triangles
bool schemeHasCreases(Scheme scheme);     // sharpness tags and crease options apply
// Empty when --limit is available, otherwise why not.
std::string limitUnavailableReason(Scheme scheme);

struct SchemeRequest {
  Scheme scheme = Scheme::kCatmullClark;
  int levels = 1;
  bool limit = false;
  CreaseOptions crease;
  long long maxFaces = 16LL * 1024 * 1024;
};

// catmull-clark, bilinear, doo-sabin.
Expected<SurfaceMesh> refinePolygons(const PolygonMesh& mesh, const SchemeRequest& request);
// butterfly, sqrt3.
Expected<SurfaceMesh> refineTriangles(const BaseTopology& topology, std::span<const Vec3> points,
                                      const SchemeRequest& request);

}  // namespace tessera::schemes

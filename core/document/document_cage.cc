#include "core/document/document_cage.h"

#include "core/catmark/surfaces.h"
#include "core/loop/surfaces.h"
#include "core/topology/cage_tags.h"

namespace tessera {

Expected<SurfaceMesh> documentCage(const Document& document, int level) {
  TESSERA_ASSIGN_OR_RETURN(auto eval, document.evaluate(level));
  const Level& topology = eval->levels[level];
  const std::vector<Vec3>& points = eval->points[level];
  const bool catmark = document.scheme() == DocumentScheme::kCatmullClark;
  SurfaceMesh cage = catmark ? polygonSurfaceOf(topology, points) : controlSurfaceOf(topology, points);
  cage.normals.clear();  // a cage's points are not on its surface: no normals to state
  addCageTags(topology, cage);
  const LoopOptions& options = document.options().loop;
  cage.boundary = options.boundary == BoundaryInterpolation::kEdgeAndCorner ? "edge-and-corner" : "edge-only";
  cage.creaseMethod = options.creaseMethod == CreaseMethod::kChaikin ? "chaikin" : "uniform";
  cage.scheme = catmark ? "catmull-clark" : "loop";
  return cage;
}

}  // namespace tessera

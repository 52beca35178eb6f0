#include "core/tessellation/document_grid.h"

#include <algorithm>

namespace tessera {

Expected<QuantizationGrid> documentGrid(const Document& doc) {
  const auto& points = doc.basePoints();
  if (points.empty()) return invalidArgument("a document without points has no grid");
  Vec3 lo = points[0], hi = lo;
  for (const Vec3& p : points) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-9});
  const Vec3 center = 0.5 * (lo + hi), half(2.5 * extent, 2.5 * extent, 2.5 * extent);
  // gridFor relates the error to the box it is given; scale to the base box.
  const double ratio = std::max((hi - lo).norm() / (2.0 * half).norm(), 1e-3);
  return gridFor(center - half, center + half, kDefaultMaxErrorFraction * ratio);
}

}  // namespace tessera

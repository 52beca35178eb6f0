#include "core/catmark/stencils.h"

#include <cassert>

#include "core/catmark/point_rules.h"

namespace tessera {

CatmarkStencils::CatmarkStencils(const Level& parent, const LoopOptions& options)
    : parent_(parent),
      inherit_(parent, options),
      parentSharpness_(static_cast<size_t>(parent.maxValence)),
      childSharpness_(static_cast<size_t>(parent.maxValence)) {}

Vec3 CatmarkStencils::faceChild(Index f, std::span<const Vec3> p) const {
  return catmark::facePoint(parent_, f, p);
}

Vec3 CatmarkStencils::edgeChild(Index e, std::span<const Vec3> p) {
  const auto faceOf = [&](Index f) {
    assert(f >= 0 && "boundary edges are infinitely sharp; absent faces are never refined");
    return catmark::facePoint(parent_, f, p);
  };
  return catmark::edgePoint(parent_, e, p, inherit_.edgeChildRule(e), faceOf);
}

Vec3 CatmarkStencils::vertexChild(Index v, std::span<const Vec3> p) {
  const auto faceOf = [&](Index f) { return catmark::facePoint(parent_, f, p); };
  const auto ring = parent_.ringEdgesOf(v);
  const auto childHalf = [&](int k) {
    const Index e = ring[k];
    return inherit_.halfSharpness(e, parent_.edgeVertices[e][0] == v ? 0 : 1);
  };
  return catmark::vertexPoint(parent_, v, p, faceOf, inherit_.vertexChildRule(v),
                              inherit_.vertexChildSharpness(v), childHalf, parentSharpness_.data(),
                              childSharpness_.data());
}

}  // namespace tessera

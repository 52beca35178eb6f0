#include "core/catmark/interpolate.h"

#include <cassert>
#include <vector>

#include "core/catmark/point_rules.h"

namespace tessera {

namespace {

// The uniform numbering (quad_split.h): face points first, so that edge
// and vertex points read them rather than recompute them.
class UniformCatmark {
 public:
  UniformCatmark(const Level& parent, const Level& child, std::span<const Vec3> p, std::span<Vec3> c)
      : parent_(parent),
        child_(child),
        p_(p),
        c_(c),
        corners_(static_cast<Index>(parent.faceVertices.size())),
        firstFaceVertex_(parent.numVertices),
        parentSharpness_(parent.maxValence),
        childSharpness_(parent.maxValence) {}

  void facePoints() const {
    for (Index f = 0, nF = parent_.numFaces(); f < nF; ++f)
      c_[firstFaceVertex_ + f] = catmark::facePoint(parent_, f, p_);
  }

  void edgePoints() const {
    const Index first = parent_.numVertices + parent_.numFaces();
    const auto faceOf = [this](Index f) -> const Vec3& { return c_[firstFaceVertex_ + f]; };
    for (Index e = 0, nE = static_cast<Index>(parent_.edgeVertices.size()); e < nE; ++e) {
      assert((parent_.edgeFaces[e][1] != kNoIndex || isSharp(parent_.edgeSharpness[e])) &&
             "boundary edges are infinitely sharp");
      c_[first + e] = catmark::edgePoint(parent_, e, p_, child_.vertexRules[first + e], faceOf);
    }
  }

  void vertexPoints() {
    const auto faceOf = [this](Index f) -> const Vec3& { return c_[firstFaceVertex_ + f]; };
    for (Index v = 0; v < parent_.numVertices; ++v) {
      const auto ring = parent_.ringEdgesOf(v);
      const auto childHalf = [&](int k) {
        const Index e = ring[k];
        return child_.edgeSharpness[corners_ + 2 * e + (parent_.edgeVertices[e][0] == v ? 0 : 1)];
      };
      c_[v] = catmark::vertexPoint(parent_, v, p_, faceOf, child_.vertexRules[v], child_.vertexSharpness[v],
                                   childHalf, parentSharpness_.data(), childSharpness_.data());
    }
  }

 private:
  const Level& parent_;
  const Level& child_;
  std::span<const Vec3> p_;
  std::span<Vec3> c_;
  const Index corners_;
  const Index firstFaceVertex_;
  std::vector<float> parentSharpness_, childSharpness_;
};

}  // namespace

void interpolateCatmark(const Level& parent, const Level& child, std::span<const Vec3> parentPoints,
                        std::span<Vec3> childPoints) {
  assert(static_cast<int>(childPoints.size()) >= child.numVertices);
  UniformCatmark stencils(parent, child, parentPoints, childPoints);
  stencils.facePoints();
  stencils.edgePoints();
  stencils.vertexPoints();
}

}  // namespace tessera

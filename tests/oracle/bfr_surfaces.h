// OpenSubdiv's Bfr as the oracle of limit surfaces (Bfr::RefinerSurfaceFactory,
// double precision): a base mesh's faces evaluated at face parameters, the
// position and the normal Du x Dv, each face's surface prepared once. Both
// schemes' tests use it (bfr_limit_test.cc, bfr_catmark_limit_test.cc).
#pragma once

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>

#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/util/vec3.h"

namespace tessera::oracle {

struct BfrValue {
  Vec3 position, normal;
  bool degenerate = false;  // Du x Dv vanishes: no normal from the derivatives
};

class BfrSurfaces {
 public:
  // `refiner`: the base mesh, unrefined, with its scheme and tags.
  BfrSurfaces(std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> refiner, std::span<const Vec3> points,
              int approxLevel)
      : refiner_(std::move(refiner)) {
    OpenSubdiv::Bfr::SurfaceFactory::Options o;
    o.SetApproxLevelSharp(approxLevel).SetApproxLevelSmooth(approxLevel);
    factory_ = std::make_unique<OpenSubdiv::Bfr::RefinerSurfaceFactory<>>(*refiner_, o);
    for (const Vec3& p : points) meshPoints_.insert(meshPoints_.end(), {p[0], p[1], p[2]});
  }

  BfrValue at(int face, const std::array<double, 2>& uv) {
    auto& s = surfaces_[face];
    if (!s.surface.IsValid()) {
      if (!factory_->InitVertexSurface(face, &s.surface))
        throw std::runtime_error("Bfr: no surface for a face");
      s.patch.resize(3 * s.surface.GetNumPatchPoints());
      s.surface.PreparePatchPoints(meshPoints_.data(), 3, s.patch.data(), 3);
    }
    double p[3], du[3], dv[3];
    s.surface.Evaluate(uv.data(), s.patch.data(), 3, p, du, dv);
    const Vec3 u(du[0], du[1], du[2]), v(dv[0], dv[1], dv[2]);
    const Vec3 n = u % v;
    // At a corner whose sector has one face, the surface leaves the vertex
    // quadratically across it (its second tangent has eigenvalue 1/4), so the
    // parameterization's derivatives there are parallel or zero.
    const double scale = std::max(u.norm(), v.norm());
    return {Vec3(p[0], p[1], p[2]), n, n.norm() <= 1e-6 * scale * scale};
  }

 private:
  struct FaceSurface {
    OpenSubdiv::Bfr::Surface<double> surface;
    std::vector<double> patch;
  };
  std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> refiner_;
  std::unique_ptr<OpenSubdiv::Bfr::RefinerSurfaceFactory<>> factory_;
  std::vector<double> meshPoints_;
  std::map<int, FaceSurface> surfaces_;
};

}  // namespace tessera::oracle

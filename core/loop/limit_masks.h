// Exact limit masks of a vertex whose rules no longer change: the left
// eigenvectors of its ring's subdivision matrix.
//
// Loop refines a vertex's ring (the vertex and its n neighbours) into the
// next level's ring by a fixed (n+1)x(n+1) matrix S once every sharpness is
// 0 or infinite. The limit point is l1 . P for the left eigenvector l1 of
// S's eigenvalue 1, and the surface near it is
//   x(u) = l1.P + sum_i (li . P) psi_i(u),   psi_i(u/2) = lambda_i psi_i(u),
// so the tangent plane is spanned by li . P for the two leading subdominant
// eigenvalues, when those are unique as a pair (Doo & Sabin '78, Reif '95,
// Zorin '00; Halstead et al. '93 compute Catmull-Clark's masks this way).
// OpenSubdiv's Loop masks (sdc/loopScheme.h) are these eigenvectors only for
// smooth vertices and for crease sectors of up to three faces; at darts,
// wider crease sectors, corners and cusps they are approximations.
//
// A crease or corner splits the ring into sectors between sharp edges; each
// sector's rows only read the sector (the vertex rule reads the two crease
// neighbours, which bound every sector), so each has its own matrix and
// tangent plane. Where the leading subdominant eigenvalues do not single out
// a plane (three or more tie, or the second and third tie), the sector has no
// tangent plane; SectorMasks::Kind says what normal is used instead.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/loop/crease.h"

namespace tessera {

// A ring whose rules do not change from level to level.
struct StationaryRing {
  int valence = 0;
  bool boundary = false;
  VertexRule rule = VertexRule::kSmooth;
  std::vector<bool> sharpEdges;  // ring edge k infinitely sharp
};

struct SectorMasks {
  enum class Kind : uint8_t {
    // tangent1 x tangent2 is the sector's limit normal.
    kTangentPlane,
    // A corner sector without a tangent plane (3 or more faces): the plane
    // of its two bounding crease curves, whose limit tangents at the corner
    // are their first edges (a curve's end point interpolates and its end
    // tangent is the first control edge). It is the one plane that contains
    // both curves' directions, so shading stays continuous along them.
    kBoundingCurves,
    // A crease sector without a tangent plane (the next eigenvalues tie):
    // the plane of the crease tangent (tangent1) and the sector's dominant
    // direction (tangent2), which hold the leading terms of the surface.
    kDominantAndCrease,
    // A cone point (a cusp: a sharp vertex whose ring has no two sharp
    // edges): the ring's radial mode leads alone, so there is no tangent
    // plane; the normal is the cone's axis (tangent1, the left eigenvector
    // of that mode), oriented to the faces' side.
    kConeAxis,
  };
  int firstEdge = 0;  // faces firstEdge .. firstEdge + faceCount - 1 (mod valence)
  int faceCount = 0;
  Kind kind = Kind::kTangentPlane;
  // Weights over (vertex, ring 0 .. valence-1); oriented so tangent1 x
  // tangent2 points to the side the faces' counter-clockwise order faces.
  std::vector<double> tangent1, tangent2;
  double lambda1 = 0.0, lambda2 = 0.0;  // the eigenvalues of the two tangents

  // The normal is tangent1 x tangent2, linear in the ring in each factor;
  // the other kinds orient it by the ring's faces.
  bool normalIsCrossProduct() const {
    return kind == Kind::kTangentPlane || kind == Kind::kDominantAndCrease;
  }
};

struct StationaryMasks {
  std::vector<double> position;      // weights over (vertex, ring 0 .. valence-1)
  std::vector<SectorMasks> sectors;  // in ring order from the first sharp edge
};

// The masks of a ring, computed on first use and cached for the process
// (thread-safe). Smooth rings of any valence are valid input, though limit.cc
// evaluates those in closed form. The cache keeps at most
// kStationaryMasksCacheEntries configurations; past that the masks are
// computed and returned without being kept, and `cached` (if given) says
// false: a caller that keeps a raw pointer must keep only cached ones.
inline constexpr size_t kStationaryMasksCacheEntries = 16384;
std::shared_ptr<const StationaryMasks> stationaryMasks(const StationaryRing& ring, bool* cached = nullptr);

// Uncached, for tests: the same computation.
StationaryMasks computeStationaryMasks(const StationaryRing& ring);

// The subdivision matrix of the ring, row-major (n+1)^2, for tests.
std::vector<double> stationarySubdivisionMatrix(const StationaryRing& ring);

}  // namespace tessera

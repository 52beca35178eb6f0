// The limit position and tangents of a Catmull-Clark dart (a vertex with
// one sharp edge) as the surface has them under Sdc's rules.
//
// A dart's one-ring (the vertex, its n neighbours and the n opposite
// corners of its faces) is closed under one step of subdivision: the vertex
// takes the smooth rule, the sharp edge its midpoint, the other edges and
// faces the usual points. So it has a subdivision matrix of its own. The
// limit position is that matrix's left eigenvector of eigenvalue 1; the
// tangent plane is spanned by its largest left eigenvectors below 1 that
// are symmetric and antisymmetric across the dart edge (0.4621 and 0.4101 at
// valence 3, both 1/2 at 4, 0.5264 and 0.5500 at 5). OpenSubdiv's
// Limit() takes the smooth masks at a dart, which are not these: its
// position is off by about 4e-3 of the diagonal and its normal by about
// 0.5 rad on jittered tori (docs/LIMITS.md "Catmull-Clark limits").
#pragma once

#include <vector>

namespace tessera::catmark {

// Weights of the vertex, of ring neighbour i and of ring face i's opposite
// corner, i counted from the dart edge in ring order (face i lies between
// neighbours i and i + 1).
struct DartMask {
  double vertex = 0;
  std::vector<double> neighbours, faceCorners;
};

struct DartMasks {
  int valence = 0;
  DartMask limit;   // sums to 1
  DartMask along;   // symmetric across the dart edge, towards it
  DartMask across;  // antisymmetric, towards neighbour 1; along x across turns as the ring does
  double alongEigenvalue = 0, acrossEigenvalue = 0;
};

// Up to this valence a dart takes these masks; above it, Limit()'s smooth
// ones. The power iteration's steps grow with the valence as the ring's
// eigenvalues crowd together below 0.6545 (18 ms at valence 64 on the
// 2-core machine of docs/PERFORMANCE.md, 3.9 s at 400), and a mesh may hold
// a vertex of any valence: a bound keeps a hostile mesh from holding the
// evaluation for minutes (docs/LIMITS.md "Catmull-Clark limits").
inline constexpr int kMaxExactDartValence = 64;
inline bool hasExactDartMasks(int valence) {
  return valence >= 3 && valence <= kMaxExactDartValence;
}

// Computed once per valence (3 to kMaxExactDartValence; power iteration on
// the ring's matrix, core/catmark/left_eigenvector.h) and kept. Thread-safe.
const DartMasks& dartMasks(int valence);

}  // namespace tessera::catmark

// The tangent across a Catmull-Clark crease into a span of three or more
// faces, exactly as the surface has it under Sdc's crease rules.
//
// A crease vertex's span of k faces, with its crease neighbours a and b,
// its interior ring neighbours and the opposite corners of its faces, is
// closed under one step of subdivision (the crease vertex point reads a, v
// and b only), so it has a subdivision matrix of its own. The limit
// tangent across the crease is that matrix's left eigenvector of the
// largest eigenvalue below 1 that is symmetric under a <-> b (the crease
// direction a - b has 1/2). For k = 1 and 2 the masks of OpenSubdiv's
// Limit() (Biermann et al., "Piecewise Smooth Subdivision Surfaces with
// Normal Control") are that eigenvector; for k >= 3 they are not, since
// they were derived for Biermann's modified rules: Limit()'s normal there
// is about 1e-2 rad off the surface that Bfr converges to (docs/LIMITS.md
// "Catmull-Clark limits").
#pragma once

#include <vector>

namespace tessera::catmark {

struct CreaseSpanTangent {
  int faces = 0;                           // k >= 3
  double eigenvalue = 0;                   // 0.5797 for k = 3, rising towards 2/3
  double vertex = 0;                       // weight of the crease vertex
  double creaseNeighbour = 0;              // of a and of b
  std::vector<double> interiorNeighbours;  // of interior ring neighbour i = 1..k-1, at [i - 1]
  std::vector<double> faceCorners;         // of span face i = 0..k-1's opposite corner, at [i]
};

// Computed once per k (power iteration on the span's matrix, restricted to
// the mirror-symmetric vectors with no constant part) and kept; scaled so
// that it points into the span with about the length of Limit()'s mask.
// Thread-safe.
const CreaseSpanTangent& creaseSpanTangent(int faces);

}  // namespace tessera::catmark

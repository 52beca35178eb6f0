// Sharpness values and vertex rules shared by tags, the base mesh, the
// topology and the rules of every scheme.
//
// Semantics follow OpenSubdiv 3.5's Sdc (sdc/crease.h), so that a surface
// authored for one tool is the same surface in the other:
//   0            smooth
//   (0, 10)      semi-sharp: sharp for `s` levels, blended for a fraction
//                (DeRose, Kass & Truong '98, "Subdivision Surfaces in
//                Character Animation")
//   >= 10        infinitely sharp (a crease, or a corner for vertices)
#pragma once

#include <cmath>
#include <cstdint>

namespace tessera {

inline constexpr float kSharpnessSmooth = 0.0f;
inline constexpr float kSharpnessInfinite = 10.0f;

inline bool isSharp(float s) {
  return s > kSharpnessSmooth;
}
inline bool isSmooth(float s) {
  return s <= kSharpnessSmooth;
}
inline bool isInfinite(float s) {
  return s >= kSharpnessInfinite;
}
inline bool isSemiSharp(float s) {
  return s > kSharpnessSmooth && s < kSharpnessInfinite;
}

// Canonical stored value: infinite values collapse to kSharpnessInfinite.
inline float canonicalSharpness(float s) {
  return isInfinite(s) ? kSharpnessInfinite : s;
}

// The rule of a vertex by its number of sharp edges, those of Hoppe et al.
// '94 (Pulli & Lounsbery, "Hierarchical Editing and Rendering of Subdivision
// Surfaces" §2.4): 0 smooth, 1 dart, 2 crease, 3+ corner; a sharp vertex is a
// corner (or a cusp when no sharp edge meets it -- the corner mask serves
// both). Every scheme and the topology (core/topology/level.h) share it, as
// they share Sdc::Crease in OpenSubdiv.
enum class VertexRule : uint8_t {
  kSmooth = 1,
  kDart = 2,
  kCrease = 4,
  kCorner = 8,
};

inline bool isSmoothLike(VertexRule r) {
  return r == VertexRule::kSmooth || r == VertexRule::kDart;
}

inline VertexRule vertexRule(float vertexSharpness, int sharpEdgeCount) {
  if (isSharp(vertexSharpness)) return VertexRule::kCorner;
  switch (sharpEdgeCount) {
    case 0:
      return VertexRule::kSmooth;
    case 1:
      return VertexRule::kDart;
    case 2:
      return VertexRule::kCrease;
    default:
      return VertexRule::kCorner;
  }
}

// Boundary edges are always infinitely sharp; this decides boundary corners
// (Sdc's VtxBoundaryInterpolation, shared by every scheme).
enum class BoundaryInterpolation {
  kEdgeOnly,       // a boundary vertex with one face follows the crease rule
  kEdgeAndCorner,  // a boundary vertex with one face is an infinitely sharp corner
};

}  // namespace tessera

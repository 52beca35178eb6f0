// Sharpness values shared by tags, the base mesh and the Loop rules.
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

}  // namespace tessera

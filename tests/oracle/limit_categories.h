// Which kind of vertex a limit belongs to, for the comparisons with
// OpenSubdiv: PrimvarRefiner::Limit() is the true limit only at some of them
// (core/loop/limit.h), and Bfr approximates irregular features.
#pragma once

#include <string>

#include "core/loop/exact_limit.h"
#include "core/mesh/sharpness.h"
#include "core/topology/level.h"

namespace tessera::oracle {

enum class LimitCategory {
  kSmooth,         // no sharp edge in the ring
  kNarrowCrease,   // infinitely sharp crease, first sector of 1..3 faces
  kWideCrease,     // infinitely sharp crease, first sector of 4+ faces
  kDart,           // one infinitely sharp edge
  kCornerOneFace,  // infinitely sharp corner, the sector of ring face 0 has one face
  kCornerWide,     // infinitely sharp corner, that sector has 2+ faces
  kCusp,           // sharp vertex with fewer than two sharp edges
  kSemiSharp,      // a semi-sharp edge or vertex that has not decayed
};

inline std::string nameOf(LimitCategory c) {
  switch (c) {
    case LimitCategory::kSmooth:
      return "smooth";
    case LimitCategory::kNarrowCrease:
      return "crease, 1-3 faces";
    case LimitCategory::kWideCrease:
      return "crease, 4+ faces";
    case LimitCategory::kDart:
      return "dart";
    case LimitCategory::kCornerOneFace:
      return "corner, 1-face side";
    case LimitCategory::kCornerWide:
      return "corner, wider side";
    case LimitCategory::kCusp:
      return "cusp";
    case LimitCategory::kSemiSharp:
      return "semi-sharp";
  }
  return "?";
}

inline LimitCategory categoryOf(const Level& level, Index v) {
  if (isSemiSharp(level.vertexSharpness[v])) return LimitCategory::kSemiSharp;
  for (Index e : level.ringEdgesOf(v)) {
    if (isSemiSharp(level.edgeSharpness[e])) return LimitCategory::kSemiSharp;
  }
  const std::vector<int> sharp = sharpRingEdges(level, v);
  switch (level.vertexRules[v]) {
    case VertexRule::kSmooth:
      return LimitCategory::kSmooth;
    case VertexRule::kDart:
      return LimitCategory::kDart;
    case VertexRule::kCrease:
      return sharp[1] - sharp[0] <= 3 ? LimitCategory::kNarrowCrease : LimitCategory::kWideCrease;
    case VertexRule::kCorner: {
      if (sharp.size() < 2) return LimitCategory::kCusp;
      // The sector holding ring face 0 (limit.h's primary side of a corner).
      const int n = level.valence(v);
      const int faces = sharp[0] == 0 ? sharp[1] : sharp[0] + n - sharp.back();
      return faces == 1 ? LimitCategory::kCornerOneFace : LimitCategory::kCornerWide;
    }
  }
  return LimitCategory::kSemiSharp;
}

// Where Limit()'s position, and its normal, are the true limit's.
inline bool osdPositionIsExact(LimitCategory c) {
  return c != LimitCategory::kDart && c != LimitCategory::kSemiSharp;
}
inline bool osdNormalIsExact(LimitCategory c) {
  return c == LimitCategory::kSmooth || c == LimitCategory::kNarrowCrease ||
         c == LimitCategory::kCornerOneFace;
}

}  // namespace tessera::oracle

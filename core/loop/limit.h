// Limit positions and normals of every vertex of a level, by Loop's limit
// masks: smooth and dart vertices use the eigenvector masks, crease vertices
// the (1/6, 2/3, 1/6) B-spline mask, corners stay put. Normals are
// tangent1 x tangent2 with OpenSubdiv's tangent masks (sdc/loopScheme.h):
// at an interior crease they describe the surface in the counter-clockwise
// span from the first to the second crease edge of the ring.
//
// As in OpenSubdiv's PrimvarRefiner::Limit, a vertex's rule at this level
// decides its mask, so semi-sharp features still present count as sharp.
#pragma once

#include <memory>

#include <cmath>
#include <span>

#include "core/loop/level.h"
#include "core/util/vec3.h"

namespace tessera {

struct LimitFrame {
  Vec3 position;
  Vec3 tangent1;
  Vec3 tangent2;
  // Unit tangent1 x tangent2 (zero if degenerate). Inline so that the
  // square root of one vertex overlaps the arithmetic of the next.
  Vec3 normal() const {
    const Vec3 n = tangent1 % tangent2;
    const double len2 = n.sqrnorm();
    return len2 > 0.0 ? (1.0 / std::sqrt(len2)) * n : Vec3(0, 0, 0);
  }
};

LimitFrame limitFrame(const Level& level, Index v, std::span<const Vec3> points);

namespace detail {
class SmoothTables;
}

// limitFrame() for many vertices of one level, one at a time, with the
// per-valence tables built once (the incremental hierarchy's use).
class LimitEvaluator {
 public:
  explicit LimitEvaluator(const Level& level);
  ~LimitEvaluator();
  LimitFrame frame(Index v, std::span<const Vec3> points) const;

 private:
  const Level& level_;
  std::unique_ptr<const detail::SmoothTables> tables_;
};

// A sector of a vertex's ring between two consecutive sharp edges: ring faces
// firstFace .. firstFace + faceCount - 1 (modulo the valence), and the limit
// normal of the surface on that side.
struct LimitSector {
  int firstFace = 0;
  int faceCount = 0;
  Vec3 normal;
};

// The sectors of a crease or corner vertex other than the one that
// limitFrame()'s single normal describes (OpenSubdiv's choice). A crease is
// one-sided in its limit normal; these give the other sides their own, so a
// mesh can split vertices along creases and shade each side correctly.
// Smooth, dart and cusp vertices, and boundary creases, have none.
std::vector<LimitSector> otherLimitSectors(const Level& level, Index v, std::span<const Vec3> points);

// The side of v that ring face `ringFace` (its position in v's ring) lies
// on, numbered as a mesh splits the vertex: 0 for the sector limitFrame()
// describes (and for smooth, dart and cusp vertices, which have one side),
// 1 + j for otherLimitSectors()[j]. Topological: a triangle inside that
// face takes that side's copy whatever its shape.
int limitSideOfRingFace(const Level& level, Index v, int ringFace);

// Fills positions (and normals, if non-empty) for all vertices of the level.
void computeLimit(const Level& level, std::span<const Vec3> points, std::span<Vec3> positions,
                  std::span<Vec3> normals);

}  // namespace tessera

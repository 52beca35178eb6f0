// Limit positions and normals of every vertex of a level: the true limit of
// the Loop surface. Smooth vertices use the closed-form eigenvector masks
// (Loop '87); every other rule -- darts, creases, corners, cusps, and
// semi-sharp features that have not decayed at this level -- goes through
// the eigenstructure of its ring's subdivision matrix, after refining the
// ring until its rules stop changing (exact_limit.h, docs/LIMITS.md). Normals
// are tangent1 x tangent2; a crease or corner has one per sector between
// sharp edges.
//
// OpenSubdiv's PrimvarRefiner::Limit() instead applies the masks of the
// rules at the level (semi-sharp counts as infinitely sharp) and Hoppe et
// al.'s crease masks; the two agree at smooth vertices and at crease sectors
// of up to three faces (tests/oracle/limit_vs_osd_test.cc lists the rest).
#pragma once

#include <memory>

#include <cmath>
#include <span>

#include "core/loop/loop_options.h"
#include "core/topology/level.h"
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

class FarRingSharpness;  // local_ring.h

// `far` supplies the far rings Chaikin's decay reads where the level does
// not hold them (a sparse level, local_ring.h).
LimitFrame limitFrame(const Level& level, Index v, std::span<const Vec3> points,
                      CreaseMethod method = CreaseMethod::kUniform, const FarRingSharpness* far = nullptr);

namespace detail {
class SmoothTables;
}

// limitFrame() for many vertices of one level, one at a time, with the
// per-valence tables built once (the incremental hierarchy's use).
class LimitEvaluator {
 public:
  explicit LimitEvaluator(const Level& level, CreaseMethod method = CreaseMethod::kUniform,
                          const FarRingSharpness* far = nullptr);
  ~LimitEvaluator();
  LimitFrame frame(Index v, std::span<const Vec3> points) const;

 private:
  const Level& level_;
  CreaseMethod method_;
  const FarRingSharpness* far_;
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
std::vector<LimitSector> otherLimitSectors(const Level& level, Index v, std::span<const Vec3> points,
                                           CreaseMethod method = CreaseMethod::kUniform,
                                           const FarRingSharpness* far = nullptr);

// The side of v that ring face `ringFace` (its position in v's ring) lies
// on, numbered as a mesh splits the vertex: 0 for the sector limitFrame()
// describes (and for smooth, dart and cusp vertices, which have one side),
// 1 + j for otherLimitSectors()[j]. Topological: a triangle inside that
// face takes that side's copy whatever its shape.
int limitSideOfRingFace(const Level& level, Index v, int ringFace);

// Fills positions (and normals, if non-empty) for all vertices of the level.
void computeLimit(const Level& level, std::span<const Vec3> points, std::span<Vec3> positions,
                  std::span<Vec3> normals, CreaseMethod method = CreaseMethod::kUniform);

}  // namespace tessera

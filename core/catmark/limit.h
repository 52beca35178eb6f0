// Limit positions and normals of Catmull-Clark at every vertex of an all-quad
// level, with the masks of OpenSubdiv's PrimvarRefiner::Limit() (Sdc's
// catmarkScheme.h): smooth vertices by the eigenvector masks, crease
// vertices by the B-spline along the crease and Biermann et al.'s tangent
// across it into a span of one or two faces, corners at their control point
// with the plane of their first two edges. Where Limit()'s masks are not the
// surface's, its own neighbourhood's eigenvectors instead: a dart's limit
// and tangents (core/catmark/dart_masks.h), and the tangent across a crease
// into three faces or more (core/catmark/crease_span_tangent.h).
// Where a semi-sharp feature has not decayed, Limit()'s masks count it as
// sharp; the vertex's ring is refined until it has and the masks are taken
// there instead (core/catmark/semi_sharp_limit.h), which needs the
// document's crease options and, under Chaikin's decay on a sparse level,
// the far rings the level does not hold whole (FarRingSharpness).
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "core/catmark/polygon_level.h"
#include "core/loop/limit.h"
#include "core/topology/level.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera {

struct CatmarkLimitFrame {
  Vec3 position;
  Vec3 tangent1;
  Vec3 tangent2;
};

namespace detail {
class CatmarkTangentTables;
}
class FarRingSharpness;  // core/loop/local_ring.h

// catmarkLimitFrame for many vertices of one level, one at a time, with
// the tangent weights built once for the level's largest valence (the
// sparse hierarchy's use; one call builds them per vertex).
class CatmarkLimitEvaluator {
 public:
  // How many of the level's vertices frame() is asked for. For the whole
  // level, the constructor first looks once over the level's sharpness for
  // a semi-sharp value: without one, no vertex takes the decayed limit, and
  // frame() skips looking at each vertex's ring for one (a linear pass over
  // a few floats per edge, where a few vertices would not repay it).
  enum class Scope { kSomeVertices, kWholeLevel };
  // `far`, if given, outlives the evaluator.
  CatmarkLimitEvaluator(const Level& level, const CreaseOptions& options,
                        const FarRingSharpness* far = nullptr, Scope scope = Scope::kSomeVertices);
  ~CatmarkLimitEvaluator();
  CatmarkLimitFrame frame(Index v, std::span<const Vec3> points) const;

 private:
  const Level& level_;
  CreaseOptions options_;
  const FarRingSharpness* far_;
  std::unique_ptr<const detail::CatmarkTangentTables> tables_;
  bool mayDecay_;  // whether some vertex may have a semi-sharp feature
};

// One vertex of an all-quad level with full topology, or a complete vertex
// of a sparse level (core/hierarchy/sparse_level.h): it reads the vertex's
// ring, its ring faces' corners and its rules only.
CatmarkLimitFrame catmarkLimitFrame(const Level& level, Index v, std::span<const Vec3> points,
                                    const CreaseOptions& options, const FarRingSharpness* far = nullptr);

// The weight of vertex v's own control point in the limit mask
// catmarkLimitFrame uses (n/(n+5) smooth, the dart mask's at a dart, 2/3
// on a crease, 1 at a corner or a boundary vertex of one face, the decayed
// ring's where a semi-sharp feature acts): the limit position is affine in
// that point, so direct manipulation (Pulli & Lounsbery §2.2) solves for it
// in one step. Always > 0.
double catmarkSelfLimitWeight(const Level& level, Index v, const CreaseOptions& options,
                              const FarRingSharpness* far = nullptr);

// The sectors of a crease or corner vertex other than the one whose
// normal catmarkLimitFrame's tangents give (the ring faces after its first
// sharp edge, or for a corner the side holding ring face 0), numbered as
// catmarkLimitSideOfRingFace numbers a vertex's sides, each with its limit
// normal: a crease's other side by the same tangent across it, into that
// side; a corner's one-face side by its edges' limit curves. So a mesh
// splits the vertex along its sharp edges and shades each side as
// OpenSubdiv's Bfr evaluates that side's faces. Smooth and dart vertices,
// and boundary creases, have none. Where a semi-sharp feature has not
// decayed, the sides are those it leaves once it has
// (core/catmark/semi_sharp_limit.h), which `options` and `far` decide as
// for catmarkLimitFrame.
std::vector<LimitSector> catmarkOtherLimitSectors(const Level& level, Index v, std::span<const Vec3> points,
                                                  const CreaseOptions& options,
                                                  const FarRingSharpness* far = nullptr);

// The side of v that ring face `ringFace` (its position in v's ring) lies
// on: limitSideOfRingFace (core/loop/limit.h), or where a semi-sharp
// feature has not decayed, the side it lies on once it has. Topological.
int catmarkLimitSideOfRingFace(const Level& level, Index v, int ringFace, const CreaseOptions& options,
                               const FarRingSharpness* far = nullptr);

// Every vertex; `normals` may be empty. A level with a face that is not a
// quad is refused (refine it once first): the masks read each face's
// opposite corner. Where the tangents are parallel (a degenerate control
// net), the normal is the area-weighted normal of the adjacent faces.
Status computeCatmarkLimit(const Level& level, const CreaseOptions& options, std::span<const Vec3> points,
                           std::span<Vec3> positions, std::span<Vec3> normals);

}  // namespace tessera

// A small image-morph sample made procedurally (docs/INTERPOLATION.md): two 160 x 120
// images of a striped ring (a shape with a hole) on different backgrounds,
// a green dot in each at the same mesh vertex, and two annulus meshes of one
// connectivity over them, the second an affine image of the first (so no
// triangle folds). Used by the tests and by deploy/samples/make_morph_sample.sh.
#pragma once

#include <string>
#include <vector>

#include "core/io/png_image.h"
#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera::testing {

struct MorphSample {
  Image a, b;
  std::vector<Vec3> meshA, meshB;  // z = 0, pixel coordinates
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> interpolating;  // base vertices tagged in morph.tags
  int dotVertex = 0;               // the vertex the dots mark (interpolating)
  Vec3 holeA, holeB;               // the centre of the hole in each image
};

// `mirrored`: mesh B is a mirror image of mesh A (every triangle turns over).
MorphSample makeMorphSample(bool mirrored = false);

// Writes a.png, b.png, mesh_a.obj, mesh_b.obj and morph.tags into `dir`.
Status writeMorphSample(const MorphSample& sample, const std::string& dir);

}  // namespace tessera::testing

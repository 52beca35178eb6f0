// Bilinear subdivision's weights (OpenSubdiv's SCHEME_BILINEAR): every new
// point lies on the piecewise bilinear surface of the control mesh, so the
// mesh gets finer without changing shape. Pure functions, no mesh.
#pragma once

namespace tessera::bilinear {

// Face point: the centroid of the face's corners.
inline double facePointWeight(int faceSize) {
  return 1.0 / faceSize;
}
// Edge point: the midpoint.
inline constexpr double kEdgeEndWeight = 0.5;
// Vertex point: the vertex itself.
inline constexpr double kVertexWeight = 1.0;

}  // namespace tessera::bilinear

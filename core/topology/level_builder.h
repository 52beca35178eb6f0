// Builds a Level (level 0) from faces: edges in order of first use, ordered
// rings, and the checks that the faces form an oriented 2-manifold, as
// OpenSubdiv's Vtr::Level::completeTopologyFromFaceVertices and
// orderVertexFacesAndEdges do for every scheme. The Loop base level
// (core/loop/level_builder.h) and the polygon base level
// (core/catmark/polygon_level.h) are both built here; tags and the boundary
// rules come after, from applyTags (tags.h).
#pragma once

#include "core/topology/level.h"
#include "core/util/buffer.h"
#include "core/util/status.h"

namespace tessera::topology {

// Faces as compressed rows of corners, counter-clockwise.
struct FaceRows {
  int numVertices = 0;
  // When set, every face has this many corners: face f is corners
  // regularSize * f onward and offsets is unused.
  int regularSize = 0;
  Buffer<Index> offsets;  // otherwise numFaces + 1 row starts into corners
  Buffer<Index> corners;

  int numFaces() const {
    return regularSize ? static_cast<int>(corners.size()) / regularSize
                       : static_cast<int>(offsets.size()) - 1;
  }
};

// Errors (never asserts), each naming the face, edge or vertex: an empty
// mesh, faces with fewer than 3 corners or a repeated corner, out-of-range
// indices, unused vertices, non-manifold edges and vertices, and
// inconsistent orientation. The level has no sharpness yet (tags.h).
// A level whose faces all have one size stores no face offsets (level.h);
// a level of triangles also gets faceEdgeSides.
Expected<Level> buildLevel(FaceRows faces);

}  // namespace tessera::topology

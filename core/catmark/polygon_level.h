// Builds the base Level (level 0) of a polygon mesh with its feature tags
// and the boundary rules of OpenSubdiv's Far factory, through the one
// topology builder (core/topology/level_builder.h) and the one tag applier
// (core/topology/tags.h) that the Loop base level uses too.
#pragma once

#include <vector>

#include "core/loop/level_builder.h"
#include "core/loop/loop_options.h"
#include "core/mesh/base_mesh.h"
#include "core/mesh/polygon_soup.h"
#include "core/topology/level.h"
#include "core/topology/tags.h"
#include "core/util/status.h"

namespace tessera {

// OpenSubdiv's Sdc options that the crease rules of every scheme share; the
// Loop options are exactly these.
using CreaseOptions = LoopOptions;

struct PolyTopology {
  int numVertices = 0;
  // Face f uses indices[faceOffsets[f] .. faceOffsets[f+1]), counter-clockwise.
  std::vector<int> faceOffsets{0};
  std::vector<int> indices;
  using Crease = topology::Crease;
  std::vector<Crease> creases;
  std::vector<float> vertexSharpness;  // empty, or one per vertex

  int numFaces() const { return static_cast<int>(faceOffsets.size()) - 1; }
  int numFacesNotTriangles() const { return countFacesNotTriangles(faceOffsets); }
  void addFace(std::span<const int> face) {
    indices.insert(indices.end(), face.begin(), face.end());
    faceOffsets.push_back(static_cast<int>(indices.size()));
  }

  // Triangles and tags of a validated base mesh.
  static PolyTopology fromBaseMesh(const BaseMesh& mesh);
  // The same triangles and tags as polygons.
  static PolyTopology fromTriangles(BaseTopology triangles);
  // Faces of a soup as they are (no tags); buildPolyLevel validates them.
  static PolyTopology fromSoup(const PolygonSoup& soup);
};

// Errors (never asserts), each naming the face, edge or vertex: faces with
// fewer than 3 corners or a repeated corner, out-of-range indices, non-
// manifold edges and vertices, inconsistent orientation, unused vertices,
// and tags on missing edges or vertices.
Expected<Level> buildPolyLevel(const PolyTopology& topology, const CreaseOptions& options);

}  // namespace tessera

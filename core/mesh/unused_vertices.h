// Dropping the vertices no face uses (`--drop-unused`): scanned meshes often
// carry a few (the Stanford bunny has one), and a BaseMesh never does.
#pragma once

#include <vector>

#include "core/mesh/polygon_soup.h"

namespace tessera {

// How the file's vertex numbers map to the mesh's after dropping.
struct VertexRenumbering {
  // newIndex[fileIndex]: the vertex's index in the mesh, or -1 if dropped.
  // Empty when nothing was renumbered (the identity).
  std::vector<int> newIndex;
  int dropped = 0;

  bool isIdentity() const { return newIndex.empty(); }
  int fileVertexCount() const { return static_cast<int>(newIndex.size()); }
};

// Removes from `soup` every point no face names, keeping the others in order,
// and rewrites the faces' indices. Returns the renumbering: the identity when
// every point is used, or when a face names a vertex that does not exist (the
// soup is then left as the file numbers it, for validation to refuse).
VertexRenumbering dropUnusedVertices(PolygonSoup& soup);

}  // namespace tessera

// Validation of untrusted polygon soups into a BaseMesh.
//
// Rejects, with a message naming the source, the element and the reason:
// empty meshes, NaN/Inf coordinates, out-of-range indices, non-triangle faces
// (unless triangulate is set: polygon_triangulation.h, which also refuses
// polygons that cannot be triangulated), degenerate faces (repeated index or
// zero area), duplicate faces, non-manifold edges and vertices, inconsistently
// oriented neighbours, and vertices no face uses (see unused_vertices.h for
// dropping them first).
#pragma once

#include <string>

#include "core/mesh/base_mesh.h"
#include "core/mesh/polygon_soup.h"
#include "core/util/status.h"

namespace tessera {

struct BuildOptions {
  bool triangulate = false;  // triangulate polygons with more than 3 corners
};

// `sourceName` (usually the file path) prefixes every error message.
Expected<BaseMesh> buildBaseMesh(const PolygonSoup& soup, const BuildOptions& options,
                                 const std::string& sourceName);

}  // namespace tessera

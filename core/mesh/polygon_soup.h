// PolygonSoup: what a file reader produces before any validation -- points and
// polygons as raw indices, exactly as the file stated them. buildBaseMesh()
// (mesh_validation.h) is the only way from a soup to a BaseMesh.
#pragma once

#include <vector>

#include "core/util/vec3.h"

namespace tessera {

struct PolygonSoup {
  std::vector<Vec3> points;
  // Face i uses indices[faceOffsets[i] .. faceOffsets[i+1]); faceOffsets has
  // numFaces()+1 entries (a single 0 when there are no faces).
  std::vector<int> faceOffsets{0};
  std::vector<int> indices;

  int numFaces() const { return static_cast<int>(faceOffsets.size()) - 1; }
  void addFace(const std::vector<int>& face) {
    indices.insert(indices.end(), face.begin(), face.end());
    faceOffsets.push_back(static_cast<int>(indices.size()));
  }
};

}  // namespace tessera

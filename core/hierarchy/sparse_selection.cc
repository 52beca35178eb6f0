#include "core/hierarchy/sparse_selection.h"

#include <algorithm>
#include <utility>

namespace tessera {
namespace {

// Faces sharing a vertex with a flagged face, added to the flags. Every
// vertex of a flagged face must be complete (the nesting in the header).
void growByOneRing(const SparseLevel& level, Buffer<uint8_t>& faces) {
  const Level& m = level.mesh;
  Buffer<uint8_t> grown = faces;
  for (Index f = 0; f < m.numFaces(); ++f) {
    if (!faces[f]) continue;
    for (Index v : m.triangleVertices(f)) {
      for (Index g : m.ringFacesOf(v)) {
        if (g >= 0) grown[g] = 1;
      }
    }
  }
  faces.swap(grown);
}

// The local index of the ancestor of `face` at `level`, kNoIndex if the
// level does not hold it.
Index ancestorAt(const SparseLevel& level, FaceId face) {
  return level.findFace(face.index() >> (2 * (face.level() - level.depth)));
}

}  // namespace

bool SparseSelection::replaceEditDemand(std::set<FaceId> faces) {
  if (faces == editDemand_) return false;
  editDemand_ = std::move(faces);
  return true;
}

int SparseSelection::deepestDemand() const {
  int deepest = 0;
  for (FaceId f : demand_) deepest = std::max(deepest, f.level());
  for (FaceId f : extraDemand_) deepest = std::max(deepest, f.level());
  return deepest;
}

void SparseSelection::select(const SparseLevel& level, Buffer<uint8_t>& selected, Buffer<uint8_t>& refined,
                             Buffer<uint8_t>* editSelected) const {
  const int l = level.depth;
  const Index numFaces = level.mesh.numFaces();
  auto mark = [&](const std::set<FaceId>& demand, Buffer<uint8_t>& faces) {
    for (FaceId face : demand) {
      if (face.level() <= l) continue;
      const Index a = ancestorAt(level, face);
      if (a != kNoIndex) faces[a] = 1;
    }
  };
  if (editSelected != nullptr) {
    editSelected->assign(numFaces, 0);
    mark(editDemand_, *editSelected);
    growByOneRing(level, *editSelected);
  }
  if (l < uniformLevel_) {
    selected.assign(numFaces, 1);
    refined.assign(numFaces, 1);
    return;
  }
  selected.assign(numFaces, 0);
  mark(demand_, selected);
  mark(extraDemand_, selected);
  growByOneRing(level, selected);
  refined = selected;
  growByOneRing(level, refined);
}

bool SparseSelection::ancestorRingSelected(const SparseLevel& level, const Buffer<uint8_t>& selected,
                                           FaceId face) {
  const Index a = ancestorAt(level, face);
  if (a == kNoIndex) return false;
  for (Index v : level.mesh.triangleVertices(a)) {
    for (Index g : level.mesh.ringFacesOf(v)) {
      if (g >= 0 && !selected[g]) return false;
    }
  }
  return true;
}

Index SparseSelection::markAncestorRing(const SparseLevel& level, FaceId face,
                                        Buffer<uint8_t>& editSelected) {
  const Index a = ancestorAt(level, face);
  if (a == kNoIndex) return kNoIndex;
  bool marked = false;
  for (Index v : level.mesh.triangleVertices(a)) {
    for (Index g : level.mesh.ringFacesOf(v)) {
      if (g < 0 || editSelected[g]) continue;
      editSelected[g] = 1;
      marked = true;
    }
  }
  return marked ? a : kNoIndex;
}

}  // namespace tessera

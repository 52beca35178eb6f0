// Which quadtree nodes a LOD profile shows (Pulli & Lounsbery, "Hierarchical
// Editing and Rendering of Subdivision Surfaces" §3.1): a cut through the
// document's hierarchy. A node is split -- replaced by its four children --
// when
//   * its level is below the profile's base level;
//   * an edit needs it: the hierarchy made it a node for an edit (the 2-ring
//     of an edit at level l is shown at level l, §3.1.1), and with
//     `fidelity` the faces around an edited vertex go one level further;
//   * the limit normals at the ends of one of its edges differ by more than
//     the threshold (§3.1.2); a crease or corner end uses the normal of its
//     sector on this face's side, so the crease itself does not count;
//   * along a sharp edge, the crease tangents at its ends differ by more
//     than the threshold (§3.1.2, Color Plate 1(h));
// and its level is below the profile's maximum. A split decision reads only
// the limits at the node's corners, so an edit re-decides only the nodes
// around the vertices whose limits it changed.
#pragma once

#include <span>
#include <vector>

#include "core/document/document.h"
#include "core/tessellation/lod_profile.h"

namespace tessera {

class AdaptiveCut {
 public:
  // Decides every node top-down, growing the hierarchy where the profile
  // refines deeper than it holds.
  static Expected<AdaptiveCut> build(Document& doc, const LodProfile& profile);

  // False when the hierarchy was rebuilt since the cut was made (its local
  // indices changed): build a new cut.
  bool isCurrent(const SparseHierarchy& hierarchy) const;

  // Re-decides the nodes around the vertices whose limits changed. Returns
  // the nodes (level, local face) whose decision flipped, or an error-free
  // empty optional when the hierarchy had to grow (build a new cut).
  std::optional<std::vector<std::pair<int, Index>>> redecide(Document& doc, std::span<const VertexId> limits);

  int numLevels() const { return static_cast<int>(split_.size()); }
  bool isNode(const SparseHierarchy& h, int l, Index f) const {
    return l == 0 || split_[l - 1][h.level(l).parentOfFace(f)] != 0;
  }
  bool isSplit(int l, Index f) const { return split_[l][f] != 0; }
  const LodProfile& profile() const { return profile_; }

 private:
  explicit AdaptiveCut(const LodProfile& profile) : profile_(profile) {}

  bool wantsSplit(const SparseHierarchy& h, int l, Index f) const;
  bool normalsDisagree(const SparseHierarchy& h, int l, Index f) const;
  bool creaseTangentsDisagree(const SparseHierarchy& h, int l, Index f) const;
  bool aroundEditedVertex(const SparseHierarchy& h, int l, Index f) const;
  // Decides the subtree below a node that just became split.
  bool decideSubtree(Document& doc, int l, Index f, std::vector<std::pair<int, Index>>& flipped);
  void clearSubtree(const SparseHierarchy& h, int l, Index f);
  void markEditedVertices(const Document& doc);

  LodProfile profile_;
  double cosThreshold_ = 1.0;
  std::vector<Buffer<uint8_t>> split_;
  std::vector<uint64_t> generations_;
  std::vector<uint64_t> editedVertices_;  // packed ids of vertices an edit moves, sorted (fidelity)
  // Per level, per face: seen in this redecide (all zero between calls).
  std::vector<std::vector<uint8_t>> faceMarks_;
};

}  // namespace tessera

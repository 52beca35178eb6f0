// Which faces of the sparse hierarchy exist (Pulli & Lounsbery, "Hierarchical
// Editing and Rendering of Subdivision Surfaces" §4.1): the faces each level
// refines, decided from the faces demanded below it. OpenSubdiv keeps this
// decision apart from refinement in the same way (Vtr::SparseSelector).
//
// Every level up to the uniform level is whole. Below it, a face is a node
// with children (selected) when it lies in the 1-ring of an ancestor of a
// demanded face, and the faces refined at level k are the 1-ring of the
// selected ones: with Sel_k the selected faces, R_k = N1(Sel_k) and
// Sel_k = N1(ancestors at k of demanded faces). These nest (Sel_k+1 within
// the children of Sel_k, and N2 of a child face within the children of N1
// of its parent), so every vertex of a refined face is complete
// (sparse_hierarchy.h in core/document has the whole argument).
//
// Demand comes in three kinds: faces edits address or addressed (what the
// structure holds), faces the current edits address (what makes edit
// nodes), and faces tessellations refine. Which faces an edit addresses is
// the evaluator's to say; this class only turns demanded faces into
// selected faces, level by level.
#pragma once

#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "core/hierarchy/ids.h"
#include "core/hierarchy/sparse_level.h"
#include "core/util/buffer.h"

namespace tessera {

class SparseSelection {
 public:
  // Ancestors are found by `counts`' split (hierarchy/ids.h).
  SparseSelection(LevelCounts counts, int uniformLevel)
      : counts_(std::move(counts)), uniformLevel_(uniformLevel) {}

  int uniformLevel() const { return uniformLevel_; }
  void raiseUniformLevel(int level) { uniformLevel_ = level; }

  // A face an edit addresses: held from now on, and an edit node's reason
  // while the edit lasts. Returns whether it was not an edit's demand yet.
  bool demandForEdit(FaceId face) {
    hold(face);
    return editDemand_.insert(face).second;
  }
  // A face a tessellation refines.
  void demandForTessellation(FaceId face) { hold(face); }
  // The faces the current edits address, after an edit left for good: what
  // the structure grew for the others stays. Returns whether that changed
  // the edits' demand.
  bool replaceEditDemand(std::set<FaceId> faces);

  // The deepest level a face is demanded at (0 when none is).
  int deepestDemand() const { return deepest_; }

  // The selection of `level` grown by the demand held since it was last
  // grown (a level's demand is only ever added to, so its selection only
  // grows): flags what it adds in `selected` (resized to the level's faces),
  // sets `editSelected` (selectEdits), and returns the faces the next
  // level must refine that it does not refine yet, ascending. The cost
  // follows the new demand, not the level.
  std::vector<Index> growSelection(const SparseLevel& level, Buffer<uint8_t>& selected,
                                   Buffer<uint8_t>& editSelected);
  // Whether demand held since `level` was last grown waits there.
  bool hasFresh(int level) const;
  // `editSelected` of `level`, per face: a node with children because of
  // an edit (N1 of the ancestors there of the current edits' faces).
  void selectEdits(const SparseLevel& level, Buffer<uint8_t>& editSelected) const;

  // Whether the ancestor of `face` at `level` is present and every face of
  // its 1-ring is flagged in `selected` (what a demanded face adds to the
  // level's selection).
  bool ancestorRingSelected(const SparseLevel& level, const Buffer<uint8_t>& selected, FaceId face) const;
  // Flags the 1-ring of the ancestor of `face` at `level` in `editSelected`
  // in place (what select adds to editSelected for one more demanded face).
  // Returns the ancestor when that flagged a face that was not flagged yet,
  // kNoIndex otherwise.
  Index markAncestorRing(const SparseLevel& level, FaceId face, Buffer<uint8_t>& editSelected) const;

 private:
  // What the structure holds is kept per level, as the ancestors there of
  // every face held deeper: a level's selection is read from its own list,
  // whose length is at most the level's faces, however many faces below it
  // were demanded (a view asks for hundreds of thousands).
  struct Ancestors {
    std::vector<uint64_t> sorted;   // canonical face indices, ascending, unique
    std::vector<uint64_t> pending;  // added since, merged into `sorted` when read
    std::vector<uint64_t> fresh;    // merged into `sorted` since growSelection last read them
  };
  static void mergePending(Ancestors& a);
  void hold(FaceId face);
  // The local index of the ancestor of `face` at `level`, kNoIndex if the
  // level does not hold it.
  Index ancestorAt(const SparseLevel& level, FaceId face) const;

  LevelCounts counts_;
  int uniformLevel_ = 0;
  int deepest_ = 0;
  // Faces edits address or addressed and faces tessellations refine: what
  // the structure holds. Mutable: asking a level merges what is pending.
  mutable std::vector<Ancestors> held_;
  std::set<FaceId> editDemand_;  // faces the current edits address: what makes edit nodes
};

}  // namespace tessera

#include "core/hierarchy/sparse_selection.h"

#include <algorithm>
#include <utility>

namespace tessera {
namespace {

// Flags the faces sharing a vertex with the faces of `from` (all flagged
// already) and appends those newly flagged to `added`. Every vertex of a
// face in `from` must be complete (the nesting in the header).
// Each vertex's ring is read once, though about six faces of `from` share it.
void flagRings(const Level& m, const std::vector<Index>& from, Buffer<uint8_t>& faces,
               std::vector<Index>& added) {
  std::vector<uint8_t> seen(m.numVertices, 0);
  for (Index f : from) {
    for (Index v : m.faceVerticesOf(f)) {
      if (seen[v]) continue;
      seen[v] = 1;
      for (Index g : m.ringFacesOf(v)) {
        if (g >= 0 && !faces[g]) faces[g] = 1, added.push_back(g);
      }
    }
  }
}

// The local indices of the faces of `level` whose canonical indices are in
// `ids` (ascending), by one pass over both sorted lists, or by searching
// when `ids` is much the shorter; through the level's face order once it
// grew in place.
std::vector<Index> localFaces(const SparseLevel& level, const std::vector<uint64_t>& ids) {
  std::vector<Index> out;
  const auto& faceIds = level.faceIds;
  const auto& order = level.faceOrder;
  const size_t n = faceIds.size();
  auto idAt = [&](size_t i) { return faceIds[order.empty() ? i : static_cast<size_t>(order[i])]; };
  const bool search = ids.size() * 16 < n;
  size_t at = 0;
  for (uint64_t id : ids) {
    if (search) {
      size_t lo = at, hi = n;
      while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (idAt(mid) < id)
          lo = mid + 1;
        else
          hi = mid;
      }
      at = lo;
    } else {
      while (at < n && idAt(at) < id) ++at;
    }
    if (at == n) break;
    if (idAt(at) == id) out.push_back(order.empty() ? static_cast<Index>(at) : order[at]);
  }
  return out;
}

}  // namespace

Index SparseSelection::ancestorAt(const SparseLevel& level, FaceId face) const {
  return level.findFace(counts_.ancestorAt(face, level.depth).index());
}

bool SparseSelection::replaceEditDemand(std::set<FaceId> faces) {
  if (faces == editDemand_) return false;
  editDemand_ = std::move(faces);
  return true;
}

void SparseSelection::hold(FaceId face) {
  const int l = face.level();
  deepest_ = std::max(deepest_, l);
  if (static_cast<int>(held_.size()) < l) held_.resize(l);
  // Once a level holds the ancestor, every level above holds its own;
  // levels above the uniform one are whole, whatever is demanded.
  for (int k = l - 1; k >= uniformLevel_; --k) {
    const uint64_t ancestor = counts_.ancestorAt(face, k).index();
    const auto& sorted = held_[k].sorted;
    if (std::binary_search(sorted.begin(), sorted.end(), ancestor)) break;
    held_[k].pending.push_back(ancestor);
  }
}

void SparseSelection::mergePending(Ancestors& a) {
  if (a.pending.empty()) return;
  std::sort(a.pending.begin(), a.pending.end());
  a.pending.erase(std::unique(a.pending.begin(), a.pending.end()), a.pending.end());
  std::vector<uint64_t> added;
  std::set_difference(a.pending.begin(), a.pending.end(), a.sorted.begin(), a.sorted.end(),
                      std::back_inserter(added));
  a.pending.clear();
  a.fresh.insert(a.fresh.end(), added.begin(), added.end());
  const auto middle = static_cast<std::ptrdiff_t>(a.sorted.size());
  a.sorted.insert(a.sorted.end(), added.begin(), added.end());
  std::inplace_merge(a.sorted.begin(), a.sorted.begin() + middle, a.sorted.end());
}

bool SparseSelection::hasFresh(int level) const {
  if (level >= static_cast<int>(held_.size())) return false;
  mergePending(held_[level]);
  return !held_[level].fresh.empty();
}

void SparseSelection::selectEdits(const SparseLevel& level, Buffer<uint8_t>& editSelected) const {
  const int l = level.depth;
  editSelected.assign(level.mesh.numFaces(), 0);
  std::vector<Index> seeds, ring;
  for (FaceId face : editDemand_) {
    if (face.level() <= l) continue;
    const Index a = ancestorAt(level, face);
    if (a != kNoIndex && !editSelected[a]) editSelected[a] = 1, seeds.push_back(a);
  }
  flagRings(level.mesh, seeds, editSelected, ring);
}

std::vector<Index> SparseSelection::growSelection(const SparseLevel& level, Buffer<uint8_t>& selected,
                                                  Buffer<uint8_t>& editSelected) {
  const int l = level.depth;
  const Index numFaces = level.mesh.numFaces();
  selectEdits(level, editSelected);
  auto unrefined = [&](Index f) {
    return level.firstChildFace.empty() || level.firstChildFace[f] == kNoIndex;
  };
  std::vector<Index> toRefine;
  if (l < uniformLevel_) {
    if (l < static_cast<int>(held_.size())) mergePending(held_[l]), held_[l].fresh.clear();
    selected.assign(numFaces, 1);
    for (Index f = 0; f < numFaces; ++f) {
      if (unrefined(f)) toRefine.push_back(f);
    }
    return toRefine;
  }
  selected.resize(numFaces, 0);
  if (l >= static_cast<int>(held_.size())) return toRefine;
  Ancestors& a = held_[l];
  mergePending(a);
  if (a.fresh.empty()) return toRefine;
  std::sort(a.fresh.begin(), a.fresh.end());
  std::vector<Index> seeds = localFaces(level, a.fresh);
  a.fresh.clear();
  // Sel grows by N1 of the new ancestors, R by N1 of what Sel gained (the
  // header's nesting); a face selected or refined before keeps its flag.
  std::vector<Index> ring, fresh;
  for (Index f : seeds) {
    if (!selected[f]) selected[f] = 1, fresh.push_back(f);
  }
  flagRings(level.mesh, seeds, selected, ring);
  fresh.insert(fresh.end(), ring.begin(), ring.end());
  Buffer<uint8_t> refined(numFaces, 0);
  for (Index f : fresh) refined[f] = 1;
  std::vector<Index> outer;
  flagRings(level.mesh, fresh, refined, outer);
  fresh.insert(fresh.end(), outer.begin(), outer.end());
  for (Index f : fresh) {
    if (unrefined(f)) toRefine.push_back(f);
  }
  std::sort(toRefine.begin(), toRefine.end());
  toRefine.erase(std::unique(toRefine.begin(), toRefine.end()), toRefine.end());
  return toRefine;
}

bool SparseSelection::ancestorRingSelected(const SparseLevel& level, const Buffer<uint8_t>& selected,
                                           FaceId face) const {
  const Index a = ancestorAt(level, face);
  if (a == kNoIndex) return false;
  for (Index v : level.mesh.faceVerticesOf(a)) {
    for (Index g : level.mesh.ringFacesOf(v)) {
      if (g >= 0 && !selected[g]) return false;
    }
  }
  return true;
}

Index SparseSelection::markAncestorRing(const SparseLevel& level, FaceId face,
                                        Buffer<uint8_t>& editSelected) const {
  const Index a = ancestorAt(level, face);
  if (a == kNoIndex) return kNoIndex;
  bool marked = false;
  for (Index v : level.mesh.faceVerticesOf(a)) {
    for (Index g : level.mesh.ringFacesOf(v)) {
      if (g < 0 || editSelected[g]) continue;
      editSelected[g] = 1;
      marked = true;
    }
  }
  return marked ? a : kNoIndex;
}

}  // namespace tessera

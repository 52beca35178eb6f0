// Base faces grouped into clusters of neighbours, so that a region -- the
// unit of encoding, caching and re-sending -- holds enough triangles to
// amortize what each region costs on the wire (header, vertex ids' frame,
// checksum, Draco's own header: docs/REGION_ENCODING.md "Region groups").
// A dense scanned mesh shown at a coarse level has a few triangles per base
// face; one region per base face then costs several times the bytes of one
// Draco mesh of the same surface.
//
// Base faces are triangles (a Loop document) or polygons (Catmull-Clark);
// clusters count faces either way.
//
// Clusters are a function of the base topology and the cluster size alone:
// the same in every process, across edits, undos and restarts, so a
// region's id and extent never change while a document lives. Each is
// grown breadth-first over shared edges from the lowest-numbered face not
// yet taken, up to `size` faces (fewer where the faces left around it run
// out), and is named by that seed face.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/catmark/polygon_level.h"
#include "core/loop/level_builder.h"

namespace tessera {
class BaseFaceClusters;
}

namespace tessera::cluster_detail {
// Grows the clusters over the faces `corners(f)` gives (f < numFaces);
// `sameParent(f, g)` says whether g may join f's.
template <typename Corners, typename SameParent>
BaseFaceClusters grow(int numFaces, Corners corners, int size, SameParent sameParent);
}  // namespace tessera::cluster_detail

namespace tessera {

class BaseFaceClusters {
 public:
  // size >= 1; size 1 puts every face in a cluster of its own.
  static BaseFaceClusters build(const BaseTopology& base, int size);
  static BaseFaceClusters build(const PolyTopology& base, int size);
  // The same, each cluster grown only over faces of one cluster of
  // `within`: the clusters nest in those (a view's tiles, tile_tree.h).
  static BaseFaceClusters buildWithin(const BaseTopology& base, int size, const BaseFaceClusters& within);
  static BaseFaceClusters buildWithin(const PolyTopology& base, int size, const BaseFaceClusters& within);

  int size() const { return size_; }
  int numClusters() const { return static_cast<int>(seeds_.size()); }
  uint32_t clusterOf(int face) const { return clusterOf_[face]; }
  // The cluster's lowest-numbered face: its seed, and its region's id.
  int seedOf(uint32_t cluster) const { return seeds_[cluster]; }
  // Its faces, in ascending order.
  std::span<const int> facesOf(uint32_t cluster) const {
    return {faces_.data() + offsets_[cluster],
            static_cast<size_t>(offsets_[cluster + 1] - offsets_[cluster])};
  }

 private:
  template <typename Corners, typename SameParent>
  friend BaseFaceClusters cluster_detail::grow(int, Corners, int, SameParent);

  int size_ = 1;
  std::vector<uint32_t> clusterOf_;  // per face
  std::vector<int> seeds_;           // per cluster
  std::vector<int> offsets_;         // per cluster + 1, into faces_
  std::vector<int> faces_;
};

}  // namespace tessera

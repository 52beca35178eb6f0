#include "core/hierarchy/sparse_level.h"

#include <algorithm>

#include "core/hierarchy/sparse_split.h"

namespace tessera {

namespace {

template <typename T>
size_t bytesOf(const Buffer<T>& b) {
  return b.capacity() * sizeof(T);
}

Index findIn(const Buffer<uint64_t>& ids, const Buffer<Index>& order, uint64_t canonical) {
  if (order.empty()) {
    auto it = std::lower_bound(ids.begin(), ids.end(), canonical);
    return it != ids.end() && *it == canonical ? static_cast<Index>(it - ids.begin()) : kNoIndex;
  }
  auto it = std::lower_bound(order.begin(), order.end(), canonical,
                             [&](Index local, uint64_t id) { return ids[local] < id; });
  return it != order.end() && ids[*it] == canonical ? *it : kNoIndex;
}

}  // namespace

namespace sparse_split {

void mergeOrder(const Buffer<uint64_t>& ids, Index first, Buffer<Index>& order) {
  const auto n = static_cast<Index>(ids.size());
  if (first == n) return;
  if (order.empty()) {
    order.resize(first);
    for (Index i = 0; i < first; ++i) order[i] = i;
  }
  auto byId = [&](Index a, Index b) { return ids[a] < ids[b]; };
  const size_t middle = order.size();
  for (Index i = first; i < n; ++i) order.push_back(i);
  std::sort(order.begin() + static_cast<std::ptrdiff_t>(middle), order.end(), byId);
  std::inplace_merge(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(middle), order.end(), byId);
}

void orderIfUnsorted(const Buffer<uint64_t>& ids, Buffer<Index>& order) {
  order.clear();
  if (!std::is_sorted(ids.begin(), ids.end())) mergeOrder(ids, 0, order);
}

}  // namespace sparse_split

Index SparseLevel::findVertex(uint64_t canonical) const {
  return findIn(vertexIds, vertexOrder, canonical);
}
Index SparseLevel::findEdge(uint64_t canonical) const {
  return findIn(edgeIds, edgeOrder, canonical);
}
Index SparseLevel::findFace(uint64_t canonical) const {
  return findIn(faceIds, faceOrder, canonical);
}

size_t SparseLevel::memoryBytes() const {
  const Level& m = mesh;
  return bytesOf(m.faceVertices) + bytesOf(m.faceEdges) + bytesOf(m.edgeVertices) + bytesOf(m.edgeFaces) +
         bytesOf(m.edgeFaceLocal) + bytesOf(m.faceEdgeSides) + bytesOf(m.ringOffsets) + bytesOf(m.ringEdges) +
         bytesOf(m.ringVertices) + bytesOf(m.ringFaces) + bytesOf(m.ringFaceLocal) +
         bytesOf(m.edgeSharpness) + bytesOf(m.vertexSharpness) + bytesOf(m.vertexRules) + bytesOf(vertexIds) +
         bytesOf(edgeIds) + bytesOf(faceIds) + bytesOf(vertexOrder) + bytesOf(edgeOrder) +
         bytesOf(faceOrder) + bytesOf(complete) + bytesOf(origin) + bytesOf(originKind) +
         bytesOf(faceParent) + bytesOf(firstChildFace) + bytesOf(childOfVertex) + bytesOf(childOfEdge) +
         bytesOf(halvesOfEdge) + bytesOf(childOfFace);
}

SparseLevel sparseBaseLevel(Level base) {
  SparseLevel level;
  level.mesh = std::move(base);
  const Level& m = level.mesh;
  level.vertexIds.resize(m.numVertices);
  level.edgeIds.resize(m.numEdges());
  level.faceIds.resize(m.numFaces());
  for (Index v = 0; v < m.numVertices; ++v) level.vertexIds[v] = static_cast<uint64_t>(v);
  for (Index e = 0; e < m.numEdges(); ++e) level.edgeIds[e] = static_cast<uint64_t>(e);
  for (Index f = 0; f < m.numFaces(); ++f) level.faceIds[f] = static_cast<uint64_t>(f);
  level.complete.assign(m.numVertices, 1);
  level.firstChildFace.assign(m.numFaces(), kNoIndex);
  return level;
}

SparseLevel refineSparse(SparseLevel& parent, std::span<const uint8_t> refine, const LevelCounts& counts,
                         const LoopOptions& options) {
  return counts.quads() ? refineSparseQuads(parent, refine, counts, options)
                        : refineSparseTriangles(parent, refine, counts, options);
}

LevelExtension extendSparse(SparseLevel& parent, SparseLevel& child, std::span<const Index> faces,
                            const LevelCounts& counts, const LoopOptions& options) {
  return counts.quads() ? extendSparseQuads(parent, child, faces, counts, options)
                        : extendSparseTriangles(parent, child, faces, counts, options);
}

}  // namespace tessera

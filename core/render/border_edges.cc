#include "core/render/border_edges.h"

#include <bit>

namespace tessera {

namespace {

using Key = std::array<uint64_t, 6>;

// The edge's ends by position bits, the smaller first.
Key keyOf(const Vec3& a, const Vec3& b, bool* flipped) {
  *flipped = bitsLess(b, a);
  const Vec3& x = *flipped ? b : a;
  const Vec3& y = *flipped ? a : b;
  return {std::bit_cast<uint64_t>(x[0]), std::bit_cast<uint64_t>(x[1]), std::bit_cast<uint64_t>(x[2]),
          std::bit_cast<uint64_t>(y[0]), std::bit_cast<uint64_t>(y[1]), std::bit_cast<uint64_t>(y[2])};
}

uint64_t hashOf(const Key& k) {
  uint64_t h = 0x9E3779B97F4A7C15ull;
  for (uint64_t w : k) {
    h ^= w;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 31;
  }
  return h;
}

bool sameSide(const EdgeSide& a, const EdgeSide& b) {
  return bitsEqual(a.n0, b.n0) && bitsEqual(a.n1, b.n1);
}

EdgeSide flip(const EdgeSide& s) {
  return {s.n1, s.n0};
}

}  // namespace

void BorderEdges::reserve(size_t edges) {
  entries_.reserve(edges);
  size_t want = 16;
  while (want < 2 * edges) want *= 2;
  if (want > slots_.size()) {
    slots_.assign(want, -1);
    for (size_t i = 0; i < entries_.size(); ++i) slots_[find(entries_[i].key)] = static_cast<int32_t>(i);
  }
}

void BorderEdges::grow() {
  reserve(std::max<size_t>(16, entries_.size() * 2));
}

size_t BorderEdges::find(const Key& key) const {
  const size_t mask = slots_.size() - 1;
  for (size_t s = hashOf(key) & mask;; s = (s + 1) & mask)
    if (slots_[s] < 0 || entries_[slots_[s]].key == key) return s;
}

void BorderEdges::record(const Vec3& p0, const Vec3& p1, const EdgeSide& side) {
  if (2 * (entries_.size() + 1) > slots_.size()) grow();
  bool flipped = false;
  const Key key = keyOf(p0, p1, &flipped);
  const EdgeSide canonical = flipped ? flip(side) : side;
  const size_t s = find(key);
  if (slots_[s] < 0) {
    slots_[s] = static_cast<int32_t>(entries_.size());
    entries_.push_back({key, {canonical, {}}, 1});
    return;
  }
  Entry& e = entries_[slots_[s]];
  for (int i = 0; i < e.count; ++i)
    if (sameSide(e.side[i], canonical)) return;
  if (e.count < 2) e.side[e.count++] = canonical;
}

std::optional<EdgeSide> BorderEdges::other(const Vec3& p0, const Vec3& p1, const EdgeSide& mine) const {
  if (slots_.empty()) return std::nullopt;
  bool flipped = false;
  const Key key = keyOf(p0, p1, &flipped);
  const int32_t at = slots_[find(key)];
  if (at < 0) return std::nullopt;
  const Entry& e = entries_[at];
  const EdgeSide m = flipped ? flip(mine) : mine;
  for (int i = 0; i < e.count; ++i)
    if (!sameSide(e.side[i], m)) return flipped ? flip(e.side[i]) : e.side[i];
  return std::nullopt;
}

}  // namespace tessera

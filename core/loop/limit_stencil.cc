#include "core/loop/limit_stencil.h"

#include <deque>

namespace tessera {

namespace {

static_assert(sizeof(LimitStencilKey) == 4 * (2 + kMaxStencilValence), "the key has no padding");

// The words a key of valence n uses (header, vertex sharpness, n edges),
// mixed 64 bits at a time: the lookup runs once per non-smooth vertex, so
// it must cost a few multiplications, not a division or a long chain.
uint64_t hashOf(const LimitStencilKey& key) {
  const int words = 2 + key.valence();
  const auto* bytes = reinterpret_cast<const unsigned char*>(&key);
  uint64_t h = 0x9e3779b97f4a7c15ull;
  for (int w = 0; w < words; w += 2) {
    uint64_t chunk = 0;
    std::memcpy(&chunk, bytes + 4 * w, w + 1 < words ? 8 : 4);
    h = (h ^ chunk) * 0xff51afd7ed558ccdull;
  }
  return h ^ (h >> 32);
}

// Open addressing with linear probing in a power-of-two table at most half
// full: no division per lookup. Stencils live in a deque, so the pointers
// handed out stay valid for the thread's life (nothing is evicted).
struct Table {
  static constexpr size_t kSlots = 2 * kLimitStencilCacheEntries;
  static_assert((kSlots & (kSlots - 1)) == 0, "a power of two");
  struct Slot {
    uint64_t hash = 0;
    int32_t entry = -1;
  };
  std::vector<Slot> slots = std::vector<Slot>(kSlots);
  std::vector<LimitStencilKey> keys;
  std::deque<LimitStencil> stencils;
};

Table& table() {
  thread_local Table t;
  return t;
}

}  // namespace

bool limitStencilKey(const Level& level, Index v, LimitStencilKey& key) {
  const int n = level.valence(v);
  if (n > kMaxStencilValence) return false;
  key.header = static_cast<uint32_t>(n) | (level.isBoundaryVertex(v) ? 1u << 16 : 0u) |
               (static_cast<uint32_t>(level.vertexRules[v]) << 17);
  key.vertexSharpness = level.vertexSharpness[v];
  const Index* ringE = level.ringEdgesOf(v).data();
  for (int k = 0; k < n; ++k) key.edgeSharpness[k] = level.edgeSharpness[ringE[k]];
  return true;
}

const LimitStencil* findLimitStencil(const LimitStencilKey& key) {
  Table& t = table();
  const uint64_t h = hashOf(key);
  for (size_t i = h & (Table::kSlots - 1);; i = (i + 1) & (Table::kSlots - 1)) {
    const Table::Slot& slot = t.slots[i];
    if (slot.entry < 0) return nullptr;
    if (slot.hash == h && t.keys[slot.entry] == key) return &t.stencils[slot.entry];
  }
}

const LimitStencil* insertLimitStencil(const LimitStencilKey& key, LimitStencil stencil) {
  Table& t = table();
  if (t.stencils.size() >= kLimitStencilCacheEntries) return nullptr;
  const uint64_t h = hashOf(key);
  size_t i = h & (Table::kSlots - 1);
  while (t.slots[i].entry >= 0) {
    if (t.slots[i].hash == h && t.keys[t.slots[i].entry] == key) return &t.stencils[t.slots[i].entry];
    i = (i + 1) & (Table::kSlots - 1);
  }
  t.slots[i] = {h, static_cast<int32_t>(t.stencils.size())};
  t.keys.push_back(key);
  t.stencils.push_back(std::move(stencil));
  return &t.stencils.back();
}

}  // namespace tessera

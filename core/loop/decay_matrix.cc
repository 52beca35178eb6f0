#include "core/loop/decay_matrix.h"

#include <cstring>
#include <string>
#include <unordered_map>

#include "core/mesh/sharpness.h"

namespace tessera {

namespace {

// The configuration as bytes: everything refineLocalRing reads besides the
// points. Float sharpness goes in bit for bit, so two rings share a matrix
// only if every step would take the same branches with the same weights.
void appendWord(std::string& key, uint32_t word) {
  key.append(reinterpret_cast<const char*>(&word), sizeof word);
}

void appendFloat(std::string& key, float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  appendWord(key, bits);
}

// The same bytes read from the level, so that a cache hit gathers nothing
// but the ring's points (gatherLocalRing fills the far rings for semi-sharp
// edges only, and so does this).
void configurationKey(const Level& level, Index v, CreaseMethod method, const FarRingSharpness* farRings,
                      std::string& key) {
  const int n = level.valence(v);
  key.clear();
  appendWord(key, static_cast<uint32_t>(n) | (level.isBoundaryVertex(v) ? 1u << 16 : 0u) |
                      (static_cast<uint32_t>(level.vertexRules[v]) << 17) |
                      (static_cast<uint32_t>(method) << 24));
  appendFloat(key, level.vertexSharpness[v]);
  auto ringE = level.ringEdgesOf(v);
  for (int k = 0; k < n; ++k) appendFloat(key, level.edgeSharpness[ringE[k]]);
  if (method != CreaseMethod::kChaikin) return;
  // Chaikin's decay at an edge's far end reads that vertex's ring.
  thread_local std::vector<float> far;
  auto ringV = level.ringVerticesOf(v);
  for (int k = 0; k < n; ++k) {
    if (!isSemiSharp(level.edgeSharpness[ringE[k]])) {
      appendWord(key, 0);
      continue;
    }
    farRingSharpness(level, ringV[k], farRings, far);
    appendWord(key, static_cast<uint32_t>(far.size()));
    for (float s : far) appendFloat(key, s);
  }
}

// m . W for a mask m over the stationary ring: the same mask over the
// original ring.
std::vector<double> composeMask(const std::vector<double>& mask, const std::vector<double>& weights,
                                int size) {
  std::vector<double> out(size, 0.0);
  for (int i = 0; i < size; ++i) {
    if (mask[i] == 0.0) continue;
    for (int j = 0; j < size; ++j) out[j] += mask[i] * weights[static_cast<size_t>(i) * size + j];
  }
  return out;
}

void composeMasks(DecayMatrix& decay) {
  const int size = decay.valence + 1;
  const auto held = stationaryMasks({decay.valence, decay.boundary, decay.rule, decay.sharpEdges});
  const StationaryMasks& stationary = *held;
  decay.composed.position = composeMask(stationary.position, decay.weights, size);
  decay.composed.sectors = stationary.sectors;
  decay.composedSuffices = true;
  for (SectorMasks& sector : decay.composed.sectors) {
    sector.tangent1 = composeMask(sector.tangent1, decay.weights, size);
    if (!sector.tangent2.empty()) sector.tangent2 = composeMask(sector.tangent2, decay.weights, size);
    decay.composedSuffices = decay.composedSuffices && sector.normalIsCrossProduct();
  }
}

}  // namespace

void DecayMatrix::apply(std::span<const Vec3> points, std::vector<Vec3>& out) const {
  const int size = valence + 1;
  out.resize(size);
  const double* row = weights.data();
  for (int i = 0; i < size; ++i, row += size) {
    Vec3 sum(0, 0, 0);
    for (int j = 0; j < size; ++j) {
      if (row[j] != 0.0) sum += row[j] * points[j];
    }
    out[i] = sum;
  }
}

DecayMatrix computeDecayMatrix(const LocalRing& ring, CreaseMethod method) {
  const int size = ring.valence + 1;
  DecayMatrix out;
  out.valence = ring.valence;
  out.weights.assign(static_cast<size_t>(size) * size, 0.0);
  // Three columns at a time: unit points in x, y and z of columns c..c+2
  // give those columns of the composed matrix.
  LocalRing rings[2];
  for (int c = 0; c < size; c += 3) {
    rings[0] = ring;
    for (int j = 0; j < size; ++j) {
      rings[0].points[j] = Vec3(j == c ? 1.0 : 0.0, j == c + 1 ? 1.0 : 0.0, j == c + 2 ? 1.0 : 0.0);
    }
    const int steps = refineUntilStationary(rings, method);
    const LocalRing& last = rings[steps % 2];
    for (int i = 0; i < size; ++i) {
      for (int d = 0; d < 3 && c + d < size; ++d)
        out.weights[static_cast<size_t>(i) * size + c + d] = last.points[i][d];
    }
    if (c == 0) {
      out.steps = steps;
      out.boundary = last.boundary;
      out.rule = last.rule;
      out.sharpEdges.resize(ring.valence);
      for (int k = 0; k < ring.valence; ++k) out.sharpEdges[k] = isSharp(last.edgeSharpness[k]);
    }
  }
  composeMasks(out);
  return out;
}

const DecayMatrix* cachedDecayMatrix(const Level& level, Index v, std::span<const Vec3> points,
                                     CreaseMethod method, const FarRingSharpness* far) {
  // Per thread, so a lookup takes no lock; entries are never evicted, so
  // the pointers stay valid for the thread's life.
  thread_local std::unordered_map<std::string, DecayMatrix> cache;
  thread_local std::string key;
  configurationKey(level, v, method, far, key);
  auto it = cache.find(key);
  if (it != cache.end()) return &it->second;
  if (cache.size() >= kDecayMatrixCacheEntries) return nullptr;
  const LocalRing ring = gatherLocalRing(level, v, points, method, far);
  return &cache.emplace(key, computeDecayMatrix(ring, method)).first->second;
}

}  // namespace tessera

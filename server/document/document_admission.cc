#include "server/document/document_admission.h"

#include <algorithm>

namespace tessera::server {

namespace {

// The triangles of uniform level `level` (<= the counts' deepest): Loop's
// faces, or each quad's two (a polygon of n corners at a Catmull-Clark
// base, n - 2).
int64_t trianglesAt(const LevelCounts& counts, int level) {
  const int64_t faces = static_cast<int64_t>(counts.faces(level));
  if (!counts.quads()) return faces;
  return level == 0 ? static_cast<int64_t>(counts.corners(0)) - 2 * faces : 2 * faces;
}

}  // namespace

int64_t uniformTriangles(const LevelCounts& counts, uint32_t level) {
  if (level > static_cast<uint32_t>(counts.maxLevel())) {
    // Beyond the counts: four times per level, saturating.
    int64_t t = trianglesAt(counts, counts.maxLevel());
    for (uint32_t l = static_cast<uint32_t>(counts.maxLevel()); l < level && t < (INT64_MAX >> 2); ++l)
      t *= 4;
    return t;
  }
  return trianglesAt(counts, static_cast<int>(level));
}

int64_t minimumTriangles(const LevelCounts& counts, const wire::LodProfile& profile) {
  return uniformTriangles(counts, std::min<uint32_t>(profile.base_level(), 64));
}

int64_t maximumTriangles(const LevelCounts& counts, const wire::LodProfile& profile, const Limits& limits) {
  const int64_t budget =
      profile.triangle_budget() == 0
          ? limits.maxTrianglesPerSubscriber
          : static_cast<int64_t>(std::min<uint64_t>(profile.triangle_budget(),
                                                    static_cast<uint64_t>(limits.maxTrianglesPerSubscriber)));
  return std::min(budget, uniformTriangles(counts, std::min<uint32_t>(profile.max_level(), 64)));
}

Lane laneFor(int64_t triangles, const ServerConfig& config) {
  return triangles > config.bulkTriangles ? Lane::kBulk : Lane::kInteractive;
}

}  // namespace tessera::server

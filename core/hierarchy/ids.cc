#include "core/hierarchy/ids.h"

#include <charconv>

namespace tessera {

namespace {

template <typename Id>
Expected<Id> parseId(const std::string& text, char kind, const char* name) {
  const std::string form = std::string("'") + kind + "LEVEL:INDEX'";
  if (text.size() < 4 || text[0] != kind) {
    return parseError(std::string(name) + " id '" + text + "' must look like " + form);
  }
  const auto colon = text.find(':');
  if (colon == std::string::npos) return parseError(std::string(name) + " id '" + text + "' has no ':'");
  int level = -1;
  uint64_t index = 0;
  const char* begin = text.data() + 1;
  const char* mid = text.data() + colon;
  const char* end = text.data() + text.size();
  auto [p1, e1] = std::from_chars(begin, mid, level);
  auto [p2, e2] = std::from_chars(mid + 1, end, index);
  if (e1 != std::errc() || p1 != mid || begin == mid || e2 != std::errc() || p2 != end || mid + 1 == end) {
    return parseError(std::string(name) + " id '" + text + "' must look like " + form);
  }
  if (level < 0 || level > kMaxIdLevel) {
    return parseError(std::string(name) + " id '" + text + "': level must be 0.." +
                      std::to_string(kMaxIdLevel));
  }
  if (index > Id::kIndexMask) return parseError(std::string(name) + " id '" + text + "': index too large");
  return Id(level, index);
}

}  // namespace

Expected<VertexId> parseVertexId(const std::string& text) {
  return parseId<VertexId>(text, 'v', "vertex");
}
Expected<EdgeId> parseEdgeId(const std::string& text) {
  return parseId<EdgeId>(text, 'e', "edge");
}
Expected<FaceId> parseFaceId(const std::string& text) {
  return parseId<FaceId>(text, 'f', "face");
}

LevelCounts::LevelCounts(uint64_t vertices, uint64_t edges, uint64_t faces, int maxLevel) {
  counts_.push_back({vertices, edges, faces});
  for (int l = 0; l < maxLevel; ++l) {
    const auto& c = counts_.back();
    counts_.push_back({c[0] + c[1], 2 * c[1] + 3 * c[2], 4 * c[2]});
  }
}

namespace {

template <typename Id>
Status checkId(Id id, int maxLevel, uint64_t count, const char* what) {
  if (id.level() > maxLevel) {
    return notFound(id.toString() + ": level " + std::to_string(id.level()) + " is above the maximum level " +
                    std::to_string(maxLevel));
  }
  if (id.index() >= count) {
    return notFound(id.toString() + ": level " + std::to_string(id.level()) + " has " +
                    std::to_string(count) + " " + what);
  }
  return Status::ok();
}

}  // namespace

Status LevelCounts::check(VertexId id) const {
  return checkId(id, maxLevel(), id.level() <= maxLevel() ? vertices(id.level()) : 0, "vertices");
}
Status LevelCounts::check(EdgeId id) const {
  return checkId(id, maxLevel(), id.level() <= maxLevel() ? edges(id.level()) : 0, "edges");
}
Status LevelCounts::check(FaceId id) const {
  return checkId(id, maxLevel(), id.level() <= maxLevel() ? faces(id.level()) : 0, "faces");
}

int LevelCounts::birthLevel(VertexId id) const {
  // A vertex keeps its index on the way down, so it was born at the first
  // level whose vertex count exceeds its index.
  int level = 0;
  while (vertices(level) <= id.index()) ++level;
  return level;
}

}  // namespace tessera

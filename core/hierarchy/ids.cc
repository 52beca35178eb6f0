#include "core/hierarchy/ids.h"

#include <algorithm>
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
  counts_.push_back({vertices, edges, faces, 3 * faces});
  for (int l = 0; l < maxLevel; ++l) {
    const auto& c = counts_.back();
    counts_.push_back({c[0] + c[1], 2 * c[1] + 3 * c[2], 4 * c[2], 12 * c[2]});
  }
}

LevelCounts LevelCounts::quads(uint64_t vertices, uint64_t edges, std::span<const int> faceSizes,
                               int maxLevel) {
  auto begin = std::make_shared<std::vector<uint64_t>>(faceSizes.size() + 1, 0);
  for (size_t f = 0; f < faceSizes.size(); ++f)
    (*begin)[f + 1] = (*begin)[f] + static_cast<uint64_t>(faceSizes[f]);
  LevelCounts counts(0, 0, 0, 0);
  counts.split_ = SplitKind::kQuads;
  counts.counts_ = {{vertices, edges, faceSizes.size(), begin->back()}};
  for (int l = 0; l < maxLevel; ++l) {
    const auto& c = counts.counts_.back();
    counts.counts_.push_back({c[0] + c[2] + c[1], 2 * c[1] + c[3], c[3], 4 * c[3]});
  }
  counts.baseFaceBegin_ = std::move(begin);
  return counts;
}

LevelCounts::Origin LevelCounts::originOf(VertexId id) const {
  const uint64_t parentVertices = vertices(id.level() - 1);
  if (id.index() < parentVertices) return Origin::kVertex;
  if (quads() && id.index() < parentVertices + faces(id.level() - 1)) return Origin::kFace;
  return Origin::kEdge;
}

uint64_t LevelCounts::firstChildFace(FaceId id) const {
  if (quads() && id.level() == 0) return (*baseFaceBegin_)[id.index()];
  return 4 * id.index();
}

int LevelCounts::faceSize(FaceId id) const {
  if (!quads()) return 3;
  if (id.level() > 0) return 4;
  return static_cast<int>((*baseFaceBegin_)[id.index() + 1] - (*baseFaceBegin_)[id.index()]);
}

namespace {

// The base face whose corner row holds `corner`.
uint64_t baseFaceOfCorner(const std::vector<uint64_t>& begin, uint64_t corner) {
  const auto it = std::upper_bound(begin.begin(), begin.end(), corner);
  return static_cast<uint64_t>(it - begin.begin()) - 1;
}

}  // namespace

FaceId LevelCounts::parentFace(FaceId id) const {
  if (quads() && id.level() == 1) return {0, baseFaceOfCorner(*baseFaceBegin_, id.index())};
  return {id.level() - 1, id.index() / 4};
}

FaceId LevelCounts::ancestorAt(FaceId id, int level) const {
  if (level == 0) return baseFace(id);
  return {level, id.index() >> (2 * (id.level() - level))};
}

std::pair<uint64_t, uint64_t> LevelCounts::descendantsAt(FaceId id, int level) const {
  if (level == id.level()) return {id.index(), id.index() + 1};
  if (quads() && id.level() == 0) {
    const int shift = 2 * (level - 1);
    return {(*baseFaceBegin_)[id.index()] << shift, (*baseFaceBegin_)[id.index() + 1] << shift};
  }
  const int shift = 2 * (level - id.level());
  return {id.index() << shift, (id.index() + 1) << shift};
}

FaceId LevelCounts::baseFace(FaceId id) const {
  if (!quads()) return {0, id.index() >> (2 * id.level())};
  if (id.level() == 0) return id;
  return {0, baseFaceOfCorner(*baseFaceBegin_, id.index() >> (2 * (id.level() - 1)))};
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

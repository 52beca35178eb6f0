#include "core/morph/morph.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/loop/ghost_ring.h"

namespace tessera {

namespace {

std::string triangleText(const std::array<int, 3>& t) {
  return "(" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " + std::to_string(t[2]) + ")";
}

// What one key holds once its edit history is resolved: the values a morph
// interpolates.
struct KeyState {
  std::map<uint64_t, Vec3> offsets;  // packed VertexId -> summed local offset
  std::map<uint64_t, float> edgeTags, vertexTags;
  std::map<uint64_t, InterpolationEdit> interpolating;
  std::map<std::pair<int, int>, float> baseCreases;
  std::vector<float> baseCorners;
};

KeyState stateOf(const Document& doc) {
  KeyState s;
  for (const Edit& edit : doc.edits()) {
    if (!edit.active) continue;
    if (const auto* m = std::get_if<MoveEdit>(&edit.change)) {
      for (const VertexOffset& o : m->offsets) s.offsets[o.vertex.packed()] += o.localOffset;
    } else if (const auto* e = std::get_if<EdgeSharpnessEdit>(&edit.change)) {
      s.edgeTags[e->edge.packed()] = e->sharpness;
    } else if (const auto* v = std::get_if<VertexSharpnessEdit>(&edit.change)) {
      s.vertexTags[v->vertex.packed()] = v->sharpness;
    } else if (const auto* t = std::get_if<InterpolationEdit>(&edit.change)) {
      if (t->interpolating) {
        s.interpolating[t->vertex.packed()] = *t;
      } else {
        s.interpolating.erase(t->vertex.packed());
      }
    }
  }
  for (const auto& c : doc.baseTopology().creases)
    s.baseCreases[{std::min(c.v0, c.v1), std::max(c.v0, c.v1)}] = c.sharpness;
  s.baseCorners = doc.baseTopology().vertexSharpness;
  s.baseCorners.resize(doc.baseTopology().numVertices, 0.0f);
  return s;
}

// (1 - s) a + s b: exactly a at s = 0 and b at s = 1.
Vec3 lerp(const Vec3& a, const Vec3& b, double s) {
  return (1 - s) * a + s * b;
}
double lerp(double a, double b, double s) {
  return (1 - s) * a + s * b;
}

template <typename Value>
Value valueOr(const std::map<uint64_t, Value>& m, uint64_t key, Value fallback) {
  auto it = m.find(key);
  return it == m.end() ? fallback : it->second;
}

// The same elements in both keys, or an error naming the first that is not.
template <typename Value, typename Name>
Status sameKeys(const std::map<uint64_t, Value>& a, const std::map<uint64_t, Value>& b, size_t ka, size_t kb,
                const char* what, Name name) {
  for (int side = 0; side < 2; ++side) {
    const auto& from = side == 0 ? a : b;
    const auto& to = side == 0 ? b : a;
    for (const auto& [id, value] : from) {
      if (to.count(id) == 0) {
        return invalidArgument(name(id) + " has " + what + " in key " + std::to_string(side == 0 ? ka : kb) +
                               " but not in key " + std::to_string(side == 0 ? kb : ka) +
                               " (a morph interpolates values, so every key must have it)");
      }
    }
  }
  return Status::ok();
}

}  // namespace

Status checkMorphScheme(const Document& key, const std::string& name) {
  if (key.scheme() == DocumentScheme::kLoop) return Status::ok();
  return invalidArgument(name + " is a " + documentSchemeName(key.scheme()) +
                         " document: morph keys are Loop documents");
}

Status checkSameConnectivity(const BaseTopology& a, const BaseTopology& b, const std::string& nameA,
                             const std::string& nameB) {
  if (a.numVertices != b.numVertices) {
    return invalidArgument(nameB + " has " + std::to_string(b.numVertices) + " vertices, " + nameA + " has " +
                           std::to_string(a.numVertices) + ": a morph needs one connectivity");
  }
  if (a.triangles.size() != b.triangles.size()) {
    return invalidArgument(nameB + " has " + std::to_string(b.triangles.size()) + " triangles, " + nameA +
                           " has " + std::to_string(a.triangles.size()) + ": a morph needs one connectivity");
  }
  for (size_t f = 0; f < a.triangles.size(); ++f) {
    if (a.triangles[f] != b.triangles[f]) {
      return invalidArgument("triangle " + std::to_string(f) + " is " + triangleText(a.triangles[f]) +
                             " in " + nameA + " but " + triangleText(b.triangles[f]) + " in " + nameB +
                             ": a morph needs one connectivity");
    }
  }
  return Status::ok();
}

Morph::Morph(std::vector<Document> keys, std::vector<double> times)
    : keys_(std::move(keys)), times_(std::move(times)) {}

Expected<Morph> Morph::create(std::vector<Document> keys, std::vector<double> times) {
  if (keys.size() < 2)
    return invalidArgument("a morph needs at least two keys, got " + std::to_string(keys.size()));
  if (times.empty()) {
    for (size_t k = 0; k < keys.size(); ++k)
      times.push_back(static_cast<double>(k) / static_cast<double>(keys.size() - 1));
  }
  if (times.size() != keys.size()) {
    return invalidArgument(std::to_string(keys.size()) + " keys but " + std::to_string(times.size()) +
                           " times");
  }
  for (size_t k = 0; k < keys.size(); ++k) {
    if (!std::isfinite(times[k]) || (k > 0 && !(times[k] > times[k - 1]))) {
      return invalidArgument("key times must be finite and strictly increasing (key " + std::to_string(k) +
                             ")");
    }
  }
  for (size_t k = 0; k < keys.size(); ++k)
    TESSERA_RETURN_IF_ERROR(checkMorphScheme(keys[k], "key " + std::to_string(k)));
  const Document& first = keys[0];
  for (size_t k = 1; k < keys.size(); ++k) {
    const std::string name = "key " + std::to_string(k);
    TESSERA_RETURN_IF_ERROR(
        checkSameConnectivity(first.baseTopology(), keys[k].baseTopology(), "key 0", name));
    const DocumentOptions& a = first.options();
    const DocumentOptions& b = keys[k].options();
    if (a.maxLevel != b.maxLevel || a.loop.creaseMethod != b.loop.creaseMethod ||
        a.loop.boundary != b.loop.boundary) {
      return invalidArgument(
          name + " has other document options (max level, crease method or boundary rule) than key 0");
    }
  }
  return Morph(std::move(keys), std::move(times));
}

Status Morph::setPath(uint32_t v, const TcbParams& params) {
  if (static_cast<int>(v) >= keys_[0].baseTopology().numVertices) {
    return notFound("base vertex " + std::to_string(v) + " does not exist");
  }
  for (double x : {params.tension, params.continuity, params.bias}) {
    if (!(x >= -1 && x <= 1)) return invalidArgument("Kochanek-Bartels parameters must be in [-1, 1]");
  }
  paths_[v] = params;
  return Status::ok();
}

std::pair<size_t, double> Morph::segment(double t) const {
  t = std::clamp(t, times_.front(), times_.back());
  size_t k = 0;
  while (k + 2 < times_.size() && t >= times_[k + 1]) ++k;
  return {k, (t - times_[k]) / (times_[k + 1] - times_[k])};
}

// Kochanek & Bartels 1984, eq. 8-9 with their adjustment for keys unevenly
// spaced in time; a cubic Hermite piece between keys k and k+1.
Vec3 Morph::pointAt(uint32_t v, double t) const {
  const auto [k, s] = segment(t);
  auto p = [&](size_t i) { return keys_[i].basePoints()[v]; };
  auto it = paths_.find(v);
  if (it == paths_.end() || keys_.size() == 2) return lerp(p(k), p(k + 1), s);
  const TcbParams& c = it->second;
  const size_t n = keys_.size();
  const Vec3 p0 = p(k), p1 = p(k + 1);
  const Vec3 before = k > 0 ? p0 - p(k - 1) : p1 - p0;
  const Vec3 after = k + 2 < n ? p(k + 2) - p1 : p1 - p0;
  const Vec3 span = p1 - p0;
  const double T = c.tension, C = c.continuity, B = c.bias;
  Vec3 out = 0.5 * (1 - T) * ((1 + C) * (1 + B) * before + (1 - C) * (1 - B) * span);
  Vec3 in = 0.5 * (1 - T) * ((1 - C) * (1 + B) * span + (1 + C) * (1 - B) * after);
  const double dt = times_[k + 1] - times_[k];
  if (k > 0) out *= 2 * dt / (times_[k] - times_[k - 1] + dt);
  if (k + 2 < n) in *= 2 * dt / (dt + times_[k + 2] - times_[k + 1]);
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * out + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * in;
}

Expected<Document> Morph::at(double t) const {
  if (!std::isfinite(t)) return invalidArgument("morph time must be finite");
  const auto [k, s] = segment(t);
  const KeyState a = stateOf(keys_[k]), b = stateOf(keys_[k + 1]);
  auto vertexName = [](uint64_t id) { return VertexId::fromPacked(id).toString(); };
  auto edgeName = [](uint64_t id) { return EdgeId::fromPacked(id).toString(); };
  TESSERA_RETURN_IF_ERROR(sameKeys(a.edgeTags, b.edgeTags, k, k + 1, "a sharpness edit", edgeName));
  TESSERA_RETURN_IF_ERROR(
      sameKeys(a.vertexTags, b.vertexTags, k, k + 1, "a vertex sharpness edit", vertexName));
  TESSERA_RETURN_IF_ERROR(
      sameKeys(a.interpolating, b.interpolating, k, k + 1, "an interpolating tag", vertexName));

  BaseTopology topology = keys_[0].baseTopology();
  std::map<std::pair<int, int>, float> creases = a.baseCreases;
  for (const auto& [edge, sharpness] : b.baseCreases) creases.emplace(edge, 0.0f);
  topology.creases.clear();
  for (const auto& [edge, unused] : creases) {
    const auto fa = a.baseCreases.find(edge), fb = b.baseCreases.find(edge);
    const float sa = fa == a.baseCreases.end() ? 0.0f : fa->second,
                sb = fb == b.baseCreases.end() ? 0.0f : fb->second;
    const float blended = static_cast<float>(lerp(sa, sb, s));
    if (blended > 0) topology.creases.push_back({edge.first, edge.second, blended});
  }
  topology.vertexSharpness.resize(topology.numVertices);
  for (int v = 0; v < topology.numVertices; ++v) {
    topology.vertexSharpness[v] = static_cast<float>(lerp(a.baseCorners[v], b.baseCorners[v], s));
  }
  std::vector<Vec3> points(topology.numVertices);
  for (int v = 0; v < topology.numVertices; ++v) points[v] = pointAt(static_cast<uint32_t>(v), t);

  std::vector<Edit> edits;
  uint64_t id = 1;
  auto add = [&](auto change) { edits.push_back(Edit{EditId{id++}, true, std::move(change)}); };
  std::map<int, MoveEdit> moves;  // one per level: a move names vertices of one level
  std::map<uint64_t, Vec3> offsets = a.offsets;
  for (const auto& [v, o] : b.offsets) offsets.emplace(v, Vec3(0, 0, 0));
  for (const auto& [v, unused] : offsets) {
    const Vec3 blended = lerp(valueOr(a.offsets, v, Vec3(0, 0, 0)), valueOr(b.offsets, v, Vec3(0, 0, 0)), s);
    const VertexId vertex = VertexId::fromPacked(v);
    moves[vertex.level()].offsets.push_back({vertex, blended});
  }
  for (auto& [level, move] : moves) add(std::move(move));
  for (const auto& [e, sa] : a.edgeTags)
    add(EdgeSharpnessEdit{EdgeId::fromPacked(e), static_cast<float>(lerp(sa, b.edgeTags.at(e), s))});
  for (const auto& [v, sa] : a.vertexTags) {
    add(VertexSharpnessEdit{VertexId::fromPacked(v), static_cast<float>(lerp(sa, b.vertexTags.at(v), s))});
  }
  for (const auto& [v, ta] : a.interpolating) {
    const InterpolationEdit& tb = b.interpolating.at(v);
    add(InterpolationEdit{ta.vertex, true, lerp(ta.tension, tb.tension, s), lerp(ta.tangent, tb.tangent, s)});
  }
  auto doc =
      Document::restore(std::move(topology), std::move(points), keys_[0].options(), std::move(edits), id);
  if (!doc.isOk()) return doc.status().withContext("the morph at t = " + std::to_string(t));
  return doc;
}

}  // namespace tessera

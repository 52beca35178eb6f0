#include "core/morph/keyed_document.h"

#include <cmath>

namespace tessera {

Expected<Document*> KeyedDocument::editKey(uint32_t k) {
  if (k >= keys_.size()) {
    return notFound("key " + std::to_string(k) + " does not exist: the document has " +
                    std::to_string(keys_.size()) +
                    (keys_.size() == 1 ? " key (add a second with AddMorphKey)" : " keys"));
  }
  morph_.reset();
  return &keys_[k];
}

Status KeyedDocument::addKey(std::vector<Vec3> points, MorphImages images) {
  TESSERA_RETURN_IF_ERROR(checkMorphScheme(keys_[0], "key 0"));
  if (keys_.size() >= kMaxMorphKeys) {
    return invalidArgument("the document already has " + std::to_string(keys_.size()) +
                           " keys, the most a morph document holds");
  }
  const Document& first = keys_[0];
  if (points.size() != first.basePoints().size()) {
    return invalidArgument("the second key has " + std::to_string(points.size()) + " points, key 0 has " +
                           std::to_string(first.basePoints().size()) + ": a morph needs one connectivity");
  }
  for (size_t v = 0; v < points.size(); ++v) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(points[v][c])) {
        return invalidArgument("the second key's point " + std::to_string(v) + " is not finite");
      }
    }
  }
  auto key1 = Document::restore(first.baseTopology(), std::move(points), first.options(), first.edits(),
                                first.nextEditId());
  if (!key1.isOk()) return key1.status().withContext("the second key (key 0's edits on its points)");
  return restoreKey(std::move(*key1), std::move(images));
}

Status KeyedDocument::restoreKey(Document key1, MorphImages images) {
  if (keys_.size() >= kMaxMorphKeys) return invalidArgument("the document already has two keys");
  TESSERA_RETURN_IF_ERROR(checkMorphScheme(keys_[0], "key 0"));
  TESSERA_RETURN_IF_ERROR(checkMorphScheme(key1, "key 1"));
  TESSERA_RETURN_IF_ERROR(
      checkSameConnectivity(keys_[0].baseTopology(), key1.baseTopology(), "key 0", "key 1"));
  keys_.push_back(std::move(key1));
  images_ = std::move(images);
  morph_.reset();
  return Status::ok();
}

Expected<const Morph*> KeyedDocument::morph() const {
  if (!isMorph())
    return invalidArgument("the document has one key: add a second (AddMorphKey) to view it at a time t");
  if (!morph_) {
    TESSERA_ASSIGN_OR_RETURN(Morph m, Morph::create(keys_));
    morph_ = std::make_shared<const Morph>(std::move(m));
  }
  return morph_.get();
}

Expected<const Morph*> KeyedDocument::morphAt(double t) const {
  if (!(t >= 0.0 && t <= 1.0))
    return invalidArgument("morph time " + std::to_string(t) + " is not in [0, 1]");
  return morph();
}

Expected<Document> KeyedDocument::at(double t) const {
  TESSERA_ASSIGN_OR_RETURN(const Morph* m, morphAt(t));
  return m->at(t);
}

Expected<Vec3> KeyedDocument::pointAt(uint32_t v, double t) const {
  TESSERA_ASSIGN_OR_RETURN(const Morph* m, morphAt(t));
  if (v >= keys_[0].basePoints().size())
    return notFound("base vertex " + std::to_string(v) + " does not exist");
  return m->pointAt(v, t);
}

Expected<std::vector<Vec3>> KeyedDocument::pointsAt(double t) const {
  TESSERA_ASSIGN_OR_RETURN(const Morph* m, morphAt(t));
  std::vector<Vec3> points(keys_[0].basePoints().size());
  for (size_t v = 0; v < points.size(); ++v) points[v] = m->pointAt(static_cast<uint32_t>(v), t);
  return points;
}

}  // namespace tessera

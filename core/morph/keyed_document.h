// A service document with morph keys (docs/INTERPOLATION.md "Morph
// documents in the service"): key 0 always, key 1
// once a second key of the same connectivity was added. Editors edit either
// key; viewers see the document at a time t in [0, 1], built by Morph::at
// (docs/INTERPOLATION.md "Morphing": the control meshes are interpolated,
// then subdivided).
//
// A 2D morph document carries the two images the keys' meshes are drawn
// over (as in the image morph, core/morph/image_morph.h), as opaque PNG
// bytes: the core never
// decodes them here, the viewers do.
//
//   KeyedDocument doc(std::move(key0));
//   TESSERA_RETURN_IF_ERROR(doc.addKey(points1, {pngA, pngB}));
//   (*doc.editKey(1))->moveBy(...);
//   TESSERA_ASSIGN_OR_RETURN(Document at, doc.at(0.25));
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/document/document.h"
#include "core/morph/morph.h"
#include "core/util/status.h"

namespace tessera {

// The images of a 2D morph document: key 0's and key 1's, PNG bytes (both
// empty for a 3D document).
struct MorphImages {
  std::string from, to;
  bool empty() const { return from.empty() && to.empty(); }
};

inline constexpr size_t kMaxMorphKeys = 2;

class KeyedDocument {
 public:
  explicit KeyedDocument(Document key0) { keys_.push_back(std::move(key0)); }

  size_t numKeys() const { return keys_.size(); }
  bool isMorph() const { return keys_.size() > 1; }
  // Errors name the key and how many the document has. Mutable access
  // drops the cached morph: the caller may change the key.
  Expected<Document*> editKey(uint32_t k);
  Document& editKey0() {
    morph_.reset();
    return keys_[0];
  }
  const Document& key0() const { return keys_[0]; }
  // Key 0 for growing its hierarchy only (a tessellation refining it),
  // which changes no surface, so the cached morph stays.
  Document& growableKey0() { return keys_[0]; }
  const Document& key(size_t k) const { return keys_[k]; }
  const MorphImages& images() const { return images_; }

  // Takes key 1 back (a server refusing an AddMorphKey after applying it).
  void removeLastKey() {
    if (keys_.size() > 1) keys_.pop_back(), images_ = {}, morph_.reset();
  }

  // Adds key 1: key 0's base triangles and tags on these base points, with
  // key 0's edits as they are now (their offsets are in local frames, so
  // they follow the new points; core/loop/local_frame.h), and the morph's
  // images.
  // Refused if the document already has two keys, if the point count
  // differs, or if a point is not finite (each error names the vertex).
  Status addKey(std::vector<Vec3> points, MorphImages images = {});
  // Restores a second key exactly as saved (keyed_document_file.cc).
  Status restoreKey(Document key1, MorphImages images);

  // The document at time t (0: key 0, 1: key 1), rebuilt once per change
  // of either key: a morph view at t needs only at(t).
  Expected<Document> at(double t) const;
  // Base vertex v at time t.
  Expected<Vec3> pointAt(uint32_t v, double t) const;
  // Every base point at time t: what a coarse morph stream sends.
  Expected<std::vector<Vec3>> pointsAt(double t) const;

 private:
  Expected<const Morph*> morph() const;
  // The same, for a time t that must be in [0, 1] (the error says so).
  Expected<const Morph*> morphAt(double t) const;

  std::vector<Document> keys_;
  MorphImages images_;
  mutable std::shared_ptr<const Morph> morph_;
};

}  // namespace tessera

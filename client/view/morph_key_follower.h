// MorphKeyFollower: a 2D morph document's images follow its keys
// (docs/VIEWER.md, "Morph documents"). Two sessions besides the
// Connection's, subscribed at t = 0 and t = 1 with the uniform profile every
// view of the document uses, keep a view of either key current through the
// keys' edits; their regions give each displayed vertex its position under
// either key, which the renderer turns into texture coordinates.
//
// Not thread-safe: the Connection's network thread alone uses it.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>

#include "client/lib/document_view.h"
#include "client/lib/session.h"

namespace tessera::view {

// Per displayed vertex id, its position (pixels) under key 0 (x, y) and
// under key 1 (x, y).
using KeyPositionMap = std::unordered_map<uint64_t, std::array<float, 4>>;

// The key positions of the vertices of either key's regions: x and y of
// each vertex of `key0` in [0] and [1], of `key1` in [2] and [3]; 0 for a
// key whose regions lack the vertex.
KeyPositionMap keyPositions(const std::map<uint64_t, RegionMesh>& key0,
                            const std::map<uint64_t, RegionMesh>& key1);

class MorphKeyFollower {
 public:
  // The profile a key's session subscribes with, given the profile of the
  // surface shown: uniform at its max level, at t = key.
  static wire::LodProfile profileAtKey(const wire::LodProfile& shown, int key);

  // sessions[k]: connected, `document` open and subscribed at t = k.
  MorphKeyFollower(uint64_t document, std::array<std::unique_ptr<client::Session>, 2> sessions);

  struct Polled {
    // Set when the keys' views changed and both have their snapshot.
    std::shared_ptr<const KeyPositionMap> positions;
    // Why a key's session was lost (that key then stops following; the
    // surface shown is unaffected); empty when none was.
    std::string error;
  };
  // Applies what the key sessions received, at most 16 messages each. A
  // gap asks for a fresh snapshot at the key with profileAtKey(shown, k).
  Polled poll(const wire::LodProfile& shown);

 private:
  const uint64_t document_;
  std::array<std::unique_ptr<client::Session>, 2> sessions_;
  std::array<client::DocumentView, 2> views_;
};

}  // namespace tessera::view

// A viewer's level-of-detail profile (Pulli & Lounsbery, "Hierarchical
// Editing and Rendering of Subdivision Surfaces" §3.1): how finely the
// adaptive tessellation follows the hierarchy. Each subscriber chooses its
// own; the profile is part of the API and of every encoded region.
#pragma once

#include <cstdint>
#include <string>

#include "core/util/status.h"

namespace tessera {

struct LodProfile {
  int baseLevel = 2;                   // every face is shown at least this fine
  int maxLevel = 5;                    // never finer than this
  double angleThresholdDegrees = 10;   // refine where limit normals (or crease tangents) differ more
  int64_t triangleBudget = 4'000'000;  // refuse tessellations above this
  bool fidelity = false;               // edits at level l refine their 2-ring to l+1, not l (§3.1.1)
  // Regions carry the id of the control vertex each vertex is the limit of,
  // which a viewer needs to pick and drag. A display-only viewer (streaming
  // to thin clients, watching a session) can do without: about a third
  // fewer bytes per region.
  bool vertexIds = true;

  friend bool operator==(const LodProfile&, const LodProfile&) = default;

  // Ok when the numbers make sense; errors name the field and the value.
  Status check() const;
  // "base2-max5-angle10-budget4000000-fid0" ("...-noids" without vertex
  // ids): a stable key for caches (the angle in the fewest digits that
  // read back exactly).
  std::string key() const;
  // For people: "base level 2, max level 5, angle 10°, budget 4000000 triangles".
  std::string describe() const;
};

}  // namespace tessera

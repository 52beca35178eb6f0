// A subscriber's requested LOD profile (docs/PROTOCOL.md §9), checked
// against the server's limits and the document before any work: its budget,
// its levels, and a morph view's time, rounded so that viewers playing the
// same frames share one view (docs/PROTOCOL.md §14).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/tessellation/region_codec.h"
#include "core/tessellation/tessellation.h"
#include "core/util/status.h"
#include "protocol/tessera.pb.h"
#include "server/base/config.h"
#include "server/store/store.h"

namespace tessera::server {

// Morph views are at multiples of 1/kMorphTimeSteps (LodProfile.morph_t is
// rounded).
inline constexpr double kMorphTimeSteps = 10000;

struct ProfileRequest {
  LodProfile profile;
  std::optional<double> morphT;
  std::string key;  // the view's: equal requests share a view
};

// The triangle budget a request gets: its own when it asks for less than
// --max-triangles, else that cap.
int64_t budgetOf(const wire::LodProfile& requested, const Limits& limits);

// What the document serves for `requested`, or an invalid-argument error
// naming the field: levels out of order or above the document's
// `documentMaxLevel`, a morph time on a document with one key
// (`isMorph` false) or outside [0, 1].
Expected<ProfileRequest> checkProfileRequest(const wire::LodProfile& requested, const Limits& limits,
                                             store::DocumentId document, int documentMaxLevel, bool isMorph);

// The region codec a subscription asks for (Subscribe.codec; unset =
// Draco), or an invalid-argument error naming the field: a value this
// server does not know, or meshopt for a view-dependent subscription, whose
// tiles are Draco only (docs/REGION_ENCODING.md, "meshopt regions").
Expected<RegionCodec> codecFromWire(const wire::Subscribe& request);

}  // namespace tessera::server

#include "server/document/profile_request.h"

#include <algorithm>
#include <cmath>

namespace tessera::server {

int64_t budgetOf(const wire::LodProfile& requested, const Limits& limits) {
  if (requested.triangle_budget() == 0) return limits.maxTrianglesPerSubscriber;
  return std::min<int64_t>(static_cast<int64_t>(std::min<uint64_t>(requested.triangle_budget(), INT64_MAX)),
                           limits.maxTrianglesPerSubscriber);
}

Expected<ProfileRequest> checkProfileRequest(const wire::LodProfile& requested, const Limits& limits,
                                             store::DocumentId document, int documentMaxLevel, bool isMorph) {
  ProfileRequest request;
  LodProfile& profile = request.profile;
  profile.baseLevel = static_cast<int>(std::min<uint32_t>(requested.base_level(), 64));
  profile.maxLevel = static_cast<int>(std::min<uint32_t>(requested.max_level(), 64));
  profile.angleThresholdDegrees = requested.angle_threshold_degrees();
  profile.triangleBudget = budgetOf(requested, limits);
  profile.fidelity = requested.fidelity() > 0;
  profile.vertexIds = !requested.omit_vertex_ids();
  TESSERA_RETURN_IF_ERROR(profile.check());
  if (profile.maxLevel > documentMaxLevel) {
    return invalidArgument("LOD profile: max level " + std::to_string(profile.maxLevel) +
                           " exceeds the document's " + std::to_string(documentMaxLevel));
  }
  if (requested.has_morph_t()) {
    const double t = requested.morph_t();
    if (!isMorph) {
      return invalidArgument("LOD profile: morph_t is set but document " + std::to_string(document.value) +
                             " has one key (AddMorphKey adds the second)");
    }
    if (!(t >= 0.0 && t <= 1.0)) {
      return invalidArgument("LOD profile: morph_t " + std::to_string(t) + " is not in [0, 1]");
    }
    request.morphT = std::round(t * kMorphTimeSteps) / kMorphTimeSteps;
  }
  request.key = profile.key() +
                (request.morphT ? "-t" + std::to_string(std::lround(*request.morphT * kMorphTimeSteps)) : "");
  return request;
}

Expected<RegionCodec> codecFromWire(const wire::Subscribe& request) {
  switch (request.codec()) {
    case wire::REGION_CODEC_UNSPECIFIED:
    case wire::REGION_CODEC_DRACO:
      return RegionCodec::kDraco;
    case wire::REGION_CODEC_MESHOPT:
      if (request.has_view()) {
        return invalidArgument(
            "Subscribe.codec: REGION_CODEC_MESHOPT is served to LOD profile subscriptions only; a "
            "view-dependent subscription (Subscribe.view) gets Draco tiles (leave codec unset)");
      }
      return RegionCodec::kMeshopt;
    default:
      return invalidArgument("Subscribe.codec: unknown value " +
                             std::to_string(static_cast<int>(request.codec())) +
                             " (this server knows REGION_CODEC_DRACO = 1 and REGION_CODEC_MESHOPT = 2; unset "
                             "means Draco)");
  }
}

}  // namespace tessera::server

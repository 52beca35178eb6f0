#include "core/tessellation/lod_profile.h"

#include <cmath>

namespace tessera {

Status LodProfile::check() const {
  if (baseLevel < 0) return invalidArgument("LOD profile: base level must be >= 0, got " + std::to_string(baseLevel));
  if (maxLevel < baseLevel) {
    return invalidArgument("LOD profile: max level " + std::to_string(maxLevel) + " is below the base level " +
                           std::to_string(baseLevel));
  }
  if (!std::isfinite(angleThresholdDegrees) || angleThresholdDegrees <= 0.0 || angleThresholdDegrees > 180.0) {
    return invalidArgument("LOD profile: angle threshold must be in (0, 180] degrees, got " +
                           std::to_string(angleThresholdDegrees));
  }
  if (triangleBudget <= 0) {
    return invalidArgument("LOD profile: triangle budget must be > 0, got " + std::to_string(triangleBudget));
  }
  return Status::ok();
}

std::string LodProfile::key() const {
  return "base" + std::to_string(baseLevel) + "-max" + std::to_string(maxLevel) + "-angle" +
         std::to_string(angleThresholdDegrees) + "-budget" + std::to_string(triangleBudget) + "-fid" +
         (fidelity ? "1" : "0") + (vertexIds ? "" : "-noids");
}

}  // namespace tessera

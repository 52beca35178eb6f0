#include "core/tessellation/lod_profile.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace tessera {

namespace {

// The shortest text that reads back as the same double: "10", "12.5",
// never "10.000000" (std::to_string), and still distinct for distinct
// angles, as a cache key must be.
std::string shortest(double value) {
  char buffer[32];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

}  // namespace

Status LodProfile::check() const {
  if (baseLevel < 0)
    return invalidArgument("LOD profile: base level must be >= 0, got " + std::to_string(baseLevel));
  if (maxLevel < baseLevel) {
    return invalidArgument("LOD profile: max level " + std::to_string(maxLevel) +
                           " is below the base level " + std::to_string(baseLevel));
  }
  if (!std::isfinite(angleThresholdDegrees) || angleThresholdDegrees <= 0.0 ||
      angleThresholdDegrees > 180.0) {
    return invalidArgument("LOD profile: angle threshold must be in (0, 180] degrees, got " +
                           shortest(angleThresholdDegrees));
  }
  if (triangleBudget <= 0) {
    return invalidArgument("LOD profile: triangle budget must be > 0, got " + std::to_string(triangleBudget));
  }
  return Status::ok();
}

std::string LodProfile::key() const {
  return "base" + std::to_string(baseLevel) + "-max" + std::to_string(maxLevel) + "-angle" +
         shortest(angleThresholdDegrees) + "-budget" + std::to_string(triangleBudget) + "-fid" +
         (fidelity ? "1" : "0") + (vertexIds ? "" : "-noids");
}

std::string LodProfile::describe() const {
  return "base level " + std::to_string(baseLevel) + ", max level " + std::to_string(maxLevel) + ", angle " +
         shortest(angleThresholdDegrees) + "\u00b0, budget " + std::to_string(triangleBudget) + " triangles" +
         (fidelity ? ", fidelity" : "") + (vertexIds ? "" : ", without vertex ids");
}

}  // namespace tessera

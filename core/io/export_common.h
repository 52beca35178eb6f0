// Small conversions shared by the exporters (internal to core/io).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include "core/util/status.h"
#include "core/util/vec3.h"

namespace tessera::io_detail {

// Every binary format Tessera writes (PLY, glTF, Draco) stores float32.
inline std::array<float, 3> toFloat3(const Vec3& v) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

// glTF 2.0 (3.7.2.1) requires NORMAL to be unit length, and Draco's
// octahedral normal coding assumes it. Normalise in double, then round, so the
// float result is within one ulp of unit length. Callers have already rejected
// zero and non-finite normals.
inline std::array<float, 3> unitFloat3(const Vec3& v) {
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return toFloat3(v / length);
}

// Writes `size` bytes to `path`, replacing it; errors are ioError naming the
// path and the operating system's reason. Defined in mesh_export.cc.
Status writeFileBytes(const std::string& path, const char* data, std::size_t size);

}  // namespace tessera::io_detail

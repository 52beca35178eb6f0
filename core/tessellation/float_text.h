// Numbers in the errors of the quantization grid and the region codec: nine
// significant digits, enough to tell every float32 apart, which is the
// precision Draco stores positions in (quantization_grid.h).
#pragma once

#include <cstdio>
#include <string>

#include "core/util/vec3.h"

namespace tessera {

inline std::string floatText(double x) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.9g", x);
  return text;
}

// "(x, y, z)".
inline std::string pointText(const Vec3& p) {
  return "(" + floatText(p[0]) + ", " + floatText(p[1]) + ", " + floatText(p[2]) + ")";
}

}  // namespace tessera

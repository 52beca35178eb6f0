#include "client/view/gizmo.h"

#include <algorithm>

namespace tessera::view {

std::array<GizmoAxis, 3> gizmoAxes(const Mat4& view) {
  std::array<GizmoAxis, 3> axes{};
  for (int a = 0; a < 3; ++a) {
    // The view matrix's rotation maps world axis a to its column a.
    const float x = view[a * 4 + 0], y = view[a * 4 + 1], z = view[a * 4 + 2];
    axes[a] = GizmoAxis{a, x, -y, z};
  }
  std::sort(axes.begin(), axes.end(),
            [](const GizmoAxis& p, const GizmoAxis& q) { return p.depth < q.depth; });
  return axes;
}

GizmoPlacement gizmoPlacement(int width, int height) {
  const float radius = std::clamp(0.07f * static_cast<float>(std::min(width, height)), 24.0f, 64.0f);
  const float margin = 14 + radius;
  return {margin, static_cast<float>(height) - margin, radius};
}

}  // namespace tessera::view

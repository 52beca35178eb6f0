// The axes gizmo of tessera-view: where the world's X, Y and Z axes point on
// screen for the camera's rotation, drawn small in the bottom-left corner
// (hud.h draws it). Pure, so it is tested without a window.
#pragma once

#include <array>

#include "client/view/view_math.h"

namespace tessera::view {

struct GizmoAxis {
  int axis = 0;          // 0 = X, 1 = Y, 2 = Z
  float dx = 0, dy = 0;  // screen direction scaled by the axis's visible length; y down, as pixels are
  float depth = 0;       // towards the viewer is positive
};

// The three axes, farthest first, so that drawing them in order leaves the
// nearest on top.
std::array<GizmoAxis, 3> gizmoAxes(const Mat4& view);

// Where the gizmo sits: its centre and radius in pixels for a framebuffer of
// this size (bottom-left corner, radius 7% of the smaller side, 24 to 64 px).
struct GizmoPlacement {
  float cx = 0, cy = 0, radius = 0;
};
GizmoPlacement gizmoPlacement(int width, int height);

}  // namespace tessera::view

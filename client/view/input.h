// The input of tessera-view: keys and mouse, from GLFW or from the headless
// self-test scripts (self_test.h), which go through the same functions.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "client/view/camera.h"
#include "client/view/connection.h"
#include "client/view/control_points.h"
#include "client/view/hud.h"

namespace tessera::view {

// Input state shared with the GLFW callbacks (through the window user pointer).
struct App {
  OrbitCamera camera;
  ViewToggles toggles;
  Connection* connection = nullptr;
  float scroll = 0;
  std::optional<uint64_t> picked;            // packed id at toggles.controlLevel
  std::optional<uint64_t> edgeEnd;           // with `picked`: the other end of the picked edge
  std::set<uint64_t> corners;                // vertices this viewer made corners
  std::map<uint64_t, double> interpolating;  // vertices this viewer made interpolating, and their tension
  bool frameRequested = false, quit = false;
  bool undo = false, redo = false;  // done by the frame loop
};

// A key press (GLFW_KEY_*, GLFW_MOD_* bits). W, C, V, M, G and H toggle the
// wireframe, region colours, control vertices, matcap, axes gizmo and the
// HUD's collapse; F fits the model to the view. E and Shift+E make the picked
// edge infinitely sharp and smooth again, 1 to 4 give it that semi-sharpness;
// K toggles the picked vertex between corner and smooth; I toggles it
// between interpolating (docs/INTERPOLATION.md, tension 1) and plain, and = and -
// double and halve its tension; Ctrl+Z / Ctrl+Y (Ctrl+Shift+Z) undo and redo.
// On a morph document, P plays and pauses it, and , and . step its time by
// 0.05. With --views, X freezes the view (the camera moves, the tiles stay
// as sent) and L colours tiles by level.
void handleKey(App& app, int key, int mods);

// Drops the pick, and the selection others see.
void dropPick(App& app);

// One frame of mouse state, in framebuffer pixels.
struct MouseInput {
  float px = 0, py = 0;
  bool left = false, right = false, shift = false;
  float scroll = 0;
  bool captured = false;  // ImGui wants the mouse
};

// Mouse: left on a control vertex picks and drags it, left elsewhere orbits,
// shift+left on another control vertex picks the edge to it, right or
// shift+left elsewhere pans, the wheel zooms. A drag is one undo step.
class MouseTool {
 public:
  void update(const MouseInput& in, App& app, const std::vector<ControlPoint>& points, int width, int height);

 private:
  enum class Mode { kNone, kOrbit, kPan, kDrag };
  Mode mode_ = Mode::kNone;
  bool wasLeft_ = false, wasRight_ = false, pending_ = false;
  float lastX_ = 0, lastY_ = 0;
  V3 anchor_;
  std::chrono::steady_clock::time_point lastSend_;
  UndoHistory::StepId step_ = 0;
};

}  // namespace tessera::view

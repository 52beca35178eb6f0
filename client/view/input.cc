#include "client/view/input.h"

#include <algorithm>
#include <limits>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace tessera::view {

using Clock = std::chrono::steady_clock;

void dropPick(App& app) {
  app.picked.reset();
  app.edgeEnd.reset();
  app.connection->select({});
}

void handleKey(App& app, int key, int mods) {
  const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0, shift = (mods & GLFW_MOD_SHIFT) != 0;
  switch (key) {
    case GLFW_KEY_W:
      app.toggles.wireframe = !app.toggles.wireframe;
      break;
    case GLFW_KEY_C:
      app.toggles.regionColours = !app.toggles.regionColours;
      break;
    case GLFW_KEY_X:
      app.toggles.frozen = !app.toggles.frozen;
      break;
    case GLFW_KEY_L:
      app.toggles.levelColours = !app.toggles.levelColours;
      break;
    case GLFW_KEY_R:
      app.toggles.refine = (app.toggles.refine + 1) % 3;
      break;
    case GLFW_KEY_V:
      app.toggles.showControls = !app.toggles.showControls;
      break;
    case GLFW_KEY_O:
      app.toggles.showCage = !app.toggles.showCage;
      break;
    case GLFW_KEY_M:
      app.toggles.matcap = !app.toggles.matcap;
      break;
    case GLFW_KEY_G:
      app.toggles.showGizmo = !app.toggles.showGizmo;
      break;
    case GLFW_KEY_H:
      app.toggles.hudCollapsed = !app.toggles.hudCollapsed;
      break;
    case GLFW_KEY_F:
      app.frameRequested = true;
      break;
    case GLFW_KEY_P:
      if (app.toggles.morph) app.toggles.playing = !app.toggles.playing, app.toggles.morphShown = true;
      break;
    case GLFW_KEY_COMMA:
    case GLFW_KEY_PERIOD:
      if (app.toggles.morph) {
        const float step = key == GLFW_KEY_PERIOD ? 0.05f : -0.05f;
        app.toggles.morphT = std::clamp(app.toggles.morphT + step, 0.0f, 1.0f);
        app.toggles.morphShown = true;
        app.toggles.playing = false;
      }
      break;
    case GLFW_KEY_LEFT_BRACKET:
      if (app.toggles.controlLevel > 0) --app.toggles.controlLevel, dropPick(app);
      break;
    case GLFW_KEY_RIGHT_BRACKET:
      if (app.toggles.controlLevel < 10) ++app.toggles.controlLevel, dropPick(app);
      break;
    case GLFW_KEY_K:
      if (app.picked) {
        const bool corner = app.corners.count(*app.picked) == 0;
        app.connection->setVertexType(*app.picked,
                                      corner ? wire::VERTEX_TYPE_CORNER : wire::VERTEX_TYPE_SMOOTH);
        if (corner) {
          app.corners.insert(*app.picked);
        } else {
          app.corners.erase(*app.picked);
        }
      }
      break;
    case GLFW_KEY_I:
      if (app.picked) {
        auto it = app.interpolating.find(*app.picked);
        if (it == app.interpolating.end()) {
          app.interpolating[*app.picked] = 1.0;
          app.connection->setInterpolation(*app.picked, true, 1.0);
        } else {
          app.interpolating.erase(it);
          app.connection->setInterpolation(*app.picked, false, 1.0);
        }
      }
      break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_MINUS:
      // The tension scales the ghost ring by 1/tension (core/loop/ghost_ring.h):
      // doubling it pulls the surface tighter around the vertex.
      if (app.picked && app.interpolating.count(*app.picked) != 0) {
        double& tension = app.interpolating[*app.picked];
        tension = std::clamp(key == GLFW_KEY_EQUAL ? tension * 2 : tension / 2, 1e-3, 1e3);
        app.connection->setInterpolation(*app.picked, true, tension);
      }
      break;
    case GLFW_KEY_E:
      if (app.picked && app.edgeEnd) {
        app.connection->setEdgeSharpness(*app.picked, *app.edgeEnd,
                                         shift ? 0.0f : std::numeric_limits<float>::infinity());
      }
      break;
    case GLFW_KEY_1:
    case GLFW_KEY_2:
    case GLFW_KEY_3:
    case GLFW_KEY_4:
      // Semi-sharp (DeRose, Kass & Truong '98, "Subdivision Surfaces in
      // Character Animation"): sharp for that many levels below the edge's,
      // then smooth, each level taking one off (Chaikin-averaged where the
      // document asks for it).
      if (app.picked && app.edgeEnd) {
        app.connection->setEdgeSharpness(*app.picked, *app.edgeEnd, static_cast<float>(key - GLFW_KEY_0));
      }
      break;
    case GLFW_KEY_Z:
      if (ctrl) (shift ? app.redo : app.undo) = true;
      break;
    case GLFW_KEY_Y:
      if (ctrl) app.redo = true;
      break;
    case GLFW_KEY_ESCAPE:
      dropPick(app);
      break;
    case GLFW_KEY_Q:
      app.quit = true;
      break;
    default:
      break;
  }
}

void MouseTool::update(const MouseInput& in, App& app, const std::vector<ControlPoint>& points, int width,
                       int height) {
  if (!in.captured && in.scroll != 0) app.camera.zoom(in.scroll);
  if (in.left && !wasLeft_ && !in.captured) {
    mode_ = in.shift ? Mode::kPan : Mode::kOrbit;
    const auto hit = app.toggles.showControls
                         ? pickPoint(points, app.camera, width, height, in.px, in.py, 10.0f)
                         : std::nullopt;
    if (hit && in.shift && app.picked && points[*hit].id != *app.picked) {
      // The second end of an edge: picked, not dragged.
      mode_ = Mode::kNone;
      app.edgeEnd = points[*hit].id;
      app.connection->select({*app.picked, *app.edgeEnd});
    } else if (hit && !in.shift) {
      mode_ = Mode::kDrag;
      app.picked = points[*hit].id;
      app.edgeEnd.reset();
      anchor_ = points[*hit].position;
      app.connection->select({*app.picked});
      step_ = app.connection->openStep();
    }
  } else if (in.right && !wasRight_ && !in.captured) {
    mode_ = Mode::kPan;
  }
  // Motion counts from the press: a frame that sees the pointer arrive and
  // the button go down together (a starved viewer, or a click right after
  // a jump) must not turn the jump into a drag edit or an orbit.
  if ((in.left && !wasLeft_) || (in.right && !wasRight_)) lastX_ = in.px, lastY_ = in.py;
  const float dx = in.px - lastX_, dy = in.py - lastY_;
  if (mode_ == Mode::kOrbit && in.left) app.camera.orbit(dx, dy);
  if (mode_ == Mode::kPan && (in.left || in.right)) app.camera.pan(dx, dy, height);
  if (mode_ == Mode::kDrag && app.picked) {
    const auto now = Clock::now();
    if (dx != 0 || dy != 0) pending_ = true;
    // At most 30 edits a second while dragging, and the last one on release.
    if (pending_ && (!in.left || now - lastSend_ > std::chrono::milliseconds(33))) {
      const V3 t = dragTarget(app.camera, anchor_, in.px, in.py, width, height);
      app.connection->moveVertex(*app.picked, Vec3(t.x, t.y, t.z), step_);
      lastSend_ = now;
      pending_ = false;
    }
  }
  if (mode_ == Mode::kDrag && !in.left) {
    app.connection->closeStep(step_);
    mode_ = Mode::kNone;
  }
  if (!in.left && !in.right) mode_ = Mode::kNone;
  wasLeft_ = in.left, wasRight_ = in.right, lastX_ = in.px, lastY_ = in.py;
}

}  // namespace tessera::view

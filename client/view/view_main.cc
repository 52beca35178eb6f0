// tessera-view: a GLFW + OpenGL 3.3 core viewer and editor for one document
// of a tessera-server (issue 6 §2, docs/VIEWER.md). The Connection keeps the
// document current on its own thread; each frame uploads changed regions,
// draws them, handles picking and dragging of control vertices, and draws
// the HUD. With --screenshot it renders a number of frames once the first
// snapshot is in, writes a PNG and exits.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "client/view/gl.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "client/view/camera.h"
#include "client/view/connection.h"
#include "client/view/control_points.h"
#include "client/view/hud.h"
#include "client/view/input.h"
#include "client/view/refinement.h"
#include "client/view/renderer.h"
#include "client/view/screenshot.h"
#include "client/view/self_test.h"
#include "client/view/view_options.h"

namespace tessera::view {
namespace {

using Clock = std::chrono::steady_clock;

void onScroll(GLFWwindow* window, double, double dy) {
  static_cast<App*>(glfwGetWindowUserPointer(window))->scroll += static_cast<float>(dy);
}

void onKey(GLFWwindow* window, int key, int, int action, int mods) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;
  handleKey(*static_cast<App*>(glfwGetWindowUserPointer(window)), key, mods);
}

MouseInput readMouse(GLFWwindow* window, App& app, int width, int height) {
  MouseInput in;
  double x = 0, y = 0;
  glfwGetCursorPos(window, &x, &y);
  // Cursor positions are in window coordinates; the camera works in framebuffer pixels.
  int ww = 1, wh = 1;
  glfwGetWindowSize(window, &ww, &wh);
  in.px = static_cast<float>(x) * static_cast<float>(width) / static_cast<float>(std::max(ww, 1));
  in.py = static_cast<float>(y) * static_cast<float>(height) / static_cast<float>(std::max(wh, 1));
  in.captured = ImGui::GetIO().WantCaptureMouse;
  in.left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  in.right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
             glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
  in.shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
             glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  in.scroll = app.scroll;
  app.scroll = 0;
  return in;
}

std::vector<V3> visible(const std::vector<ControlPoint>& points, V3 eye) {
  std::vector<V3> out;
  for (const ControlPoint& p : points)
    if (dot(p.normal, eye - p.position) >= 0) out.push_back(p.position);
  return out;
}

// Collaborators' selections in cyan, this viewer's pick in red. Two
// selected vertices are an edge, drawn as a dotted line between them.
void drawSelections(Renderer& renderer, const App& app, const std::vector<ControlPoint>& points,
                    const std::vector<Collaborator>& collaborators, const DrawOptions& draw) {
  auto mark = [&](const std::vector<uint64_t>& ids, std::array<float, 3> colour) {
    std::vector<V3> ends;
    for (uint64_t id : ids) {
      auto it = std::lower_bound(points.begin(), points.end(), id,
                                 [](const ControlPoint& p, uint64_t v) { return p.id < v; });
      if (it != points.end() && it->id == id) ends.push_back(it->position);
    }
    renderer.drawPoints(ends, PointStyle{colour, 12}, draw);
    if (ends.size() == 2)
      renderer.drawPoints(segmentPoints(ends[0], ends[1], 24), PointStyle{colour, 5}, draw);
  };
  for (const Collaborator& c : collaborators)
    if (!c.self) mark(c.selectedVertices, {0.2f, 0.9f, 1.0f});
  std::vector<uint64_t> own;
  if (app.picked) own.push_back(*app.picked);
  if (app.edgeEnd) own.push_back(*app.edgeEnd);
  mark(own, {1.0f, 0.2f, 0.2f});
}

int run(const ViewOptions& options) {
  const bool headless = !options.screenshot.empty();
  auto connection = Connection::open(options);
  if (!connection.isOk()) {
    std::fprintf(stderr, "tessera-view: %s\n", connection.status().toString().c_str());
    return 1;
  }
  glfwSetErrorCallback(
      [](int code, const char* text) { std::fprintf(stderr, "tessera-view: GLFW %d: %s\n", code, text); });
  if (!glfwInit()) return 1;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, headless ? 0 : 4);
  const std::string title = "tessera-view: document " + std::to_string(options.document);
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, title.c_str(), nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "tessera-view: no OpenGL 3.3 core window (is DISPLAY set?)\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(headless ? 0 : 1);

  App app;
  app.connection = connection->get();
  app.toggles.wireframe = options.wireframe;
  app.toggles.regionColours = options.regionColours;
  app.toggles.controlLevel = options.controlLevel;
  app.toggles.refine = options.refine;
  app.toggles.baseLevel = static_cast<int>(options.baseLevel);
  app.toggles.maxLevel = static_cast<int>(options.maxLevel);
  app.toggles.angle = static_cast<float>(options.angle);
  glfwSetWindowUserPointer(window, &app);
  // Installed before ImGui's, which chain to them.
  glfwSetScrollCallback(window, onScroll);
  glfwSetKeyCallback(window, onKey);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");

  int rc = 0;
  {
    auto renderer = Renderer::create();
    if (!renderer.isOk()) {
      std::fprintf(stderr, "tessera-view: %s\n", renderer.status().toString().c_str());
      rc = 1;
    }
    MouseTool mouse;
    std::optional<DragScript> script;
    if (headless && options.drag) script.emplace(options.dragX, options.dragY);
    std::optional<KeyScript> keys;
    if (headless && options.editKeys) keys.emplace();
    const bool scripted = script || keys;
    RegionMap regions;
    std::vector<ControlPoint> points;
    uint64_t seenUpdates = 0;
    bool synced = false;
    RefineTiming refineTiming;
    int pointsLevel = -1;
    bool framed = false;
    int framesReady = 0, framesCounted = 0;
    double fps = 0, bytesPerSecond = 0;
    uint64_t bytesAtSample = 0;
    const auto start = Clock::now();
    auto lastFrame = start, lastSample = start;
    while (rc == 0 && !glfwWindowShouldClose(window) && !app.quit) {
      glfwPollEvents();
      const auto now = Clock::now();
      const double dt = std::chrono::duration<double>(now - lastFrame).count();
      lastFrame = now;
      if (dt > 0) fps = fps == 0 ? 1 / dt : 0.9 * fps + 0.1 / dt;
      const ConnectionStats stats = (*connection)->stats();
      if (std::chrono::duration<double>(now - lastSample).count() >= 1) {
        bytesPerSecond = static_cast<double>(stats.bytesReceived - bytesAtSample) /
                         std::chrono::duration<double>(now - lastSample).count();
        bytesAtSample = stats.bytesReceived;
        lastSample = now;
      }
      if (headless && (!stats.connected || (!stats.ready && now - start > std::chrono::duration<double>(
                                                                              options.timeoutSeconds)))) {
        std::fprintf(stderr, "tessera-view: no snapshot of document %llu: %s\n",
                     static_cast<unsigned long long>(options.document),
                     stats.lastError.empty() ? "timed out" : stats.lastError.c_str());
        rc = 1;
        break;
      }
      if (stats.regionUpdates != seenUpdates) {
        seenUpdates = stats.regionUpdates;
        regions = (*connection)->regions();
        pointsLevel = -1;
        synced = false;
      }
      if (app.toggles.refine > 0) {
        refineTiming = refineAndStream(regions, app.toggles.refine, **renderer);
        synced = false;
      } else if (!synced) {
        (*renderer)->sync(regions);
        synced = true;
      }
      if (pointsLevel != app.toggles.controlLevel) {
        points = controlPoints(regions, app.toggles.controlLevel);
        pointsLevel = app.toggles.controlLevel;
      }
      V3 lo, hi;
      if ((!framed || app.frameRequested) && bounds(regions, &lo, &hi)) {
        app.camera.frame(lo, hi);
        framed = true;
        app.frameRequested = false;
      }
      if (app.toggles.profileChanged) {
        app.toggles.profileChanged = false;
        (*connection)
            ->changeProfile(static_cast<uint32_t>(app.toggles.baseLevel),
                            static_cast<uint32_t>(app.toggles.maxLevel), app.toggles.angle);
      }
      if (app.undo) (*connection)->undo(), app.undo = false;
      if (app.redo) (*connection)->redo(), app.redo = false;

      int width = 0, height = 0;
      glfwGetFramebufferSize(window, &width, &height);
      if (options.hud) {
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
      }
      if (!headless) {
        mouse.update(readMouse(window, app, width, height), app, points, width, height);
      } else if (scripted && stats.ready && framesReady >= 2 && !(script ? script->done() : keys->done())) {
        std::optional<MouseInput> in;
        std::string error;
        if (script) {
          in = script->next(app, points, width, height);
          if (!in) error = "--drag: no visible control vertex";
        } else {
          // Fresh counts: the frame loop may just have sent an undo or redo.
          KeyScript::Frame frame = keys->next(app, regions, points, (*connection)->stats(), width, height);
          in = frame.mouse;
          if (!frame.error.empty()) error = "--edit-keys: " + frame.error;
        }
        if (!error.empty()) {
          std::fprintf(stderr, "tessera-view: %s at level %d\n", error.c_str(), app.toggles.controlLevel);
          rc = 1;
          break;
        }
        if (in) mouse.update(*in, app, points, width, height);
      }

      glViewport(0, 0, width, height);
      glClearColor(0.16f, 0.18f, 0.22f, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      DrawOptions draw;
      draw.view = app.camera.view();
      draw.projection =
          app.camera.projection(static_cast<float>(width) / static_cast<float>(std::max(height, 1)));
      draw.wireframe = app.toggles.wireframe;
      draw.regionColours = app.toggles.regionColours;
      (*renderer)->drawSurface(draw);
      if (app.toggles.showControls) {
        (*renderer)->drawPoints(visible(points, app.camera.eye()), PointStyle{}, draw);
        drawSelections(**renderer, app, points, (*connection)->collaborators(), draw);
      }
      if (options.hud) {
        HudFacts facts{.fps = fps,
                       .triangles = (*renderer)->triangles(),
                       .receivedTriangles = refineTiming.receivedTriangles,
                       .refineMs = refineTiming.refineMs,
                       .uploadMs = refineTiming.uploadMs,
                       .regions = (*renderer)->regionCount(),
                       .bytesPerSecond = bytesPerSecond,
                       .controlPoints = points.size(),
                       .pickedVertex = app.picked,
                       .pickedEdgeEnd = app.edgeEnd,
                       .stats = stats,
                       .collaborators = (*connection)->collaborators()};
        drawHud(facts, app.toggles);
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      }
      // With a self-test, frames count from when every edit has its delta.
      // Fresh counts: the mouse or a key may have queued an edit this frame.
      const ConnectionStats after = scripted ? (*connection)->stats() : stats;
      const bool scriptDone = script ? script->done() : (!keys || keys->done());
      const bool waiting = scripted && (!scriptDone || after.editsPending > 0);
      if (scripted && scriptDone && after.editsPending == 0 && after.editsSent == 0) {
        std::fprintf(stderr, "tessera-view: the self-test sent no edit\n");
        rc = 1;
        break;
      }
      if (waiting && now - start > std::chrono::duration<double>(options.timeoutSeconds)) {
        std::fprintf(stderr, "tessera-view: self-test: edits unanswered after %g s\n",
                     options.timeoutSeconds);
        rc = 1;
        break;
      }
      if (headless && stats.ready) ++framesReady;
      if (headless && stats.ready && !waiting && ++framesCounted >= options.frames) {
        if (script) {
          std::printf(
              "dragged %s by (%d, %d): %llu edits sent, %llu rejected, edit to delta %.1f ms (max %.1f ms)\n",
              app.picked ? vertexName(*app.picked).c_str() : "nothing", options.dragX, options.dragY,
              static_cast<unsigned long long>(after.editsSent),
              static_cast<unsigned long long>(after.editsRejected), after.lastLatencyMs, after.maxLatencyMs);
        }
        if (keys) {
          std::printf("keys: %s; %llu edits sent, %llu rejected\n", keys->report().c_str(),
                      static_cast<unsigned long long>(after.editsSent),
                      static_cast<unsigned long long>(after.editsRejected));
        }
        const Status written = writeScreenshot(options.screenshot, width, height);
        if (!written.isOk()) {
          std::fprintf(stderr, "tessera-view: %s\n", written.toString().c_str());
          rc = 1;
        } else {
          std::printf("wrote %s (%dx%d, document version %llu, %lld triangles)\n", options.screenshot.c_str(),
                      width, height, static_cast<unsigned long long>(stats.version),
                      static_cast<long long>((*renderer)->triangles()));
        }
        break;
      }
      glfwSwapBuffers(window);
    }
  }  // the renderer's GL objects go while the context is current
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return rc;
}

}  // namespace
}  // namespace tessera::view

int main(int argc, char** argv) {
  auto options = tessera::view::parseViewOptions(std::vector<std::string>(argv + 1, argv + argc));
  if (!options.isOk()) {
    std::fprintf(stderr, "tessera-view: %s\n\n%s", options.status().message().c_str(),
                 tessera::view::kViewHelp);
    return 2;
  }
  if (options->help) {
    std::fputs(tessera::view::kViewHelp, stdout);
    return 0;
  }
  return tessera::view::run(*options);
}

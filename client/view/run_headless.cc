// tessera-view --screenshot: no window and no display. An EGL surfaceless
// context (headless_context.h) draws into a multisampled framebuffer object
// (offscreen_target.h); the self-tests (--drag, --edit-keys) feed synthetic
// input through the window's own mouse and key code; once the document is
// in and every self-test edit has its delta, --frames frames are drawn, the
// samples resolved and the picture written.
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>

#include "client/view/headless_context.h"
#include "client/view/offscreen_target.h"
#include "client/view/run.h"
#include "client/view/self_test.h"
#include "client/view/viewer.h"

namespace tessera::view {

namespace {

using Clock = std::chrono::steady_clock;

// What ImGui's platform backend would do each frame; there is no platform.
void newImGuiFrame(int width, int height, double dt) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DisplayFramebufferScale = ImVec2(1, 1);
  io.DeltaTime = dt > 0 ? static_cast<float>(dt) : 1.0f / 60;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
}

// The frame loop once the context and the target exist; the exit code.
int renderFrames(const ViewOptions& options, Connection& connection, Viewer& viewer,
                 const OffscreenTarget& target) {
  const int width = target.width(), height = target.height();
  App& app = viewer.app();
  MouseTool mouse;
  std::optional<DragScript> script;
  if (options.drag) script.emplace(options.dragX, options.dragY);
  std::optional<KeyScript> keys;
  if (options.editKeys) keys.emplace();
  const bool scripted = script || keys;
  int framesReady = 0, framesCounted = 0;
  const auto start = Clock::now();
  // When the first picture was drawn and when the picture was whole (the
  // snapshot, or with --views the last camera's tiles): printed at the end.
  std::optional<Clock::time_point> firstDrawn, wholeDrawn;
  auto last = start;
  const auto timeout = std::chrono::duration<double>(options.timeoutSeconds);
  for (;;) {
    const auto now = Clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    const ConnectionStats stats = viewer.update(width, height);
    if (!stats.connected || (!stats.ready && now - start > timeout)) {
      std::fprintf(stderr, "tessera-view: no snapshot of document %llu: %s\n",
                   static_cast<unsigned long long>(options.document),
                   stats.lastError.empty() ? "timed out" : stats.lastError.c_str());
      return 1;
    }
    if (!stats.ready) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));  // the connection's thread does the work
      continue;
    }
    newImGuiFrame(width, height, dt);
    if (scripted && framesReady >= 2 && !(script ? script->done() : keys->done())) {
      std::optional<MouseInput> in;
      std::string error;
      if (script) {
        in = script->next(app, viewer.points(), width, height);
        if (!in) error = "--drag: no visible control vertex";
      } else {
        // Fresh counts: the frame loop may just have sent an undo or redo.
        KeyScript::Frame frame =
            keys->next(app, viewer.regions(), viewer.points(), connection.stats(), width, height);
        in = frame.mouse;
        if (!frame.error.empty()) error = "--edit-keys: " + frame.error;
      }
      if (!error.empty()) {
        ImGui::EndFrame();
        std::fprintf(stderr, "tessera-view: %s at level %d\n", error.c_str(), app.toggles.controlLevel);
        return 1;
      }
      if (in) mouse.update(*in, app, viewer.points(), width, height);
    }
    target.bind();
    viewer.draw(width, height);
    if (!firstDrawn) firstDrawn = Clock::now();
    // With a self-test, frames count from when every edit has its delta.
    // Fresh counts: the mouse or a key may have queued an edit this frame.
    const ConnectionStats after = scripted || connection.viewDependent() ? connection.stats() : stats;
    const bool scriptDone = script ? script->done() : (!keys || keys->done());
    // With --views, frames count from when the tiles of the camera sent last
    // are all here (the viewer sends it once it has framed the model).
    const bool viewLoading = connection.viewDependent() && (!after.viewComplete || viewer.cameraPending());
    // With --cage, frames count from when the cage of the level shown is here.
    const bool cageLoading = app.toggles.showCage && !viewer.cage();
    const bool waiting = (scripted && (!scriptDone || after.editsPending > 0)) || viewLoading || cageLoading;
    if (scripted && scriptDone && after.editsPending == 0 && after.editsSent == 0) {
      std::fprintf(stderr, "tessera-view: the self-test sent no edit\n");
      return 1;
    }
    if (viewLoading && now - start > timeout) {
      std::fprintf(stderr, "tessera-view: the view's tiles were not complete after %g s\n",
                   options.timeoutSeconds);
      return 1;
    }
    if (cageLoading && now - start > timeout) {
      std::fprintf(stderr, "tessera-view: the cage of level %d did not arrive after %g s: %s\n",
                   app.toggles.controlLevel, options.timeoutSeconds,
                   after.lastError.empty() ? "no answer" : after.lastError.c_str());
      return 1;
    }
    if (waiting && now - start > timeout) {
      std::fprintf(stderr, "tessera-view: self-test: edits unanswered after %g s\n", options.timeoutSeconds);
      return 1;
    }
    ++framesReady;
    if (!waiting && !wholeDrawn) wholeDrawn = Clock::now();
    if (waiting || ++framesCounted < options.frames) continue;
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
    if (const Status written = target.writePng(options.screenshot); !written.isOk()) {
      std::fprintf(stderr, "tessera-view: %s\n", written.toString().c_str());
      return 1;
    }
    std::printf("wrote %s (%dx%d, %d samples per pixel, document version %llu, %lld triangles)\n",
                options.screenshot.c_str(), width, height, target.samples(),
                static_cast<unsigned long long>(stats.version), static_cast<long long>(viewer.triangles()));
    if (const ControlCage* cage = viewer.cage(); cage && app.toggles.showCage) {
      std::string faces;
      for (const auto& [corners, count] : cage->facesBySize)
        faces += (faces.empty() ? "" : ", ") + std::to_string(count) + " of " + std::to_string(corners) +
                 " corners";
      std::printf("cage of level %d: %zu faces (%s), %zu edges, %zu drawn\n", cage->level, cage->faces(),
                  faces.c_str(), cage->edges.size(), viewer.cageEdgesDrawn());
    }
    const auto ms = [&](Clock::time_point t) {
      return std::chrono::duration<double, std::milli>(t - options.started).count();
    };
    std::printf("first picture %.0f ms, whole picture %.0f ms, %llu region bytes received\n", ms(*firstDrawn),
                ms(wholeDrawn.value_or(Clock::now())), static_cast<unsigned long long>(after.bytesReceived));
    // Which codec the server sent (--codec) and, with --surface-hash, the
    // hash of what was decoded: equal for either codec (docs/REGION_ENCODING.md
    // "meshopt regions").
    std::printf("regions received: %llu draco, %llu meshopt",
                static_cast<unsigned long long>(after.dracoRegions),
                static_cast<unsigned long long>(after.meshoptRegions));
    if (options.hashSurfaces)
      std::printf("; surface hash %llu", static_cast<unsigned long long>(after.surfaceHash));
    std::printf("\n");
    return 0;
  }
}

}  // namespace

int runHeadless(const ViewOptions& options, Connection& connection) {
  auto context = HeadlessContext::create();
  if (!context.isOk()) {
    std::fprintf(stderr, "tessera-view: %s\n", context.status().toString().c_str());
    return 1;
  }
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui_ImplOpenGL3_Init("#version 330 core");
  int rc = 1;
  {
    auto target = OffscreenTarget::create(options.width, options.height, options.msaa);
    auto viewer = target.isOk() ? Viewer::create(options, connection)
                                : Expected<std::unique_ptr<Viewer>>(target.status());
    if (!viewer.isOk()) {
      std::fprintf(stderr, "tessera-view: %s\n", viewer.status().toString().c_str());
    } else {
      rc = renderFrames(options, connection, **viewer, **target);
    }
  }  // the GL objects go while the context is current
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext();
  return rc;
}

}  // namespace tessera::view

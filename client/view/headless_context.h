// An OpenGL 3.3 core context with no window and no X server, for
// --screenshot: EGL on Mesa's surfaceless platform
// (EGL_MESA_platform_surfaceless), made current with no surface
// (EGL_KHR_surfaceless_context). Everything is drawn into a framebuffer
// object (offscreen_target.h). Nothing here uses GLFW, whose Debian 3.3
// build has no null platform, so DISPLAY need not be set.
#pragma once

#include <memory>

#include "core/util/status.h"

namespace tessera::view {

class HeadlessContext {
 public:
  // The context, current on the calling thread; an error naming the EGL
  // step that failed and its EGL error code.
  static Expected<std::unique_ptr<HeadlessContext>> create();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

 private:
  HeadlessContext() = default;
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
};

}  // namespace tessera::view

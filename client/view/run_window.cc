// tessera-view in a GLFW window: OpenGL 3.3 core with multisampling, real
// mouse and keyboard input, until the window closes or Q.
#include <algorithm>
#include <cstdio>

#include "client/view/gl.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "client/view/run.h"
#include "client/view/viewer.h"

namespace tessera::view {

namespace {

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

}  // namespace

int runWindow(const ViewOptions& options, Connection& connection) {
  glfwSetErrorCallback(
      [](int code, const char* text) { std::fprintf(stderr, "tessera-view: GLFW %d: %s\n", code, text); });
  if (!glfwInit()) {
    std::fprintf(stderr, "tessera-view: no window system (is DISPLAY set? --screenshot needs none)\n");
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, options.msaa);
  const std::string title = "tessera-view: document " + std::to_string(options.document);
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, title.c_str(), nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "tessera-view: no OpenGL 3.3 core window (is DISPLAY set?)\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  if (options.msaa > 0) glEnable(GL_MULTISAMPLE);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  int rc = 0;
  {
    auto viewer = Viewer::create(options, connection);
    if (!viewer.isOk()) {
      std::fprintf(stderr, "tessera-view: %s\n", viewer.status().toString().c_str());
      rc = 1;
    } else {
      App& app = (*viewer)->app();
      glfwSetWindowUserPointer(window, &app);
      // Installed before ImGui's, which chain to them.
      glfwSetScrollCallback(window, onScroll);
      glfwSetKeyCallback(window, onKey);
      ImGui_ImplGlfw_InitForOpenGL(window, true);
      ImGui_ImplOpenGL3_Init("#version 330 core");
      MouseTool mouse;
      while (!glfwWindowShouldClose(window) && !app.quit) {
        glfwPollEvents();
        int width = 0, height = 0;
        glfwGetFramebufferSize(window, &width, &height);
        (*viewer)->update(width, height);
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        mouse.update(readMouse(window, app, width, height), app, (*viewer)->points(), width, height);
        (*viewer)->draw(width, height);
        glfwSwapBuffers(window);
      }
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
    }
  }  // the renderer's GL objects go while the context is current
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return rc;
}

}  // namespace tessera::view

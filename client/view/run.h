// The two ways tessera-view runs one connection: in a GLFW window, or
// headless for --screenshot (EGL surfaceless, no display needed). Each
// returns the process's exit code.
#pragma once

#include "client/view/connection.h"
#include "client/view/view_options.h"

namespace tessera::view {

int runWindow(const ViewOptions& options, Connection& connection);
int runHeadless(const ViewOptions& options, Connection& connection);

}  // namespace tessera::view

// tessera-view: a viewer and editor for one document of a tessera-server
// (docs/VIEWER.md). The Connection keeps the
// document current on its own thread. In a window (run_window.cc) each frame
// uploads changed regions, draws them, handles picking and dragging of
// control vertices, and draws the HUD and the axes gizmo. With --screenshot
// it renders headless with no display at all (run_headless.cc), writes a
// PNG and exits.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "client/view/connection.h"
#include "client/view/run.h"
#include "client/view/view_options.h"
#include "tessera/version.h"

int main(int argc, char** argv) {
  using namespace tessera::view;
  const auto started = std::chrono::steady_clock::now();
  auto options = parseViewOptions(std::vector<std::string>(argv + 1, argv + argc));
  if (!options.isOk()) {
    std::fprintf(stderr, "tessera-view: %s\nRun 'tessera-view --help' for the options.\n",
                 options.status().message().c_str());
    return 2;
  }
  if (options->help) {
    std::fputs(viewHelp().c_str(), stdout);
    return 0;
  }
  if (options->version) {
    std::printf("tessera-view %s\n", tessera::kVersion);
    return 0;
  }
  options->started = started;
  auto connection = Connection::open(*options);
  if (!connection.isOk()) {
    std::fprintf(stderr, "tessera-view: %s\n", connection.status().toString().c_str());
    return 1;
  }
  return options->screenshot.empty() ? runWindow(*options, **connection)
                                     : runHeadless(*options, **connection);
}

// The headless self-tests of tessera-view (docs/VIEWER.md, "Headless mode").
// Both feed synthetic input through the same MouseTool and handleKey as the
// window's real input.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "client/view/input.h"

namespace tessera::view {

// --drag DX,DY: hover over the control vertex nearest the centre, press, move
// by (dx, dy) in 10 steps, release. The frames then wait until every edit it
// made has come back as a delta.
class DragScript {
 public:
  DragScript(int dx, int dy) : dx_(static_cast<float>(dx)), dy_(static_cast<float>(dy)) {}
  bool done() const { return step_ > kSteps + 2; }
  // Nothing when no control vertex is visible.
  std::optional<MouseInput> next(const App& app, const std::vector<ControlPoint>& points, int width,
                                 int height);

 private:
  static constexpr int kSteps = 10;
  float dx_, dy_, x0_ = 0, y0_ = 0;
  int step_ = 0;
};

// --edit-keys: click the visible control vertex nearest the centre,
// shift+click the visible neighbour (levelNeighbours) nearest to it on screen, then
// press E, 2, K, Ctrl+Z three times and Ctrl+Y, each once the edits before it have
// come back, noting the surface hash (DocumentView::surfaceHash) at the
// start and after each key. Needs Connection::hashSurfaces(true).
class KeyScript {
 public:
  struct Frame {
    std::optional<MouseInput> mouse;  // this frame's synthetic mouse, if any
    std::string error;                // nothing to pick: the script cannot run
  };
  // Call once per frame, before the mouse update; may press a key.
  Frame next(App& app, const RegionMap& regions, const std::vector<ControlPoint>& points,
             const ConnectionStats& stats, int width, int height);
  bool done() const { return done_; }
  // "edge v2:5-v2:9; surface hashes: start=H E=H K=H undo=H undo=H redo=H"
  std::string report() const;

 private:
  int step_ = 0;
  bool done_ = false;
  float ax_ = 0, ay_ = 0, bx_ = 0, by_ = 0;
  std::string edge_;
  std::vector<std::pair<std::string, uint64_t>> hashes_;
};

}  // namespace tessera::view

// Viewer: one frame of tessera-view, shared by the window (run_window.cc)
// and the headless renderer (run_headless.cc). update() takes what the
// connection has published (regions, control vertices, framing, profile
// changes, undo and redo); draw() draws the surface, the control vertices
// and selections, and the ImGui overlays (HUD, axes gizmo) into the bound
// framebuffer. The caller begins the ImGui frame between the two, so that
// its input sees ImGui's capture flags. Needs a current OpenGL 3.3 core
// context and an ImGui context with the OpenGL 3 backend for its whole life.
#pragma once

#include <chrono>
#include <memory>
#include <vector>

#include "client/view/connection.h"
#include "client/view/control_cage.h"
#include "client/view/control_points.h"
#include "client/view/input.h"
#include "client/view/refinement.h"
#include "client/view/renderer.h"
#include "client/view/view_options.h"

namespace tessera::view {

class Viewer {
 public:
  static Expected<std::unique_ptr<Viewer>> create(const ViewOptions& options, Connection& connection);

  // Reads the connection's news for a frame of this size; its stats.
  ConnectionStats update(int width, int height);
  // Draws the frame, ending the ImGui frame the caller began.
  void draw(int width, int height);

  App& app() { return app_; }
  const RegionMap& regions() const { return regions_; }
  const std::vector<ControlPoint>& points() const { return points_; }
  // The cage of the points' level once it arrived (--cage, key O).
  const ControlCage* cage() const { return cage_.get(); }
  // Its edges drawn in the last frame: both ends shown and facing the eye.
  size_t cageEdgesDrawn() const { return cageEdgesDrawn_; }
  int64_t triangles() const { return renderer_->triangles(); }
  // A view-dependent subscription: the camera moved since the view last
  // sent (it goes within the send interval), or none was sent yet.
  bool cameraPending() const { return cameraPending_; }

 private:
  Viewer(const ViewOptions& options, Connection& connection);
  void drawSelections(const DrawOptions& draw);
  std::optional<double> tensionOfPicked() const;
  // A morph document: advances a playing morph and asks for the frame at
  // the time shown once the previous one has arrived.
  void followMorph(double dt);
  // A view-dependent subscription: sends the camera when it moved.
  void sendView(int width, int height, std::chrono::steady_clock::time_point now);
  std::optional<View> lastView_;
  bool cameraPending_ = true;
  std::chrono::steady_clock::time_point lastViewSent_{};

  const ViewOptions options_;
  Connection& connection_;
  std::unique_ptr<Renderer> renderer_;
  App app_;
  RegionMap regions_;
  std::vector<ControlPoint> points_;
  ConnectionStats stats_;
  uint64_t seenUpdates_ = 0;
  bool synced_ = false, framed_ = false;
  int pointsLevel_ = -1;
  std::shared_ptr<const ControlCage> cage_;
  int requestedCageLevel_ = -1;
  size_t cageEdgesDrawn_ = 0;
  std::shared_ptr<const KeyPositionMap> keyPositions_;  // a 2D morph's texture coordinates
  double shownT_ = 0;                                   // the time of the frame on screen
  float pointDiameter_ = 0.01f;
  RefineTiming refineTiming_;
  double fps_ = 0, bytesPerSecond_ = 0;
  uint64_t bytesAtSample_ = 0;
  std::chrono::steady_clock::time_point lastFrame_, lastSample_;
  // The time last asked for, the snapshot count that answers it, and the
  // direction a playing morph runs in (it bounces between the keys).
  double requestedT_ = -1;
  bool requestedExact_ = true;  // the last request was a subscription at t, not control points
  uint64_t answeredAt_ = 0, coarseAnsweredAt_ = 0;
  float playDirection_ = 1;
};

}  // namespace tessera::view

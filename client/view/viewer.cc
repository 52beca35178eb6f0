#include "client/view/viewer.h"

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "client/view/hud.h"
#include "core/io/png_image.h"

namespace tessera::view {

namespace {

using Clock = std::chrono::steady_clock;

std::vector<V3> visible(const std::vector<ControlPoint>& points, V3 eye) {
  std::vector<V3> out;
  for (const ControlPoint& p : points)
    if (dot(p.normal, eye - p.position) >= 0) out.push_back(p.position);
  return out;
}

}  // namespace

Viewer::Viewer(const ViewOptions& options, Connection& connection)
    : options_(options), connection_(connection) {
  app_.connection = &connection;
  app_.toggles.wireframe = options.wireframe;
  app_.toggles.regionColours = options.regionColours;
  app_.toggles.showControls = options.controlPoints;
  app_.toggles.showCage = options.cage;
  app_.toggles.matcap = options.matcap;
  app_.toggles.showGizmo = options.gizmo;
  app_.toggles.hudCollapsed = options.hudCollapsed;
  app_.toggles.controlLevel = options.controlLevel;
  app_.toggles.refine = options.refine;
  app_.toggles.baseLevel = static_cast<int>(options.baseLevel);
  app_.toggles.maxLevel = static_cast<int>(options.maxLevel);
  app_.toggles.angle = static_cast<float>(options.angle);
  app_.toggles.morph = connection.isMorph();
  app_.toggles.views = connection.viewDependent();
  app_.toggles.tolerance = static_cast<float>(options.tolerancePixels);
  app_.toggles.levelColours = options.levelColours;
  if (options.morphT) {
    app_.toggles.morphT = static_cast<float>(*options.morphT);
    app_.toggles.morphShown = true;
    requestedT_ = shownT_ = *options.morphT;  // subscribed at it already
  }
  lastFrame_ = lastSample_ = Clock::now();
}

Expected<std::unique_ptr<Viewer>> Viewer::create(const ViewOptions& options, Connection& connection) {
  std::unique_ptr<Viewer> v(new Viewer(options, connection));
  TESSERA_ASSIGN_OR_RETURN(v->renderer_, Renderer::create());
  if (!connection.imageFrom().empty()) {
    // A 2D morph document: its images on the surface, seen as images are.
    TESSERA_ASSIGN_OR_RETURN(Image from, decodePng(connection.imageFrom(), "the morph's first image"));
    TESSERA_ASSIGN_OR_RETURN(Image to, decodePng(connection.imageTo(), "the morph's second image"));
    v->renderer_->setMorphImages(from, to);
    v->app_.camera.lookAtImagePlane();
  }
  return v;
}

ConnectionStats Viewer::update(int width, int height) {
  const auto now = Clock::now();
  const double dt = std::chrono::duration<double>(now - lastFrame_).count();
  lastFrame_ = now;
  if (dt > 0) fps_ = fps_ == 0 ? 1 / dt : 0.9 * fps_ + 0.1 / dt;
  stats_ = connection_.stats();
  if (const double since = std::chrono::duration<double>(now - lastSample_).count(); since >= 1) {
    bytesPerSecond_ = static_cast<double>(stats_.bytesReceived - bytesAtSample_) / since;
    bytesAtSample_ = stats_.bytesReceived;
    lastSample_ = now;
  }
  if (auto positions = connection_.keyPositions(); positions != keyPositions_) {
    keyPositions_ = std::move(positions);
    synced_ = false;
  }
  if (stats_.regionUpdates != seenUpdates_) {
    seenUpdates_ = stats_.regionUpdates;
    regions_ = connection_.regions();
    pointsLevel_ = -1;
    synced_ = false;
  }
  if (app_.toggles.refine > 0) {
    refineTiming_ = refineAndStream(regions_, app_.toggles.refine, *renderer_);
    synced_ = false;
  } else if (!synced_) {
    renderer_->sync(regions_, keyPositions_);
    synced_ = true;
  }
  V3 lo, hi;
  const bool haveBounds = bounds(regions_, &lo, &hi);
  if (pointsLevel_ != app_.toggles.controlLevel) {
    points_ = controlPoints(regions_, app_.toggles.controlLevel);
    pointsLevel_ = app_.toggles.controlLevel;
    if (haveBounds) pointDiameter_ = controlPointDiameter(lo, hi, points_.size());
  }
  // The cage's faces are asked for once per level shown (they never change).
  if (app_.toggles.showCage && requestedCageLevel_ != app_.toggles.controlLevel) {
    connection_.requestCage(app_.toggles.controlLevel);
    requestedCageLevel_ = app_.toggles.controlLevel;
  }
  if (auto cage = connection_.cage(); cage && cage->level == app_.toggles.controlLevel)
    cage_ = std::move(cage);
  // Fit to view on the first snapshot and on F: to the surface's vertices,
  // whose projection can be much smaller than their bounding box's.
  if ((!framed_ || app_.frameRequested) && haveBounds) {
    std::vector<V3> surface;
    for (const auto& [id, mesh] : regions_)
      for (const Vec3& p : mesh->positions)
        surface.push_back({static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])});
    app_.camera.fit(surface, static_cast<float>(width) / static_cast<float>(std::max(height, 1)));
    framed_ = true;
    app_.frameRequested = false;
  }
  if (app_.toggles.views && framed_ && !app_.toggles.frozen) sendView(width, height, now);
  if (app_.toggles.profileChanged) {
    app_.toggles.profileChanged = false;
    connection_.changeProfile(static_cast<uint32_t>(app_.toggles.baseLevel),
                              static_cast<uint32_t>(app_.toggles.maxLevel), app_.toggles.angle);
  }
  followMorph(dt);
  if (app_.undo) connection_.undo(), app_.undo = false;
  if (app_.redo) connection_.redo(), app_.redo = false;
  return stats_;
}

// The camera as a view (docs/VIEWS.md "The view"), sent when it moved and
// at most every kViewInterval: the server applies one per interval anyway.
void Viewer::sendView(int width, int height, Clock::time_point now) {
  constexpr auto kViewInterval = std::chrono::milliseconds(50);
  const Mat4 m = app_.camera.view();
  View v;
  const V3 eye = app_.camera.eye(), target = app_.camera.target();
  v.eye = Vec3(eye.x, eye.y, eye.z);
  v.forward = Vec3(target.x - eye.x, target.y - eye.y, target.z - eye.z);
  v.up = Vec3(m[1], m[5], m[9]);
  v.fovYRadians = app_.camera.fovY();
  v.nearDistance = app_.camera.nearDistance();
  v.width = std::max(width, 1);
  v.height = std::max(height, 1);
  v.tolerancePixels = app_.toggles.tolerance;
  if (!v.check().isOk()) return;
  const double scale = std::max(1e-9, static_cast<double>(app_.camera.distance()));
  const bool moved = !lastView_ || (lastView_->eye - v.eye).norm() > 1e-4 * scale ||
                     (lastView_->forward.normalized() - v.forward.normalized()).norm() > 1e-5 ||
                     (lastView_->up - v.up).norm() > 1e-5 || lastView_->width != v.width ||
                     lastView_->height != v.height || lastView_->tolerancePixels != v.tolerancePixels;
  cameraPending_ = moved;
  if (!moved || now - lastViewSent_ < kViewInterval) return;
  cameraPending_ = false;
  connection_.setView(v);
  lastView_ = v;
  lastViewSent_ = now;
}

void Viewer::followMorph(double dt) {
  ViewToggles& t = app_.toggles;
  if (!t.morph || !t.morphShown) return;
  if (t.playing) {
    t.morphT += playDirection_ * static_cast<float>(options_.morphRate * dt);
    if (t.morphT >= 1) t.morphT = 1, playDirection_ = -1;
    if (t.morphT <= 0) t.morphT = 0, playDirection_ = 1;
  }
  // Frames at hundredths of t, so viewers playing together share them (the
  // server encodes each once); one frame in flight at a time. Playing goes
  // through the coarse stream (docs/PERFORMANCE.md "Streaming a morph":
  // about 55 times fewer bytes than the regions of every frame); paused,
  // the exact surface at t, with the keys' finer edits and pickable ids.
  const bool inFlight = stats_.snapshots < answeredAt_ || stats_.coarseFrames < coarseAnsweredAt_;
  if (!inFlight && requestedT_ >= 0) shownT_ = requestedT_;
  const double wanted = std::round(static_cast<double>(t.morphT) * 100) / 100;
  const bool coarse = (t.playing || options_.morphCoarse) && connection_.canStreamCoarse();
  if (!inFlight && (wanted != requestedT_ || requestedExact_ == coarse)) {
    if (coarse) {
      connection_.playMorphTime(wanted);
      coarseAnsweredAt_ = stats_.coarseFrames + 1;
    } else {
      connection_.showMorphTime(wanted);
      answeredAt_ = stats_.snapshots + 1;
    }
    requestedT_ = wanted;
    requestedExact_ = !coarse;
  }
  // Edits go to the key nearer the time shown.
  connection_.setEditKey(wanted > 0.5 ? 1 : 0);
}

// Collaborators' selections in cyan, this viewer's pick in red. Two
// selected vertices are an edge, drawn as a dotted line between them.
void Viewer::drawSelections(const DrawOptions& draw) {
  auto mark = [&](const std::vector<uint64_t>& ids, std::array<float, 3> colour) {
    std::vector<V3> ends;
    for (uint64_t id : ids) {
      auto it = std::lower_bound(points_.begin(), points_.end(), id,
                                 [](const ControlPoint& p, uint64_t v) { return p.id < v; });
      if (it != points_.end() && it->id == id) ends.push_back(it->position);
    }
    renderer_->drawPoints(ends, PointStyle{colour, 1.8f, 6, 18}, draw);
    if (ends.size() == 2)
      renderer_->drawPoints(segmentPoints(ends[0], ends[1], 24), PointStyle{colour, 0.6f, 2, 6}, draw);
  };
  for (const Collaborator& c : connection_.collaborators())
    if (!c.self) mark(c.selectedVertices, {0.2f, 0.9f, 1.0f});
  std::vector<uint64_t> own;
  if (app_.picked) own.push_back(*app_.picked);
  if (app_.edgeEnd) own.push_back(*app_.edgeEnd);
  mark(own, {1.0f, 0.2f, 0.2f});
}

void Viewer::draw(int width, int height) {
  glViewport(0, 0, width, height);
  glClearColor(0.16f, 0.18f, 0.22f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  DrawOptions draw;
  draw.view = app_.camera.view();
  draw.projection =
      app_.camera.projection(static_cast<float>(width) / static_cast<float>(std::max(height, 1)));
  draw.wireframe = app_.toggles.wireframe;
  draw.regionColours = app_.toggles.regionColours;
  draw.levelColours = app_.toggles.views && app_.toggles.levelColours;
  draw.matcap = app_.toggles.matcap;
  draw.pointDiameter = pointDiameter_;
  draw.pixelsPerUnit = app_.camera.pixelsPerUnit(height);
  draw.morphT = static_cast<float>(shownT_);
  renderer_->drawSurface(draw);
  cageEdgesDrawn_ = 0;
  const bool cageShown = app_.toggles.showCage && cage_ && cage_->level == app_.toggles.controlLevel;
  if (cageShown) {
    const std::vector<V3> segments = cageSegments(*cage_, points_, app_.camera.eye());
    cageEdgesDrawn_ = segments.size() / 2;
    renderer_->drawLines(segments, {1.0f, 0.25f, 0.82f}, draw);  // the browser page's magenta
  }
  if (app_.toggles.showControls) {
    renderer_->drawPoints(visible(points_, app_.camera.eye()), PointStyle{}, draw);
    drawSelections(draw);
  }
  if (app_.toggles.showGizmo) drawGizmo(draw.view, width, height);
  if (options_.hud) {
    HudFacts facts{.fps = fps_,
                   .triangles = renderer_->triangles(),
                   .receivedTriangles = refineTiming_.receivedTriangles,
                   .refineMs = refineTiming_.refineMs,
                   .uploadMs = refineTiming_.uploadMs,
                   .regions = renderer_->regionCount(),
                   .bytesPerSecond = bytesPerSecond_,
                   .controlPoints = points_.size(),
                   .cageFacesBySize = cageShown ? cage_->facesBySize : std::map<uint32_t, size_t>{},
                   .cageEdges = cageShown ? cage_->edges.size() : 0,
                   .cageEdgesDrawn = cageEdgesDrawn_,
                   .pickedVertex = app_.picked,
                   .pickedEdgeEnd = app_.edgeEnd,
                   .pickedTension = tensionOfPicked(),
                   .stats = stats_,
                   .collaborators = connection_.collaborators(),
                   .editKey = connection_.editKey()};
    drawHud(facts, app_.toggles, width, height);
  }
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

std::optional<double> Viewer::tensionOfPicked() const {
  if (!app_.picked) return std::nullopt;
  auto it = app_.interpolating.find(*app_.picked);
  return it == app_.interpolating.end() ? std::nullopt : std::optional<double>(it->second);
}

}  // namespace tessera::view

// The Dear ImGui overlays of tessera-view: the HUD (frame rate, triangles,
// document version, edit-to-delta latency, the display toggles, the LOD
// profile, collaborators) and the axes gizmo. The HUD sits in the top-left
// corner, at most 36% of the frame wide and 42% high (its content scrolls
// beyond that), so it never covers the middle of the frame, where
// fit-to-view puts the model's centre; it collapses to its title line.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "client/view/connection.h"
#include "client/view/view_math.h"

namespace tessera::view {

// What the user can change from the HUD (and the keyboard).
struct ViewToggles {
  bool wireframe = false;
  bool regionColours = false;
  bool showControls = false;  // control vertices; off by default (--control-points, V)
  bool showCage = false;      // their level's polygons (--cage, O)
  bool matcap = false;        // M
  bool showGizmo = true;      // G
  bool hudCollapsed = false;  // H
  int controlLevel = 0;
  int refine = 0;  // client-side refinement: splits per edge, 0..2
  // LOD profile; `profileChanged` is set when the user applies a new one.
  int baseLevel = 1, maxLevel = 3;
  float angle = 15;
  bool profileChanged = false;
  // A morph document (docs/VIEWER.md, "Morph documents"): the time shown
  // (from the slider, the , and . keys, or playing), and whether it plays (P).
  bool morph = false;  // the document has two keys
  float morphT = 0;
  bool morphShown = false;  // a time is shown (else key 0 live)
  bool playing = false;
  // A view-dependent subscription (--views): the tolerance sent with the
  // camera, a frozen view (X: the camera moves, the tiles stay as sent) and
  // tiles coloured by level (L).
  bool views = false;
  float tolerance = 1;
  bool frozen = false;
  bool levelColours = false;
};

struct HudFacts {
  double fps = 0;
  int64_t triangles = 0;  // drawn: refined when refining
  int64_t receivedTriangles = 0;
  double refineMs = 0, uploadMs = 0;  // this frame's refinement and its upload
  size_t regions = 0;
  double bytesPerSecond = 0;
  size_t controlPoints = 0;
  // The cage of the points' level: faces by corner count, edges, and the
  // edges drawn (both ends shown and facing the eye); none until it arrives.
  std::map<uint32_t, size_t> cageFacesBySize;
  size_t cageEdges = 0, cageEdgesDrawn = 0;
  std::optional<uint64_t> pickedVertex;
  std::optional<uint64_t> pickedEdgeEnd;  // with pickedVertex: the picked edge's other end
  std::optional<double> pickedTension;    // the picked vertex interpolates, with this tension
  ConnectionStats stats;
  std::vector<Collaborator> collaborators;
  uint32_t editKey = 0;  // the morph key this viewer's edits go to
};

// The HUD's largest size as fractions of the frame.
inline constexpr float kHudMaxWidth = 0.36f, kHudMaxHeight = 0.42f;

// Builds the HUD window for a frame of this size; call between
// ImGui::NewFrame and ImGui::Render. Follows toggles.hudCollapsed and
// writes back a collapse made with the mouse.
void drawHud(const HudFacts& facts, ViewToggles& toggles, int width, int height);

// The axes gizmo (gizmo.h) in the bottom-left corner, behind any ImGui window.
void drawGizmo(const Mat4& view, int width, int height);

// "v2:17" for a packed vertex id.
std::string vertexName(uint64_t packed);

}  // namespace tessera::view

// The Dear ImGui HUD of tessera-view: frame rate, triangles, edit-to-delta
// latency, received bytes per second, document version, collaborators and
// their selections, plus the display toggles and the LOD profile.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "client/view/connection.h"

namespace tessera::view {

// What the user can change from the HUD (and the keyboard).
struct ViewToggles {
  bool wireframe = false;
  bool regionColours = false;
  bool showControls = true;
  int controlLevel = 0;
  int refine = 0;  // client-side refinement: splits per edge, 0..2
  // LOD profile; `profileChanged` is set when the user applies a new one.
  int baseLevel = 1, maxLevel = 3;
  float angle = 15;
  bool profileChanged = false;
};

struct HudFacts {
  double fps = 0;
  int64_t triangles = 0;  // drawn: refined when refining
  int64_t receivedTriangles = 0;
  double refineMs = 0, uploadMs = 0;  // this frame's refinement and its upload
  size_t regions = 0;
  double bytesPerSecond = 0;
  size_t controlPoints = 0;
  std::optional<uint64_t> pickedVertex;
  std::optional<uint64_t> pickedEdgeEnd;  // with pickedVertex: the picked edge's other end
  ConnectionStats stats;
  std::vector<Collaborator> collaborators;
};

// Builds the HUD window; call between ImGui::NewFrame and ImGui::Render.
void drawHud(const HudFacts& facts, ViewToggles& toggles);

// "v2:17" for a packed vertex id.
std::string vertexName(uint64_t packed);

}  // namespace tessera::view

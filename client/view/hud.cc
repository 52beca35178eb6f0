#include "client/view/hud.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "client/view/gizmo.h"
#include "core/hierarchy/ids.h"

namespace tessera::view {

namespace {

// "812", "48.2k", "2.61M": counts read at a glance.
std::string shortCount(double n) {
  char text[32];
  if (n < 1e4) {
    std::snprintf(text, sizeof text, "%.0f", n);
  } else if (n < 1e6) {
    std::snprintf(text, sizeof text, "%.1fk", n / 1e3);
  } else {
    std::snprintf(text, sizeof text, "%.2fM", n / 1e6);
  }
  return text;
}

void drawStatus(const HudFacts& f, const ViewToggles& t) {
  ImGui::Text("%zu regions, %.1f KiB/s", f.regions, f.bytesPerSecond / 1024);
  if (t.refine > 0) {
    ImGui::Text("refined from %s: %.1f + %.1f ms",
                shortCount(static_cast<double>(f.receivedTriangles)).c_str(), f.refineMs, f.uploadMs);
  }
  if (f.stats.lastLatencyMs >= 0) {
    ImGui::Text("edit to delta %.1f ms (max %.1f)", f.stats.lastLatencyMs, f.stats.maxLatencyMs);
  }
  if (!f.stats.connected) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "disconnected: reconnecting");
  if (f.stats.reconnects > 0)
    ImGui::Text("reconnected %llu times", static_cast<unsigned long long>(f.stats.reconnects));
  if (!f.stats.lastError.empty()) ImGui::TextWrapped("last error: %s", f.stats.lastError.c_str());
}

// A morph document's time: the slider shows (and sets) t; edits go to the
// key nearer the time shown.
void drawMorph(const HudFacts& f, ViewToggles& t) {
  if (!t.morph) return;
  ImGui::PushItemWidth(140);
  if (ImGui::SliderFloat("t", &t.morphT, 0.0f, 1.0f, "%.3f")) t.morphShown = true;
  ImGui::PopItemWidth();
  ImGui::SameLine();
  if (ImGui::SmallButton(t.playing ? "pause" : "play")) t.playing = !t.playing, t.morphShown = true;
  ImGui::TextDisabled("%s; edits: key %u",
                      !t.morphShown         ? "key 0 live"
                      : f.stats.coarseShown ? "coarse, refined here"
                                            : "exact at t",
                      f.editKey);
}

void drawToggles(const HudFacts& f, ViewToggles& t) {
  ImGui::Checkbox("wire W", &t.wireframe);
  ImGui::SameLine();
  ImGui::Checkbox("regions C", &t.regionColours);
  ImGui::Checkbox("matcap M", &t.matcap);
  ImGui::SameLine();
  ImGui::Checkbox("points V", &t.showControls);
  ImGui::SameLine();
  ImGui::Checkbox("cage O", &t.showCage);
  if (t.showCage) {
    std::string faces;
    for (const auto& [corners, count] : f.cageFacesBySize)
      faces += (faces.empty() ? "" : ", ") + std::to_string(count) + " of " + std::to_string(corners);
    ImGui::Text("cage: %s; %zu of %zu edges shown", faces.empty() ? "asked for" : faces.c_str(),
                f.cageEdgesDrawn, f.cageEdges);
  }
  if (!t.showControls) return;
  if (f.pickedVertex && f.pickedEdgeEnd) {
    ImGui::Text("edge %s - %s", vertexName(*f.pickedVertex).c_str(), vertexName(*f.pickedEdgeEnd).c_str());
    ImGui::TextDisabled("E sharp, 1-4 semi-sharp, Shift+E smooth");
  } else {
    ImGui::Text("%zu points; picked %s", f.controlPoints,
                f.pickedVertex ? vertexName(*f.pickedVertex).c_str() : "none");
    if (f.pickedVertex) ImGui::TextDisabled("shift+click a neighbour: an edge");
    if (f.pickedVertex && f.pickedTension) {
      ImGui::Text("interpolating, tension %.3g", *f.pickedTension);
      ImGui::TextDisabled("I plain, = tighter, - looser");
    } else if (f.pickedVertex) {
      ImGui::TextDisabled("I: make it interpolating");
    }
  }
}

// A view-dependent subscription: its tolerance, its tiles and the keys
// that show what was sent.
void drawViews(const HudFacts& f, ViewToggles& t) {
  if (!t.views) return;
  ImGui::PushItemWidth(120);
  ImGui::SliderFloat("tolerance px", &t.tolerance, 0.25f, 16.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  ImGui::PopItemWidth();
  ImGui::Text("%zu tiles, %s tris%s", f.regions, shortCount(static_cast<double>(f.triangles)).c_str(),
              f.stats.viewComplete ? "" : " (loading)");
  ImGui::Checkbox("freeze X", &t.frozen);
  ImGui::SameLine();
  ImGui::Checkbox("levels L", &t.levelColours);
}

// What is changed less often, folded away until asked for.
void drawMore(const HudFacts& f, ViewToggles& t) {
  if (!ImGui::CollapsingHeader("more")) return;
  ImGui::Checkbox("axes G", &t.showGizmo);
  ImGui::PushItemWidth(90);
  ImGui::SliderInt("refine R", &t.refine, 0, 2);
  ImGui::SliderInt("point level [ ]", &t.controlLevel, 0, 10);
  ImGui::Separator();
  ImGui::TextDisabled("LOD profile");
  ImGui::SliderInt("base level", &t.baseLevel, 0, 8);
  ImGui::SliderInt("max level", &t.maxLevel, 0, 8);
  ImGui::SliderFloat("angle", &t.angle, 1, 90, "%.0f deg");
  ImGui::PopItemWidth();
  if (t.baseLevel > t.maxLevel) t.baseLevel = t.maxLevel;
  if (ImGui::Button("subscribe")) t.profileChanged = true;
  ImGui::Text("%.0f KiB received, %llu edits timed", f.stats.bytesReceived / 1024.0,
              static_cast<unsigned long long>(f.stats.latencySamples));
  ImGui::Text("collaborators: %zu", f.collaborators.size());
  for (const Collaborator& c : f.collaborators) {
    std::string selection;
    for (size_t i = 0; i < c.selectedVertices.size() && i < 4; ++i)
      selection += " " + vertexName(c.selectedVertices[i]);
    if (c.selectedVertices.size() > 4) selection += " ...";
    ImGui::BulletText("%s%s (session %llu)%s%s", c.name.c_str(), c.self ? " [you]" : "",
                      static_cast<unsigned long long>(c.sessionId), selection.empty() ? "" : ":",
                      selection.c_str());
  }
}

}  // namespace

std::string vertexName(uint64_t packed) {
  return VertexId::fromPacked(packed).toString();
}

void drawHud(const HudFacts& f, ViewToggles& t, int width, int height) {
  // The collapsed HUD is the window's title line, which carries the facts
  // one wants at a glance; the full one adds the rest below it.
  char title[160];
  std::snprintf(title, sizeof title, "v%llu  %s tris  %.0f fps%s###tessera-view",
                static_cast<unsigned long long>(f.stats.version),
                shortCount(static_cast<double>(f.triangles)).c_str(), f.fps,
                f.stats.ready ? "" : "  (waiting)");
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
  // At least as wide as the title, which a collapsed window does not grow to.
  const float titleWidth = ImGui::CalcTextSize(title, nullptr, true).x + 2 * ImGui::GetFontSize() +
                           2 * ImGui::GetStyle().FramePadding.x;
  const float maxWidth = kHudMaxWidth * static_cast<float>(width);
  ImGui::SetNextWindowSizeConstraints(ImVec2(std::min(titleWidth, maxWidth), 0),
                                      ImVec2(maxWidth, kHudMaxHeight * static_cast<float>(height)));
  ImGui::SetNextWindowBgAlpha(0.6f);
  ImGui::SetNextWindowCollapsed(t.hudCollapsed, ImGuiCond_Always);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing;
  const bool open = ImGui::Begin(title, nullptr, flags);
  // A click on the title's arrow collapses or expands it too.
  t.hudCollapsed = ImGui::IsWindowCollapsed();
  if (open) {
    drawStatus(f, t);
    drawMorph(f, t);
    drawViews(f, t);
    drawToggles(f, t);
    drawMore(f, t);
    ImGui::TextDisabled("H fold  F fit  Q quit");
  }
  ImGui::End();
}

void drawGizmo(const Mat4& view, int width, int height) {
  static constexpr ImU32 kColours[3] = {IM_COL32(232, 72, 72, 255), IM_COL32(96, 204, 80, 255),
                                        IM_COL32(80, 136, 240, 255)};
  static constexpr const char* kNames[3] = {"X", "Y", "Z"};
  const GizmoPlacement at = gizmoPlacement(width, height);
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const ImVec2 centre(at.cx, at.cy);
  draw->AddCircleFilled(centre, at.radius + 8, IM_COL32(0, 0, 0, 60));
  for (const GizmoAxis& a : gizmoAxes(view)) {
    const ImVec2 tip(at.cx + a.dx * at.radius, at.cy + a.dy * at.radius);
    draw->AddLine(centre, tip, kColours[a.axis], 2.5f);
    draw->AddCircleFilled(tip, 6.5f, kColours[a.axis]);
    const ImVec2 glyph = ImGui::CalcTextSize(kNames[a.axis]);
    draw->AddText(ImVec2(tip.x - glyph.x / 2, tip.y - glyph.y / 2), IM_COL32(16, 16, 16, 255),
                  kNames[a.axis]);
  }
}

}  // namespace tessera::view

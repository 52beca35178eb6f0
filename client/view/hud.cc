#include "client/view/hud.h"

#include <imgui.h>

#include "core/hierarchy/ids.h"

namespace tessera::view {

std::string vertexName(uint64_t packed) {
  return VertexId::fromPacked(packed).toString();
}

void drawHud(const HudFacts& f, ViewToggles& t) {
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.75f);
  ImGui::Begin("tessera-view", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::Text("%.1f fps   %lld triangles in %zu regions", f.fps, static_cast<long long>(f.triangles),
              f.regions);
  if (t.refine > 0) {
    ImGui::Text("refined: %lld triangles from %lld, %.2f ms + %.2f ms upload",
                static_cast<long long>(f.triangles), static_cast<long long>(f.receivedTriangles), f.refineMs,
                f.uploadMs);
  }
  ImGui::Text("document version %llu%s", static_cast<unsigned long long>(f.stats.version),
              f.stats.ready ? "" : " (waiting for a snapshot)");
  ImGui::Text("received %.1f KiB/s  (%.1f KiB in all)", f.bytesPerSecond / 1024,
              f.stats.bytesReceived / 1024.0);
  if (f.stats.lastLatencyMs >= 0) {
    ImGui::Text("edit to delta: %.1f ms (max %.1f ms, %llu edits)", f.stats.lastLatencyMs,
                f.stats.maxLatencyMs, static_cast<unsigned long long>(f.stats.latencySamples));
  } else {
    ImGui::Text("edit to delta: no edit yet");
  }
  if (!f.stats.connected) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "disconnected: reconnecting");
  if (f.stats.reconnects > 0)
    ImGui::Text("reconnected %llu times", static_cast<unsigned long long>(f.stats.reconnects));
  if (!f.stats.lastError.empty()) ImGui::TextWrapped("last error: %s", f.stats.lastError.c_str());

  ImGui::Separator();
  ImGui::Checkbox("wireframe (W)", &t.wireframe);
  ImGui::SameLine();
  ImGui::Checkbox("region colours (C)", &t.regionColours);
  ImGui::Checkbox("control vertices (V)", &t.showControls);
  ImGui::SliderInt("refine: splits per edge (R)", &t.refine, 0, 2);
  ImGui::SliderInt("control level ([ ])", &t.controlLevel, 0, 10);
  if (f.pickedVertex && f.pickedEdgeEnd) {
    ImGui::Text("%zu control vertices; picked the edge %s - %s", f.controlPoints,
                vertexName(*f.pickedVertex).c_str(), vertexName(*f.pickedEdgeEnd).c_str());
    ImGui::Text("E: infinitely sharp, 1-4: semi-sharp, Shift+E: smooth");
  } else {
    ImGui::Text("%zu control vertices; picked %s", f.controlPoints,
                f.pickedVertex ? vertexName(*f.pickedVertex).c_str() : "none");
    if (f.pickedVertex) ImGui::Text("shift+click a neighbour to pick an edge");
  }

  if (ImGui::CollapsingHeader("LOD profile")) {
    ImGui::SliderInt("base level", &t.baseLevel, 0, 8);
    ImGui::SliderInt("max level", &t.maxLevel, 0, 8);
    ImGui::SliderFloat("angle", &t.angle, 1, 90, "%.0f deg");
    if (t.baseLevel > t.maxLevel) t.baseLevel = t.maxLevel;
    if (ImGui::Button("subscribe")) t.profileChanged = true;
  }

  ImGui::Separator();
  ImGui::Text("collaborators: %zu", f.collaborators.size());
  for (const Collaborator& c : f.collaborators) {
    std::string selection;
    for (size_t i = 0; i < c.selectedVertices.size() && i < 4; ++i)
      selection += " " + vertexName(c.selectedVertices[i]);
    if (c.selectedVertices.size() > 4) selection += " ...";
    ImGui::BulletText("%s%s (session %llu)%s%s", c.name.c_str(), c.self ? " [you]" : "",
                      static_cast<unsigned long long>(c.sessionId), selection.empty() ? "" : ": selected",
                      selection.c_str());
  }
  ImGui::End();
}

}  // namespace tessera::view

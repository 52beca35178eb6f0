#include "client/view/self_test.h"

#include <algorithm>
#include <array>
#include <cmath>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace tessera::view {

std::optional<MouseInput> DragScript::next(const App& app, const std::vector<ControlPoint>& points, int width,
                                           int height) {
  if (step_ == 0) {
    auto hit = pickPoint(points, app.camera, width, height, width / 2.0f, height / 2.0f, 1e9f);
    if (!hit) return std::nullopt;
    auto s = app.camera.project(points[*hit].position, width, height);
    if (!s) return std::nullopt;
    x0_ = (*s)[0], y0_ = (*s)[1];
  }
  MouseInput in;
  const float t = std::clamp(static_cast<float>(step_ - 1) / kSteps, 0.0f, 1.0f);
  in.px = x0_ + dx_ * t, in.py = y0_ + dy_ * t;
  in.left = step_ >= 1 && step_ <= kSteps + 1;
  ++step_;
  return in;
}

namespace {

struct Key {
  int key, mods;
  const char* name;
};
constexpr std::array<Key, 10> kKeys = {{{GLFW_KEY_I, 0, "I"},
                                        {GLFW_KEY_EQUAL, 0, "tighter"},
                                        {GLFW_KEY_I, 0, "I-off"},
                                        {GLFW_KEY_E, 0, "E"},
                                        {GLFW_KEY_2, 0, "2"},
                                        {GLFW_KEY_K, 0, "K"},
                                        {GLFW_KEY_Z, GLFW_MOD_CONTROL, "undo"},
                                        {GLFW_KEY_Z, GLFW_MOD_CONTROL, "undo"},
                                        {GLFW_KEY_Z, GLFW_MOD_CONTROL, "undo"},
                                        {GLFW_KEY_Y, GLFW_MOD_CONTROL, "redo"}}};

// Six mouse frames: hover, press and release on each end.
constexpr int kMouseSteps = 6;

}  // namespace

KeyScript::Frame KeyScript::next(App& app, const RegionMap& regions, const std::vector<ControlPoint>& points,
                                 const ConnectionStats& stats, int width, int height) {
  Frame frame;
  if (done_) return frame;
  if (step_ == 0) {
    auto a = pickPoint(points, app.camera, width, height, width / 2.0f, height / 2.0f, 1e9f);
    if (!a) return {std::nullopt, "no visible control vertex"};
    const auto sa = app.camera.project(points[*a].position, width, height);
    std::optional<std::array<float, 2>> sb;
    uint64_t b = 0;
    float best = 1e30f;
    for (uint64_t n : levelNeighbours(regions, points[*a].id, app.toggles.controlLevel)) {
      auto it = std::find_if(points.begin(), points.end(), [n](const ControlPoint& p) { return p.id == n; });
      if (it == points.end()) continue;
      const auto s = app.camera.project(it->position, width, height);
      if (!s || !sa) continue;
      // Only a neighbour that its own pick would find.
      auto found = pickPoint(points, app.camera, width, height, (*s)[0], (*s)[1], 2.0f);
      if (!found || points[*found].id != n) continue;
      const float d = std::hypot((*s)[0] - (*sa)[0], (*s)[1] - (*sa)[1]);
      if (d < best) best = d, sb = s, b = n;
    }
    if (!sa || !sb) return {std::nullopt, "no visible neighbour of " + vertexName(points[*a].id)};
    ax_ = (*sa)[0], ay_ = (*sa)[1], bx_ = (*sb)[0], by_ = (*sb)[1];
    edge_ = vertexName(points[*a].id) + "-" + vertexName(b);
    hashes_.push_back({"start", stats.surfaceHash});
  }
  if (step_ < kMouseSteps) {
    const bool second = step_ >= 3;
    MouseInput in;
    in.px = second ? bx_ : ax_, in.py = second ? by_ : ay_;
    in.left = step_ % 3 == 1;
    in.shift = second;
    ++step_;
    frame.mouse = in;
    return frame;
  }
  // A key once the edits before it have come back (and the frame loop has
  // taken an undo or redo key).
  if (stats.editsPending > 0 || app.undo || app.redo) return frame;
  const size_t key = static_cast<size_t>(step_ - kMouseSteps);
  if (key > 0) hashes_.push_back({kKeys[key - 1].name, stats.surfaceHash});
  if (key == kKeys.size()) {
    done_ = true;
    return frame;
  }
  handleKey(app, kKeys[key].key, kKeys[key].mods);
  ++step_;
  return frame;
}

std::string KeyScript::report() const {
  std::string out = "edge " + edge_ + "; surface hashes:";
  for (const auto& [name, hash] : hashes_) out += " " + name + "=" + std::to_string(hash);
  return out;
}

}  // namespace tessera::view

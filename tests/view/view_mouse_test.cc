// tessera-view's mouse tool without a window or a server: motion counts
// from the press, so a frame in which the pointer jumps and a button goes
// down together moves nothing (commit e9d1e65; CI saw that jump become a
// drag edit of its own undo step on a starved viewer).
#include <gtest/gtest.h>

#include "client/view/input.h"

namespace tessera::view {
namespace {

MouseInput at(float px, float py, bool left = false, bool right = false) {
  MouseInput in;
  in.px = px, in.py = py, in.left = left, in.right = right;
  return in;
}

// The camera's state as the numbers a frame is drawn from.
struct Pose {
  V3 eye, target;
};
Pose poseOf(const OrbitCamera& c) {
  return {c.eye(), c.target()};
}

void expectSamePose(const Pose& a, const Pose& b, const char* when) {
  EXPECT_FLOAT_EQ(a.eye.x, b.eye.x) << when;
  EXPECT_FLOAT_EQ(a.eye.y, b.eye.y) << when;
  EXPECT_FLOAT_EQ(a.eye.z, b.eye.z) << when;
  EXPECT_FLOAT_EQ(a.target.x, b.target.x) << when;
  EXPECT_FLOAT_EQ(a.target.y, b.target.y) << when;
  EXPECT_FLOAT_EQ(a.target.z, b.target.z) << when;
}

// No control vertices are shown, so a left press orbits and a right press
// pans; neither needs a connection.
class ViewMouse : public ::testing::Test {
 protected:
  void SetUp() override { app.toggles.showControls = false; }
  void frame(const MouseInput& in) { tool.update(in, app, {}, 640, 480); }
  App app;
  MouseTool tool;
};

TEST_F(ViewMouse, APressInTheFrameThePointerJumpedNeitherOrbitsNorPans) {
  for (const bool left : {true, false}) {
    SCOPED_TRACE(left ? "left (orbit)" : "right (pan)");
    frame(at(10, 10));
    const Pose before = poseOf(app.camera);
    frame(at(210, 110, left, !left));  // arrived and pressed in one frame
    expectSamePose(poseOf(app.camera), before, "the press frame");
    frame(at(210, 110, left, !left));  // held still
    expectSamePose(poseOf(app.camera), before, "held without motion");
    frame(at(230, 110, left, !left));  // then moved: motion from the press
    const Pose moved = poseOf(app.camera);
    EXPECT_NE(moved.eye.x, before.eye.x);
    frame(at(230, 110));  // released
  }
}

TEST_F(ViewMouse, MotionAfterThePressMovesTheCameraByThatMotionOnly) {
  // Two tools, one pressing after a jump and one pressing where the pointer
  // already was, then the same 30-pixel drag: the same orbit.
  MouseTool still;
  App other;
  other.toggles.showControls = false;
  frame(at(0, 0));
  frame(at(300, 200, true));
  frame(at(330, 200, true));
  still.update(at(300, 200), other, {}, 640, 480);
  still.update(at(300, 200, true), other, {}, 640, 480);
  still.update(at(330, 200, true), other, {}, 640, 480);
  expectSamePose(poseOf(app.camera), poseOf(other.camera), "after the drag");
}

}  // namespace
}  // namespace tessera::view

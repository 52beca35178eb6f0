// Camera paths of load runs (client/replay/camera_path.h): every path gives
// a valid view at every time, each viewer its own, the same for the same
// seed, and each moves as described.
#include <gtest/gtest.h>

#include <set>

#include "client/replay/camera_path.h"

namespace tessera::replay {
namespace {

TEST(CameraPaths, EveryPathIsValidDistinctPerViewerAndRepeatable) {
  for (const char* name : {"orbit", "zoom", "fly", "random"}) {
    auto kind = cameraPathKind(name);
    ASSERT_TRUE(kind.isOk()) << name;
    CameraPaths p;
    p.kind = *kind;
    p.centre = Vec3(1, 2, 3);
    p.radius = 2;
    std::set<std::array<double, 3>> eyes;
    for (int viewer = 0; viewer < 20; ++viewer) {
      for (double t = 0; t < 30; t += 0.37) {
        const View v = cameraAt(p, viewer, t);
        ASSERT_TRUE(v.check().isOk())
            << name << " viewer " << viewer << " at " << t << ": " << v.check().message();
        EXPECT_EQ(v.eye, cameraAt(p, viewer, t).eye) << name;
      }
      const View v = cameraAt(p, viewer, 1.0);
      eyes.insert({v.eye[0], v.eye[1], v.eye[2]});
    }
    EXPECT_EQ(eyes.size(), 20u) << name << ": every viewer has its own camera";
  }
  EXPECT_FALSE(cameraPathKind("spiral").isOk());
}

TEST(CameraPaths, OrbitKeepsItsDistanceAndZoomGoesInAndOut) {
  CameraPaths p;
  p.centre = Vec3(0, 0, 0);
  p.radius = 1;
  const double d0 = cameraAt(p, 3, 0).eye.norm();
  for (double t = 0; t < 20; t += 1) EXPECT_NEAR(cameraAt(p, 3, t).eye.norm(), d0, 1e-9);
  EXPECT_GT((cameraAt(p, 3, 5).eye - cameraAt(p, 3, 0).eye).norm(), 0.5) << "a quarter turn in 5 s";
  p.kind = CameraPathKind::kZoom;
  double nearest = 1e9, farthest = 0;
  for (double t = 0; t < 10; t += 0.1) {
    nearest = std::min(nearest, cameraAt(p, 3, t).eye.norm());
    farthest = std::max(farthest, cameraAt(p, 3, t).eye.norm());
  }
  EXPECT_NEAR(nearest, 0.3, 0.01);
  EXPECT_NEAR(farthest, 3.0, 0.01);
}

}  // namespace
}  // namespace tessera::replay

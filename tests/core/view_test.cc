// A view (core/view/view.h): bad numbers are refused by name; the projected
// error and the frustum test against the analytic pinhole camera.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "core/view/view.h"

namespace tessera {
namespace {

View phone() {
  View v;
  v.eye = Vec3(0, 0, 10);
  v.forward = Vec3(0, 0, -1);
  v.up = Vec3(0, 1, 0);
  v.fovYRadians = std::numbers::pi / 3;  // 60 degrees
  v.width = 390;
  v.height = 844;
  v.tolerancePixels = 1;
  return v;
}

void expectRefused(const View& v, const std::string& naming) {
  Status s = v.check();
  EXPECT_EQ(s.code(), ErrorCode::kInvalidArgument) << naming;
  EXPECT_NE(s.message().find(naming), std::string::npos) << s.message();
}

TEST(View, BadNumbersAreRefusedByName) {
  EXPECT_TRUE(phone().check().isOk());
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  View v = phone();
  v.eye[1] = nan;
  expectRefused(v, "the eye");
  v = phone();
  v.forward = Vec3(0, 0, 0);
  expectRefused(v, "forward");
  v = phone();
  v.up = Vec3(0, 0, inf);
  expectRefused(v, "up");
  v = phone();
  v.up = Vec3(0, 0, 2);
  expectRefused(v, "parallel");
  v = phone();
  v.width = 0;
  expectRefused(v, "viewport 0 x 844");
  v = phone();
  v.height = 20000;
  expectRefused(v, "viewport 390 x 20000");
  v = phone();
  v.tolerancePixels = 0;
  expectRefused(v, "tolerance");
  v.tolerancePixels = 1e9;
  expectRefused(v, "tolerance");
  v.tolerancePixels = nan;
  expectRefused(v, "tolerance");
  v = phone();
  v.fovYRadians = 0;
  expectRefused(v, "field of view");
  v.fovYRadians = std::numbers::pi;
  expectRefused(v, "field of view");
  v = phone();
  v.projection = Projection::kOrthographic;
  v.orthoHeight = -1;
  expectRefused(v, "orthographic height");
  v = phone();
  v.nearDistance = 0;
  expectRefused(v, "near distance");
}

TEST(View, ProjectedErrorIsThePinholeCamerasAtTheNearestDepth) {
  const View v = phone();
  // A point 10 in front: one unit covers h / (2 tan(30 deg) 10) pixels.
  const double perUnit = 844 / (2 * std::tan(std::numbers::pi / 6) * 10);
  EXPECT_NEAR(v.pixelsPerUnit({Vec3(0, 0, 0), 0}), perUnit, 1e-9 * perUnit);
  EXPECT_NEAR(v.projectedError(0.01, {Vec3(3, -2, 0), 0}), 0.01 * perUnit, 1e-9);
  // A sphere is taken at its nearest depth: radius 5 at depth 10 -> depth 5.
  EXPECT_NEAR(v.pixelsPerUnit({Vec3(0, 0, 0), 5}), 2 * perUnit, 1e-9 * perUnit);
  // Around or behind the eye: the near distance bounds it.
  EXPECT_NEAR(v.pixelsPerUnit({Vec3(0, 0, 12), 1}), 844 / (2 * std::tan(std::numbers::pi / 6) * 1e-3), 1e-3);
  View o = v;
  o.projection = Projection::kOrthographic;
  o.orthoHeight = 4;
  EXPECT_DOUBLE_EQ(o.pixelsPerUnit({Vec3(0, 0, -100), 0}), 844 / 4.0);
}

TEST(View, OnlySpheresWhollyBeyondOnePlaneAreOutside) {
  const View v = phone();
  const double ty = std::tan(std::numbers::pi / 6), tx = ty * 390 / 844;
  EXPECT_FALSE(v.outside({Vec3(0, 0, 0), 0.1}));
  EXPECT_TRUE(v.outside({Vec3(0, 0, 11), 0.5})) << "behind the eye";
  EXPECT_FALSE(v.outside({Vec3(0, 0, 11), 2})) << "around the eye";
  // At depth 10 the frame's half width is 10 tx, its half height 10 ty.
  const double edgeX = 10 * tx, edgeY = 10 * ty;
  const double nx = 1 / std::sqrt(1 + tx * tx), ny = 1 / std::sqrt(1 + ty * ty);
  EXPECT_FALSE(v.outside({Vec3(edgeX + 0.5, 0, 0), 0.51 * nx})) << "straddles the right plane";
  EXPECT_TRUE(v.outside({Vec3(edgeX + 0.5, 0, 0), 0.49 * nx})) << "beyond it";
  EXPECT_TRUE(v.outside({Vec3(0, -(edgeY + 1), 0), 0.99 * ny}));
  EXPECT_FALSE(v.outside({Vec3(0, -(edgeY + 1), 0), 1.01 * ny}));
  View o = v;
  o.projection = Projection::kOrthographic;
  o.orthoHeight = 4;
  EXPECT_TRUE(o.outside({Vec3(0, 2.6, -50), 0.5}));
  EXPECT_FALSE(o.outside({Vec3(0, 2.4, -50), 0.5}));
}

}  // namespace
}  // namespace tessera

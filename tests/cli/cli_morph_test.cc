// `tessera morph` (docs/INTERPOLATION.md) on the procedural sample (support/morph_sample.h):
// the real binary writes the frames; the tests read the PNGs back and check
// them against what the frames must show.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cli/cli_run.h"
#include "core/io/png_image.h"
#include "support/morph_sample.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

double psnr(const Image& x, const Image& y) {
  double sum = 0;
  size_t n = 0;
  for (int j = 0; j < x.height; ++j) {
    for (int i = 0; i < x.width; ++i) {
      for (int c = 0; c < 3; ++c) {
        const double d = double(x.at(i, j)[c]) - double(y.at(i, j)[c]);
        sum += d * d, ++n;
      }
    }
  }
  const double mse = sum / static_cast<double>(n);
  return mse == 0 ? INFINITY : 10 * std::log10(255.0 * 255.0 / mse);
}

// The centroid of green-dot pixels (green well above red and blue) within
// `radius` pixels of `near`; nullopt if there are none.
std::optional<Vec3> dotCentroid(const Image& image, const Vec3& near, int radius) {
  double wx = 0, wy = 0, w = 0;
  for (int j = std::max(0, int(near[1]) - radius); j <= std::min(image.height - 1, int(near[1]) + radius);
       ++j) {
    for (int i = std::max(0, int(near[0]) - radius); i <= std::min(image.width - 1, int(near[0]) + radius);
         ++i) {
      const uint8_t* p = image.at(i, j);
      const double g = double(p[1]) - std::max(p[0], p[2]);
      if (g < 100) continue;
      wx += g * (i + 0.5), wy += g * (j + 0.5), w += g;
    }
  }
  if (w == 0) return std::nullopt;
  return Vec3(wx / w, wy / w, 0);
}

std::string frame(const std::string& dir, int k) {
  char name[32];
  std::snprintf(name, sizeof name, "/frame_%04d.png", k);
  return dir + name;
}

struct MorphRun {
  std::string dir;
  testing::MorphSample sample;
  CliRun cli;
};

MorphRun morph(const std::string& name, bool mirrored, bool tags, int frames) {
  MorphRun r{testing::makeTempDir(name), testing::makeMorphSample(mirrored), {}};
  EXPECT_TRUE(testing::writeMorphSample(r.sample, r.dir).isOk());
  r.cli = runCli("morph --from " + r.dir + "/a.png --to " + r.dir + "/b.png --mesh-from " + r.dir +
                 "/mesh_a.obj --mesh-to " + r.dir + "/mesh_b.obj" +
                 (tags ? " --tags " + r.dir + "/morph.tags" : "") + " --level 3 --frames " +
                 std::to_string(frames) + " -o " + r.dir + "/out --strip " + r.dir + "/strip.png");
  return r;
}

TEST(CliMorph, TheEndFramesAreTheImagesAndTheDotFollowsItsInterpolatingVertex) {
  constexpr int kFrames = 9;
  MorphRun r = morph("tessera-morph", false, true, kFrames);
  ASSERT_EQ(r.cli.exitCode, 0) << r.cli.err;
  EXPECT_NE(r.cli.out.find("wrote 9 frames"), std::string::npos) << r.cli.out;
  EXPECT_NE(r.cli.out.find("3 interpolating vertices"), std::string::npos) << r.cli.out;
  auto first = readPng(frame(r.dir + "/out", 0)), last = readPng(frame(r.dir + "/out", kFrames - 1));
  ASSERT_TRUE(first.isOk() && last.isOk());
  const double p0 = psnr(*first, r.sample.a), p1 = psnr(*last, r.sample.b);
  EXPECT_GE(p0, 40.0);
  EXPECT_GE(p1, 40.0);
  const auto& s = r.sample;
  double worstDot = 0;
  for (int k = 0; k < kFrames; ++k) {
    const double t = k / double(kFrames - 1);
    auto image = readPng(frame(r.dir + "/out", k));
    ASSERT_TRUE(image.isOk()) << image.status().message();
    // The dot: both images' dots land where the interpolating vertex is at t.
    const Vec3 expected = (1 - t) * s.meshA[s.dotVertex] + t * s.meshB[s.dotVertex];
    auto found = dotCentroid(*image, expected, 8);
    ASSERT_TRUE(found.has_value()) << "frame " << k << ": no dot near the vertex";
    const double off = (*found - expected).norm();
    worstDot = std::max(worstDot, off);
    EXPECT_LE(off, 1.0) << "frame " << k;
    // The hole stays a hole: no warped ring covers its centre, which shows
    // what the two images hold at that pixel, dissolved (the documented
    // background rule), not the ring carried there.
    const Vec3 hole = (1 - t) * s.holeA + t * s.holeB;
    const int hx = int(hole[0]), hy = int(hole[1]);
    const uint8_t* px = image->at(hx, hy);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(px[c], (1 - t) * s.a.at(hx, hy)[c] + t * s.b.at(hx, hy)[c], 1.0)
          << "frame " << k << " channel " << c;
    }
  }
  std::printf("PSNR frame 0 vs A %.1f dB, last vs B %.1f dB; the dot at most %.2f px from its vertex\n", p0,
              p1, worstDot);
  auto strip = readPng(r.dir + "/strip.png");
  ASSERT_TRUE(strip.isOk());
  EXPECT_EQ(strip->width, kFrames * s.a.width);
}

// Without the tags the surface does not pass through the marked vertex, and
// the dot is not carried to its interpolated position as exactly.
TEST(CliMorph, WithoutInterpolationTheDotDrifts) {
  MorphRun r = morph("tessera-morph-plain", false, false, 3);
  ASSERT_EQ(r.cli.exitCode, 0) << r.cli.err;
  auto middle = readPng(frame(r.dir + "/out", 1));
  ASSERT_TRUE(middle.isOk());
  const auto& s = r.sample;
  const Vec3 expected = 0.5 * (s.meshA[s.dotVertex] + s.meshB[s.dotVertex]);
  auto found = dotCentroid(*middle, expected, 12);
  ASSERT_TRUE(found.has_value());
  std::printf("without interpolation the dot is %.2f px from its vertex at t = 0.5\n",
              (*found - expected).norm());
  EXPECT_GT((*found - expected).norm(), 1.0);
}

TEST(CliMorph, FoldsAndMismatchedMeshesAreReportedNotDrawn) {
  MorphRun r = morph("tessera-morph-fold", true, true, 5);
  EXPECT_EQ(r.cli.exitCode, 1);
  EXPECT_NE(r.cli.err.find("triangles of the level-3 surface fold over"), std::string::npos) << r.cli.err;
  EXPECT_NE(r.cli.err.find("the meshes do not give a valid warp"), std::string::npos) << r.cli.err;
  // Another connectivity: the message names the first differing triangle.
  std::ifstream in(r.dir + "/mesh_a.obj");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t f = text.find("\nf ");
  std::string line = text.substr(f + 1, text.find('\n', f + 1) - f - 1);
  int a, b, c;
  ASSERT_EQ(std::sscanf(line.c_str(), "f %d %d %d", &a, &b, &c), 3);
  text.replace(f + 1, line.size(),
               "f " + std::to_string(b) + " " + std::to_string(c) + " " + std::to_string(a));
  std::ofstream(r.dir + "/rotated.obj") << text;
  CliRun other = runCli("morph --from " + r.dir + "/a.png --to " + r.dir + "/b.png --mesh-from " + r.dir +
                        "/mesh_a.obj --mesh-to " + r.dir + "/rotated.obj --frames 2 -o " + r.dir + "/x");
  EXPECT_EQ(other.exitCode, 1);
  EXPECT_NE(other.err.find("triangle 0 is ("), std::string::npos) << other.err;
  EXPECT_NE(other.err.find("rotated.obj"), std::string::npos) << other.err;
  CliRun missing =
      runCli("morph --from " + r.dir + "/nope.png --to " + r.dir + "/b.png --mesh-from " + r.dir +
             "/mesh_a.obj --mesh-to " + r.dir + "/mesh_b.obj --frames 2 -o " + r.dir + "/x");
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_NE(missing.err.find("nope.png: no such file"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace tessera

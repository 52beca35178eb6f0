// A 2D morph document in the real tessera-view (docs/VIEWER.md "Morph documents"), rendered with
// no display from the real server: the sample's annulus (deploy/samples/
// morph) with key 1 and the two images added over the protocol. At t = 0
// the surface shows the first image's colours, at t = 1 the second's, and
// halfway a cross-dissolve between them; the green dot painted in both
// images at the same mesh vertex (make_morph_sample.sh) stays one dot. Expectations come
// from the PNGs themselves, not from earlier screenshots.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "client/lib/session.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"
#include "view/png_image.h"
#include "view/x_display.h"

namespace tessera {
namespace {

using testing::Image;
using testing::Rgb;

constexpr Rgb kBackground = {41, 46, 56};

std::string samplePath(const std::string& name) {
  return testing::sourceTestDataPath("../../deploy/samples/morph/" + name);
}

bool isGreenDot(Rgb c) {
  return c[1] > 170 && c[0] < 110 && c[2] < 110;
}

// The mean colour of an image's pixels that are neither near-white (the
// sample's background) nor the green dot: the colours a shape shows.
std::array<double, 3> meanShapeColour(const Image& image, Rgb exclude, bool excludeLight) {
  std::array<double, 3> sum{};
  double n = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const Rgb c = image.at(x, y);
      if (testing::distance(c, exclude) < 40 || isGreenDot(c)) continue;
      if (excludeLight && c[0] + c[1] + c[2] > 3 * 200) continue;
      for (int k = 0; k < 3; ++k) sum[k] += c[k];
      ++n;
    }
  }
  for (double& v : sum) v /= std::max(n, 1.0);
  return sum;
}

double gap(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
}

// The sample's morph (make_morph_sample.sh) as a server document: key 0
// created, key 1 added over the protocol, with the two images for a 2D
// morph. Fails the test and returns 0 if the server refuses.
uint64_t createMorphDocument(client::Session& admin, bool withImages) {
  auto created =
      admin.call(testing::createDocument("annulus", testing::fileBytes(samplePath("mesh_a.obj")), "", 4), 30);
  EXPECT_TRUE(created.isOk() && created->has_ack()) << (created.isOk() ? created->DebugString() : "");
  if (!created.isOk() || !created->has_ack()) return 0;
  const uint64_t doc = created->ack().document_id();
  EXPECT_TRUE(admin.call(testing::openDocument(doc), 10).isOk());
  wire::ClientMessage add;
  add.mutable_add_morph_key()->set_document_id(doc);
  add.mutable_add_morph_key()->set_mesh(testing::fileBytes(samplePath("mesh_b.obj")));
  add.mutable_add_morph_key()->set_mesh_format(wire::MESH_FORMAT_OBJ);
  if (withImages) {
    add.mutable_add_morph_key()->set_image_from(testing::fileBytes(samplePath("a.png")));
    add.mutable_add_morph_key()->set_image_to(testing::fileBytes(samplePath("b.png")));
  }
  auto added = admin.call(add, 30);
  EXPECT_TRUE(added.isOk() && added->has_ack()) << (added.isOk() ? added->DebugString() : "");
  return added.isOk() && added->has_ack() ? doc : 0;
}

TEST(ViewMorph, TheImagesOfA2DMorphFollowTheTimeShown) {
  const std::string dir = testing::makeTempDir("tessera-view-morph");
  auto server = testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = client::Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  const uint64_t doc = createMorphDocument(**admin, /*withImages=*/true);
  ASSERT_NE(doc, 0u);

  auto render = [&](const std::string& t, std::vector<std::string> extra = {}) -> Image {
    const std::string png = dir + "/t" + t + (extra.empty() ? "" : "-coarse") + ".png";
    std::vector<std::string> args = {TESSERA_VIEW_PATH,
                                     "--connect",
                                     "127.0.0.1:" + std::to_string(server->port()),
                                     "--token",
                                     server->adminToken(),
                                     "--document",
                                     std::to_string(doc),
                                     "--morph-t",
                                     t,
                                     "--max-level",
                                     "3",
                                     "--no-hud",
                                     "--no-gizmo",
                                     "--screenshot",
                                     png,
                                     "--frames",
                                     "10",
                                     "--timeout",
                                     "60"};
    args.insert(args.end(), extra.begin(), extra.end());
    const int rc = testing::runBounded(args, testing::headlessEnvironment(), dir + "/view.log", 120);
    EXPECT_EQ(rc, 0) << testing::fileBytes(dir + "/view.log");
    auto image = testing::readPng(png);
    EXPECT_TRUE(image.has_value()) << png;
    return image.value_or(Image{});
  };
  const Image at0 = render("0"), half = render("0.5"), at1 = render("1");
  const Image coarseHalf = render("0.5", {"--morph-coarse"});
  ASSERT_GT(at0.width, 0);
  ASSERT_GT(at1.width, 0);
  ASSERT_GT(half.width, 0);

  auto a = testing::readPng(samplePath("a.png"));
  auto b = testing::readPng(samplePath("b.png"));
  ASSERT_TRUE(a && b);
  const auto colourA = meanShapeColour(*a, Rgb{255, 255, 255}, true);
  const auto colourB = meanShapeColour(*b, Rgb{255, 255, 255}, true);
  ASSERT_GT(gap(colourA, colourB), 60) << "the sample's two images look alike";

  const auto shown0 = meanShapeColour(at0, kBackground, true);
  const auto shown1 = meanShapeColour(at1, kBackground, true);
  const auto shownHalf = meanShapeColour(half, kBackground, true);
  std::printf(
      "mean colours: a.png %.0f %.0f %.0f, b.png %.0f %.0f %.0f; shown at 0: %.0f %.0f %.0f, "
      "0.5: %.0f %.0f %.0f, 1: %.0f %.0f %.0f\n",
      colourA[0], colourA[1], colourA[2], colourB[0], colourB[1], colourB[2], shown0[0], shown0[1], shown0[2],
      shownHalf[0], shownHalf[1], shownHalf[2], shown1[0], shown1[1], shown1[2]);
  // Each key's picture shows its own image, not the other one.
  EXPECT_LT(gap(shown0, colourA), gap(shown0, colourB) / 3);
  EXPECT_LT(gap(shown1, colourB), gap(shown1, colourA) / 3);
  // Halfway, a cross-dissolve: every channel between the two pictures'
  // (with a margin for edges and filtering), far from both.
  for (int k = 0; k < 3; ++k) {
    EXPECT_GE(shownHalf[k], std::min(shown0[k], shown1[k]) - 12) << k;
    EXPECT_LE(shownHalf[k], std::max(shown0[k], shown1[k]) + 12) << k;
  }
  EXPECT_GT(gap(shownHalf, shown0), gap(shown0, shown1) / 4);
  EXPECT_GT(gap(shownHalf, shown1), gap(shown0, shown1) / 4);
  // The coarse stream (control points refined in the viewer) shows the
  // same picture here: the sample's keys have no finer edits to leave out.
  const auto shownCoarse = meanShapeColour(coarseHalf, kBackground, true);
  EXPECT_LT(gap(shownCoarse, shownHalf), 6)
      << shownCoarse[0] << " " << shownCoarse[1] << " " << shownCoarse[2];
  EXPECT_LT(testing::difference(coarseHalf, half, 24).pixels,
            static_cast<size_t>(half.width) * half.height / 50);
  // The dot is on the surface at every time.
  for (const Image* image : {&at0, &half, &at1, &coarseHalf}) {
    int green = 0;
    for (int y = 0; y < image->height; ++y)
      for (int x = 0; x < image->width; ++x) green += isGreenDot(image->at(x, y)) ? 1 : 0;
    EXPECT_GT(green, 20);
  }
  EXPECT_EQ(server->stop(), 0);
}

// Views are the viewer's default, but a morph's time is a profile field
// (docs/VIEWER.md "Views"): a 3D morph opened with no profile option is
// shown with the profile, the same picture as with --profile.
TEST(ViewMorph, AMorphDocumentOpenedWithTheDefaultsIsShownWithTheProfile) {
  const std::string dir = testing::makeTempDir("tessera-view-morph-default");
  auto server = testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = client::Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  const uint64_t doc = createMorphDocument(**admin, /*withImages=*/false);
  ASSERT_NE(doc, 0u);

  auto render = [&](const std::string& name, std::vector<std::string> extra) {
    const std::string png = dir + "/" + name + ".png";
    std::vector<std::string> args = {TESSERA_VIEW_PATH,
                                     "--connect",
                                     "127.0.0.1:" + std::to_string(server->port()),
                                     "--token",
                                     server->adminToken(),
                                     "--document",
                                     std::to_string(doc),
                                     "--no-hud",
                                     "--screenshot",
                                     png,
                                     "--frames",
                                     "3",
                                     "--timeout",
                                     "60"};
    args.insert(args.end(), extra.begin(), extra.end());
    const int rc = testing::runBounded(args, testing::headlessEnvironment(), dir + "/" + name + ".log", 120);
    EXPECT_EQ(rc, 0) << testing::fileBytes(dir + "/" + name + ".log");
    return testing::fileBytes(dir + "/" + name + ".log");
  };
  const std::string byDefault = render("default", {}), profile = render("profile", {"--profile"});
  // "wrote X.png (800x600, 4 samples per pixel, document version V, N triangles)"
  auto triangles = [](const std::string& log) {
    const size_t at = log.rfind(" triangles)");
    return at == std::string::npos ? std::string()
                                   : log.substr(log.rfind(", ", at) + 2, at - log.rfind(", ", at) - 2);
  };
  ASSERT_FALSE(triangles(profile).empty()) << profile;
  EXPECT_EQ(triangles(byDefault), triangles(profile)) << byDefault;
  EXPECT_EQ(byDefault.find("tiles were not complete"), std::string::npos) << byDefault;
  const auto a = testing::readPng(dir + "/default.png"), b = testing::readPng(dir + "/profile.png");
  ASSERT_TRUE(a && b);
  EXPECT_EQ(testing::difference(*a, *b, 8).pixels, 0u);
  EXPECT_EQ(server->stop(), 0);
}

}  // namespace
}  // namespace tessera

// What a user of a professional 3D viewer expects to see (docs/VIEWER.md "Look"),
// checked on pictures the real tessera-view renders with no display at all
// (DISPLAY unset: EGL on Mesa's surfaceless platform) from the real server:
// anti-aliased silhouettes, a lit top face, control points only when asked
// for, a HUD that keeps out of the frame's middle, the axes gizmo in its
// corner, and a real CGAL mesh (fandisk, sharp edges tagged as creases)
// fitted to the view.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "client/lib/session.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"
#include "view/cube_document.h"
#include "view/feature_tags.h"
#include "view/png_image.h"
#include "view/x_display.h"

namespace tessera {
namespace {

using testing::Image;
using testing::Rgb;

// The viewer's clear colour, glClearColor(0.16, 0.18, 0.22) in 8 bits.
constexpr Rgb kBackground = {41, 46, 56};

class ViewScreenshot : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::makeTempDir("tessera-view-shots");
    auto server = testing::ServerProcess::start(dir_ + "/data");
    ASSERT_TRUE(server.isOk()) << server.status().message();
    server_.emplace(std::move(*server));
  }
  void TearDown() override {
    if (server_) {
      EXPECT_EQ(server_->stop(), 0);
    }
  }

  // Renders `document` with no display; the picture, or a failure.
  Image render(uint64_t document, const std::string& name, std::vector<std::string> extra,
               std::vector<std::string> profile = {"--base-level", "2", "--max-level", "3"}) {
    const std::string png = dir_ + "/" + name + ".png";
    std::vector<std::string> args = {TESSERA_VIEW_PATH,
                                     "--connect",
                                     "127.0.0.1:" + std::to_string(server_->port()),
                                     "--token",
                                     server_->adminToken(),
                                     "--document",
                                     std::to_string(document),
                                     "--screenshot",
                                     png,
                                     "--frames",
                                     "3",
                                     "--timeout",
                                     "60"};
    args.insert(args.end(), profile.begin(), profile.end());
    args.insert(args.end(), extra.begin(), extra.end());
    const int rc = testing::runBounded(args, testing::headlessEnvironment(), dir_ + "/view.log", 120);
    EXPECT_EQ(rc, 0) << name << ": tessera-view failed; see " << dir_ << "/view.log:\n"
                     << testing::fileBytes(dir_ + "/view.log");
    auto image = testing::readPng(png);
    EXPECT_TRUE(image.has_value()) << png << " is not a readable PNG";
    return image.value_or(Image{});
  }

  std::string dir_;
  std::optional<testing::ServerProcess> server_;
};

// Yellow control-vertex dots: the surface is grey-blue, the background dark.
size_t yellowPixels(const Image& a) {
  size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const Rgb c = a.at(x, y);
      n += c[0] > 200 && c[1] > 160 && c[2] < 90;
    }
  return n;
}

TEST_F(ViewScreenshot, TheCubeIsAntiAliasedLitAndShowsItsControlPointsOnlyWhenAsked) {
  auto cube = testing::createCube(*server_, true, 5);
  ASSERT_TRUE(cube.isOk()) << cube.status().message();
  const Image aliased = render(*cube, "aliased", {"--no-hud", "--no-gizmo", "--msaa", "0"});
  const Image smooth = render(*cube, "smooth", {"--no-hud", "--no-gizmo"});
  ASSERT_EQ(smooth.width, 800);
  ASSERT_EQ(smooth.height, 600);
  ASSERT_EQ(aliased.width, 800);
  EXPECT_EQ(smooth.at(0, 0), kBackground);

  // Anti-aliasing: along the silhouette, pixels partly covered by the cube
  // blend into the background. Without multisampling a pixel is the cube's
  // or the background's.
  const auto a = testing::silhouette(aliased, kBackground), s = testing::silhouette(smooth, kBackground);
  std::printf("silhouette pixels blended: %zu of %zu without MSAA, %zu of %zu with 4x MSAA\n", a.blended,
              a.pixels, s.blended, s.pixels);
  std::fflush(stdout);  // before the next fork copies the buffer
  ASSERT_GT(a.pixels, 200u);
  ASSERT_GT(s.pixels, 200u);
  EXPECT_LT(a.blended, a.pixels / 8) << "blended silhouette pixels without MSAA";
  EXPECT_GT(s.blended, s.pixels / 2) << "too few blended silhouette pixels with MSAA";
  EXPECT_GT(s.blended, 5 * a.blended);

  // The top face: the default camera looks down on the cube, so going down
  // the middle column the silhouette starts with the top face. Its middle
  // (12% of the way down the silhouette) must be well lit, not the nearly
  // black of a lone headlight.
  int top = -1, bottom = -1;
  for (int y = 0; y < smooth.height; ++y)
    if (testing::differ(smooth.at(400, y), kBackground)) {
      if (top < 0) top = y;
      bottom = y;
    }
  ASSERT_GE(top, 0) << "nothing in the middle column";
  const int faceY = top + (bottom - top) * 12 / 100;
  double lum = 0;
  for (int dy = -4; dy <= 4; ++dy)
    for (int dx = -4; dx <= 4; ++dx) lum += testing::luminance(smooth.at(400 + dx, faceY + dy));
  lum /= 81;
  std::printf("top face luminance %.0f of 255 at (400, %d)\n", lum, faceY);
  std::fflush(stdout);
  EXPECT_GT(lum, 150) << "the top face is dark";
  // And the shading still shows the form: the sides differ from the top.
  EXPECT_GT(std::abs(testing::luminance(smooth.at(400, top + (bottom - top) * 70 / 100)) - lum), 15);

  // Control points: none by default, dots sized to the model with the option.
  EXPECT_EQ(yellowPixels(smooth), 0u) << "control points drawn by default";
  const Image points = render(*cube, "points", {"--no-hud", "--no-gizmo", "--control-points"});
  const size_t yellow = yellowPixels(points);
  std::printf("control points: %zu yellow pixels\n", yellow);
  std::fflush(stdout);
  EXPECT_GT(yellow, 20u) << "no control points with --control-points";
  // The cube's eight level-0 vertices, some hidden: small dots, not balls.
  EXPECT_LT(yellow, 8u * 20 * 20) << "control points are too big";
}

// The cage's magenta, (1.0, 0.25, 0.82) in 8 bits: neither the surface's
// grey, the background's blue, the points' yellow nor a pick's red.
size_t magentaPixels(const Image& a) {
  size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const Rgb c = a.at(x, y);
      n += c[0] > 200 && c[1] < 130 && c[2] > 150;
    }
  return n;
}

// A Catmull-Clark document's control cage (--cage) is its polygons: the quad
// cube's six quads and twelve edges at level 0, its 24 quads and 48 edges at
// level 1 (triangles would be 12 and 18, or 48 and 72), the edges of the
// quads facing the camera drawn in the cage's colour only when asked for; a
// level the document lacks is refused by name.
TEST_F(ViewScreenshot, ACatmullClarkCageIsDrawnAsItsQuads) {
  auto cube = testing::createFromTestData(*server_, "good/cube_quads.obj", "", 3);
  ASSERT_TRUE(cube.isOk()) << cube.status().message();
  const std::vector<std::string> profile = {"--base-level", "1", "--max-level", "3"};
  const Image plain = render(*cube, "cage-none", {"--no-hud", "--no-gizmo", "--control-points"}, profile);
  EXPECT_EQ(magentaPixels(plain), 0u) << "a cage drawn without --cage";
  const Image base =
      render(*cube, "cage-0", {"--no-hud", "--no-gizmo", "--control-points", "--cage"}, profile);
  std::string log = testing::fileBytes(dir_ + "/view.log");
  EXPECT_NE(log.find("cage of level 0: 6 faces (6 of 4 corners), 12 edges"), std::string::npos) << log;
  const size_t baseMagenta = magentaPixels(base);
  const Image one = render(*cube, "cage-1", {"--no-hud", "--no-gizmo", "--cage", "--level", "1"}, profile);
  log = testing::fileBytes(dir_ + "/view.log");
  EXPECT_NE(log.find("cage of level 1: 24 faces (24 of 4 corners), 48 edges"), std::string::npos) << log;
  const size_t oneMagenta = magentaPixels(one);
  std::printf("cage pixels: %zu at level 0, %zu at level 1\n", baseMagenta, oneMagenta);
  std::fflush(stdout);
  EXPECT_GT(baseMagenta, 300u) << "the level-0 cage is not drawn";
  EXPECT_GT(oneMagenta, baseMagenta) << "level 1's cage has more edges in view";

  const int rc = testing::runBounded({TESSERA_VIEW_PATH,
                                      "--connect",
                                      "127.0.0.1:" + std::to_string(server_->port()),
                                      "--token",
                                      server_->adminToken(),
                                      "--document",
                                      std::to_string(*cube),
                                      "--screenshot",
                                      dir_ + "/cage-5.png",
                                      "--frames",
                                      "2",
                                      "--timeout",
                                      "5",
                                      "--cage",
                                      "--level",
                                      "5",
                                      "--base-level",
                                      "1",
                                      "--max-level",
                                      "3"},
                                     testing::headlessEnvironment(), dir_ + "/view.log", 60);
  EXPECT_NE(rc, 0) << "a cage of a level the document lacks was shown";
  log = testing::fileBytes(dir_ + "/view.log");
  EXPECT_NE(log.find("level 5 is outside 0..3"), std::string::npos) << log;
}

TEST_F(ViewScreenshot, TheHudKeepsOutOfTheMiddleAndTheGizmoSitsInItsCorner) {
  auto cube = testing::createCube(*server_, true, 5);
  ASSERT_TRUE(cube.isOk()) << cube.status().message();
  const Image bare = render(*cube, "bare", {"--no-hud", "--no-gizmo"});
  const Image hud = render(*cube, "hud", {"--no-gizmo"});
  const Image folded = render(*cube, "folded", {"--no-gizmo", "--hud-collapsed"});
  const Image gizmo = render(*cube, "gizmo", {"--no-hud"});
  const int w = bare.width, h = bare.height;
  ASSERT_EQ(w, 800);

  // The HUD: everything it changes lies in the top-left corner, away from
  // the middle of the frame where the model's centre is.
  const auto full = testing::difference(hud, bare), line = testing::difference(folded, bare);
  std::printf("HUD: %dx%d px at (%d, %d); collapsed: %dx%d px\n", full.box.width(), full.box.height(),
              full.box.x0, full.box.y0, line.box.width(), line.box.height());
  ASSERT_GT(full.pixels, 1000u) << "no HUD";
  EXPECT_FALSE(full.box.contains(w / 2, h / 2)) << "the HUD covers the frame's centre";
  EXPECT_LE(full.box.x1, w * 40 / 100);
  EXPECT_LE(full.box.y1, h * 45 / 100);
  EXPECT_LT(full.box.width() * full.box.height(), w * h / 6) << "the HUD is not compact";
  // Collapsed, it is its title line.
  ASSERT_GT(line.pixels, 100u) << "no collapsed HUD";
  EXPECT_LT(line.box.height(), 30);
  EXPECT_LT(line.box.height() * 3, full.box.height());

  // The gizmo: in the bottom-left corner only, with its red X, green Y and
  // blue Z.
  const auto axes = testing::difference(gizmo, bare);
  std::printf("gizmo: %dx%d px at (%d, %d)\n", axes.box.width(), axes.box.height(), axes.box.x0, axes.box.y0);
  ASSERT_GT(axes.pixels, 300u) << "no gizmo";
  EXPECT_LE(axes.box.x1, w / 5);
  EXPECT_GE(axes.box.y0, h * 3 / 4);
  int red = 0, green = 0, blue = 0;
  for (int y = axes.box.y0; y <= axes.box.y1; ++y)
    for (int x = axes.box.x0; x <= axes.box.x1; ++x) {
      const Rgb c = gizmo.at(x, y);
      red += c[0] > 180 && c[1] < 110 && c[2] < 110;
      green += c[1] > 160 && c[0] < 140 && c[2] < 120;
      blue += c[2] > 190 && c[0] < 120 && c[1] < 170;
    }
  EXPECT_GT(red, 20) << "no red X axis";
  EXPECT_GT(green, 20) << "no green Y axis";
  EXPECT_GT(blue, 20) << "no blue Z axis";
}

// Fandisk from Debian's libcgal-demo with its feature lines tagged as
// creases: the fit to view on load puts its whole projection inside the
// frame, filling most of it in the tighter dimension, in a landscape and a
// portrait frame; the matcap shades it too.
TEST_F(ViewScreenshot, FandiskWithItsCreasesIsFittedToTheView) {
  const std::string off = testing::cgalMeshPath("fandisk.off");
  int creases = 0;
  const std::string tags = testing::featureTags(off, 40, creases);
  ASSERT_GT(creases, 500) << "fandisk's feature lines were not found";
  auto admin = client::Session::connect(server_->session("admin", server_->adminToken()));
  ASSERT_TRUE(admin.isOk()) << admin.status().message();
  wire::ClientMessage create = testing::createDocument("fandisk", testing::fileBytes(off), tags, 4);
  create.mutable_create_document()->set_mesh_format(wire::MESH_FORMAT_OFF);
  auto created = (*admin)->call(create, 120);
  ASSERT_TRUE(created.isOk() && created->has_ack())
      << (created.isOk() ? created->DebugString() : created.status().message());
  const uint64_t doc = created->ack().document_id();
  const std::vector<std::string> profile = {"--base-level", "1", "--max-level", "2"};

  struct Frame {
    std::string name;
    std::vector<std::string> options;
  };
  for (const Frame& f :
       {Frame{"fandisk", {"--no-hud", "--no-gizmo"}},
        Frame{"fandisk-portrait", {"--no-hud", "--no-gizmo", "--size", "480x720", "--matcap"}}}) {
    const Image image = render(doc, f.name, f.options, profile);
    ASSERT_GT(image.width, 0);
    const auto model = testing::foreground(image, kBackground);
    const double across = static_cast<double>(model.box.width()) / image.width;
    const double down = static_cast<double>(model.box.height()) / image.height;
    std::printf("%s: the model spans %.0f%% of the width and %.0f%% of the height, covers %.0f%%\n",
                f.name.c_str(), 100 * across, 100 * down,
                100.0 * model.pixels / (image.width * image.height));
    EXPECT_GE(model.box.x0, 2) << f.name << ": cut at the left";
    EXPECT_GE(model.box.y0, 2) << f.name << ": cut at the top";
    EXPECT_LE(model.box.x1, image.width - 3) << f.name << ": cut at the right";
    EXPECT_LE(model.box.y1, image.height - 3) << f.name << ": cut at the bottom";
    EXPECT_GT(std::max(across, down), 0.75) << f.name << ": the model is small in the frame";
    EXPECT_GT(static_cast<double>(model.pixels) / (image.width * image.height), 0.15) << f.name;
    // Centred: the margins left and right (top and bottom) are alike.
    EXPECT_NEAR(model.box.x0, image.width - 1 - model.box.x1, image.width * 0.06) << f.name;
    EXPECT_NEAR(model.box.y0, image.height - 1 - model.box.y1, image.height * 0.06) << f.name;
  }
}

// The hue of a pixel, in degrees; -1 for a grey one.
int hueOf(const Rgb& c) {
  const int hi = std::max({c[0], c[1], c[2]}), lo = std::min({c[0], c[1], c[2]});
  if (hi - lo < 24) return -1;
  const double d = hi - lo;
  double h = hi == c[0]   ? std::fmod((c[1] - c[2]) / d, 6.0)
             : hi == c[1] ? (c[2] - c[0]) / d + 2
                          : (c[0] - c[1]) / d + 4;
  if (h < 0) h += 6;
  return static_cast<int>(60 * h);
}

// A view-dependent subscription (the default without profile options,
// docs/VIEWER.md "Views"): the viewer frames the coarsest tiles, sends its camera, and shows the tiles
// that camera needs, several levels at once (coloured by level with
// --level-colours), more triangles than the coarsest tiles had.
class ViewScreenshotOfViews : public ViewScreenshot {
 protected:
  // `file` from CGAL's data, as the server reads it (OFF, no scheme: its
  // faces choose); `coarsest`: the triangles of its level-0 tiles; `size`
  // fits the model's shape (a wide model on a wide page).
  void expectSeveralLevels(const std::string& file, const std::string& name, long long coarsest,
                           const std::string& size) {
    auto admin = client::Session::connect(server_->session("admin", server_->adminToken()));
    ASSERT_TRUE(admin.isOk());
    wire::ClientMessage create;
    auto* c = create.mutable_create_document();
    c->set_name(name);
    c->set_mesh(testing::fileBytes(testing::cgalMeshPath(file)));
    c->set_mesh_format(wire::MESH_FORMAT_OFF);
    c->set_max_level(4);
    auto created = (*admin)->call(create, 60);
    ASSERT_TRUE(created.isOk() && created->has_ack());
    const uint64_t doc = created->ack().document_id();
    const Image levels =
        render(doc, name + "-views", {"--no-hud", "--no-gizmo", "--level-colours", "--size", size}, {});
    const std::string log = testing::fileBytes(dir_ + "/view.log");
    ASSERT_GT(levels.width, 0);
    const auto model = testing::foreground(levels, kBackground);
    EXPECT_GT(static_cast<double>(model.pixels) / (levels.width * levels.height), 0.15)
        << name << ": the model is framed";
    // Pixels by hue, in 30-degree bins: the levels' colours.
    std::map<int, size_t> bins;
    size_t coloured = 0;
    for (int y = 0; y < levels.height; ++y)
      for (int x = 0; x < levels.width; ++x) {
        const int h = hueOf(levels.at(x, y));
        if (h >= 0 && testing::differ(levels.at(x, y), kBackground)) ++bins[h / 30], ++coloured;
      }
    int shown = 0;
    for (const auto& [bin, n] : bins) shown += n > coloured / 50 ? 1 : 0;
    std::printf("views of %s: %zu model pixels, %zu coloured, %d hues over 2%%\n", name.c_str(), model.pixels,
                coloured, shown);
    EXPECT_GE(shown, 2) << name << ": several levels at once";
    // The viewer reports the triangles drawn: more than the coarsest tiles'.
    const size_t at = log.rfind(" triangles)");
    ASSERT_NE(at, std::string::npos) << log;
    const size_t from = log.rfind(", ", at);
    const long long triangles = std::stoll(log.substr(from + 2, at - from - 2));
    EXPECT_GT(triangles, 4 * coarsest) << log;
  }
};

TEST_F(ViewScreenshotOfViews, ViewsShowTheTilesTheCameraNeedsAtSeveralLevels) {
  expectSeveralLevels("hand.off", "hand", 2390, "390x844");
}

// The same on a Catmull-Clark document: CGAL's double torus, 202 quads,
// 12 pentagons, 4 hexagons and 2 heptagons, whose level-0 tiles are 466
// triangles (docs/VIEWS.md "Catmull-Clark documents").
TEST_F(ViewScreenshotOfViews, ACatmullClarkDocumentShowsTheTilesOfItsQuadSplit) {
  expectSeveralLevels("double-torus-example.off", "double-torus", 466, "844x390");
}

}  // namespace
}  // namespace tessera

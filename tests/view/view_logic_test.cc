// tessera-view without a window: options, the orbit camera's pixel/world
// conversions, control vertices of a level, picking and dragging.
#include <gtest/gtest.h>

#include "client/view/camera.h"
#include "client/view/coarse_morph.h"
#include "client/view/control_points.h"
#include "client/view/gizmo.h"
#include "client/view/undo_history.h"
#include "client/view/view_options.h"
#include "core/hierarchy/ids.h"

namespace tessera::view {
namespace {

TEST(ViewOptions, ParsesTheConnectionProfileAndHeadlessMode) {
  auto o = parseViewOptions({"--connect",
                             "example.org:7000",
                             "--token",
                             "t",
                             "--document",
                             "3",
                             "--base-level",
                             "2",
                             "--max-level",
                             "4",
                             "--angle",
                             "7.5",
                             "--screenshot",
                             "a.png",
                             "--frames",
                             "5",
                             "--size",
                             "320x200",
                             "--no-hud",
                             "--level",
                             "1",
                             "--refine",
                             "2"});
  ASSERT_TRUE(o.isOk()) << o.status().message();
  EXPECT_EQ(o->host, "example.org");
  EXPECT_EQ(o->port, 7000);
  EXPECT_EQ(o->token, "t");
  EXPECT_EQ(o->document, 3u);
  EXPECT_EQ(o->baseLevel, 2u);
  EXPECT_EQ(o->maxLevel, 4u);
  EXPECT_DOUBLE_EQ(o->angle, 7.5);
  EXPECT_EQ(o->screenshot, "a.png");
  EXPECT_EQ(o->frames, 5);
  EXPECT_EQ(o->width, 320);
  EXPECT_EQ(o->height, 200);
  EXPECT_FALSE(o->hud);
  EXPECT_EQ(o->controlLevel, 1);
  EXPECT_EQ(o->refine, 2);
  EXPECT_EQ(parseViewOptions({"--connect", "h:1", "--document", "1"})->refine, 0);
}

TEST(ViewOptions, AViewIsTheDefaultAndTheProfileIsAskedForByNamingIt) {
  const std::vector<std::string> base = {"--connect", "h:1", "--document", "1"};
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.begin(), base.begin(), base.end());
    return parseViewOptions(extra);
  };
  EXPECT_TRUE(with({})->views);
  EXPECT_TRUE(with({"--views", "--tolerance", "4"})->views);
  EXPECT_DOUBLE_EQ(with({"--tolerance", "4"})->tolerancePixels, 4);
  EXPECT_FALSE(with({"--profile"})->views);
  for (const char* option : {"--base-level", "--max-level", "--angle", "--morph-t"})
    EXPECT_FALSE(with({option, "1"})->views) << option;
  EXPECT_FALSE(with({"--morph-coarse"})->views);
  // Asking for both is an error that names them.
  auto both = with({"--views", "--max-level", "2"});
  ASSERT_FALSE(both.isOk());
  EXPECT_NE(both.status().message().find("--views"), std::string::npos) << both.status().message();
  EXPECT_FALSE(with({"--views", "--profile"}).isOk());
  EXPECT_FALSE(with({"--profile", "--tolerance", "2"}).isOk());
}

TEST(ViewOptions, RejectsMissingAndMalformedValuesNamingTheOption) {
  EXPECT_FALSE(parseViewOptions({"--document", "1"}).isOk());   // no --connect
  EXPECT_FALSE(parseViewOptions({"--connect", "h:1"}).isOk());  // no --document
  auto port = parseViewOptions({"--connect", "h:99999", "--document", "1"});
  ASSERT_FALSE(port.isOk());
  EXPECT_NE(port.status().message().find("--connect"), std::string::npos);
  auto levels =
      parseViewOptions({"--connect", "h:1", "--document", "1", "--base-level", "4", "--max-level", "2"});
  EXPECT_FALSE(levels.isOk());
  auto frames = parseViewOptions({"--connect", "h:1", "--document", "1", "--frames", "x"});
  ASSERT_FALSE(frames.isOk());
  EXPECT_NE(frames.status().message().find("--frames"), std::string::npos);
  EXPECT_FALSE(parseViewOptions({"--connect", "h:1", "--document", "1", "--bogus", "1"}).isOk());
  auto refine = parseViewOptions({"--connect", "h:1", "--document", "1", "--refine", "3"});
  ASSERT_FALSE(refine.isOk());  // at most 2 splits per edge (docs/VIEWER.md "Client-side refinement")
  EXPECT_NE(refine.status().message().find("--refine"), std::string::npos);
  EXPECT_TRUE(parseViewOptions({"--help"})->help);
  auto keys =
      parseViewOptions({"--connect", "h:1", "--document", "1", "--edit-keys", "--screenshot", "k.png"});
  ASSERT_TRUE(keys.isOk()) << keys.status().message();
  EXPECT_TRUE(keys->editKeys && keys->hashSurfaces);
  EXPECT_FALSE(parseViewOptions({"--connect", "h:1", "--document", "1", "--edit-keys"}).isOk());
}

// CLI11's --opt=value, --version, the display options (docs/VIEWER.md "Usage").
TEST(ViewOptions, TakesOptEqualsValueVersionAndTheDisplayOptions) {
  auto o = parseViewOptions({"--connect=h:9", "--document=4", "--msaa=0", "--matcap", "--hud-collapsed",
                             "--control-points", "--no-gizmo", "--size=320x200", "--region-colors"});
  ASSERT_TRUE(o.isOk()) << o.status().message();
  EXPECT_EQ(o->port, 9);
  EXPECT_EQ(o->document, 4u);
  EXPECT_EQ(o->msaa, 0);
  EXPECT_TRUE(o->matcap && o->hudCollapsed && o->controlPoints && o->regionColours && o->hud);
  EXPECT_FALSE(o->gizmo);
  EXPECT_EQ(o->width, 320);
  // Defaults: 4x MSAA, the lights, the HUD open, the gizmo, no control points.
  auto d = parseViewOptions({"--connect", "h:1", "--document", "1"});
  ASSERT_TRUE(d.isOk());
  EXPECT_EQ(d->msaa, 4);
  EXPECT_TRUE(!d->matcap && !d->hudCollapsed && !d->controlPoints && d->gizmo && d->hud);
  // The self-tests pick control vertices, so they show them.
  auto drag =
      parseViewOptions({"--connect", "h:1", "--document", "1", "--screenshot", "a.png", "--drag=-80,80"});
  ASSERT_TRUE(drag.isOk()) << drag.status().message();
  EXPECT_EQ(drag->dragX, -80);
  EXPECT_TRUE(drag->controlPoints);
  auto version = parseViewOptions({"--version"});
  ASSERT_TRUE(version.isOk());
  EXPECT_TRUE(version->version);
  EXPECT_NE(viewHelp().find("--control-points"), std::string::npos);
  auto msaa = parseViewOptions({"--connect", "h:1", "--document", "1", "--msaa", "32"});
  ASSERT_FALSE(msaa.isOk());
  EXPECT_NE(msaa.status().message().find("--msaa"), std::string::npos) << msaa.status().message();
  auto size = parseViewOptions({"--connect", "h:1", "--document", "1", "--size", "big"});
  ASSERT_FALSE(size.isOk());
  EXPECT_NE(size.status().message().find("--size"), std::string::npos);
  auto file = parseViewOptions({"--connect", "h:1", "--document", "1", "--token-file", "/nonexistent/t"});
  ASSERT_FALSE(file.isOk());
  EXPECT_NE(file.status().message().find("--token-file"), std::string::npos);
}

// Fit to view: every point of the model projects inside the frame, the
// projection is centred and fills `fill` of the tighter dimension, for
// wide and tall frames and from any direction.
TEST(ViewCamera, FitToViewPutsEveryPointInsideTheFrameAndFillsIt) {
  // A long thin L: its bounding box is much larger than its projection.
  std::vector<V3> model;
  for (int i = 0; i <= 40; ++i) model.push_back({static_cast<float>(i) * 0.25f, 0, 0});
  for (int i = 0; i <= 10; ++i) model.push_back({0, static_cast<float>(i) * 0.2f, 3});
  for (auto [width, height] : {std::pair{800, 600}, std::pair{480, 720}}) {
    for (float turn : {0.0f, 150.0f, -300.0f}) {
      OrbitCamera camera;
      camera.orbit(turn, turn / 5);
      const float aspect = static_cast<float>(width) / static_cast<float>(height);
      camera.fit(model, aspect, 0.86f);
      float x0 = 1e9f, x1 = -1e9f, y0 = 1e9f, y1 = -1e9f;
      for (const V3& p : model) {
        auto s = camera.project(p, width, height);
        ASSERT_TRUE(s.has_value());
        x0 = std::min(x0, (*s)[0]), x1 = std::max(x1, (*s)[0]);
        y0 = std::min(y0, (*s)[1]), y1 = std::max(y1, (*s)[1]);
      }
      EXPECT_GE(x0, 0);
      EXPECT_GE(y0, 0);
      EXPECT_LE(x1, width);
      EXPECT_LE(y1, height);
      const float fill =
          std::max((x1 - x0) / static_cast<float>(width), (y1 - y0) / static_cast<float>(height));
      EXPECT_GT(fill, 0.80f) << width << "x" << height << " turn " << turn;
      EXPECT_LE(fill, 0.87f);
      // Centred up to perspective.
      EXPECT_NEAR((x0 + x1) / 2, width / 2.0f, width * 0.06f);
      EXPECT_NEAR((y0 + y1) / 2, height / 2.0f, height * 0.06f);
    }
  }
}

TEST(ViewGizmo, AxesPointWhereTheCameraSeesThemAndTheNearestIsDrawnLast) {
  // Looking down -Z from +Z: X to the right, Y up (screen y down), Z at the viewer.
  const Mat4 front = lookAt({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  const auto axes = gizmoAxes(front);
  EXPECT_EQ(axes[2].axis, 2);  // Z, towards the viewer, last
  for (const GizmoAxis& a : axes) {
    if (a.axis == 0) {
      EXPECT_NEAR(a.dx, 1, 1e-5f);
      EXPECT_NEAR(a.dy, 0, 1e-5f);
    }
    if (a.axis == 1) {
      EXPECT_NEAR(a.dx, 0, 1e-5f);
      EXPECT_NEAR(a.dy, -1, 1e-5f);
    }
    if (a.axis == 2) EXPECT_NEAR(a.depth, 1, 1e-5f);
  }
  // From the right (+X), X points at the viewer and Z to the left.
  const auto side = gizmoAxes(lookAt({5, 0, 0}, {0, 0, 0}, {0, 1, 0}));
  EXPECT_EQ(side[2].axis, 0);
  for (const GizmoAxis& a : side)
    if (a.axis == 2) EXPECT_NEAR(a.dx, -1, 1e-5f);
  // Its place: the bottom-left corner.
  const GizmoPlacement at = gizmoPlacement(800, 600);
  EXPECT_LT(at.cx + at.radius, 800 / 5.0f);
  EXPECT_GT(at.cy - at.radius, 600 * 0.75f);
}

TEST(ViewControlPoints, DotsAreSizedToTheModelAndTheirNumber) {
  const float cube = controlPointDiameter({0, 0, 0}, {2, 2, 2}, 8);
  EXPECT_FLOAT_EQ(controlPointDiameter({0, 0, 0}, {20, 20, 20}, 8), 10 * cube);  // scales with the model
  EXPECT_LE(cube, 0.015f * std::sqrt(12.0f) + 1e-6f);                            // never balls
  const float cow = controlPointDiameter({0, 0, 0}, {2, 2, 2}, 2904);
  EXPECT_LT(cow, cube);  // more points, smaller dots
  EXPECT_NEAR(cow, std::sqrt(12.0f) / std::sqrt(2904.0f) / 3, 1e-6f);
  EXPECT_GE(controlPointDiameter({0, 0, 0}, {2, 2, 2}, 100000000), 0.0015f * std::sqrt(12.0f) - 1e-6f);
}

TEST(ViewCamera, ProjectingAPointOnAPixelsRayLandsOnThatPixel) {
  OrbitCamera camera;
  camera.frame({0, 0, 0}, {1, 1, 1});
  camera.orbit(40, -25);
  for (auto [px, py] : {std::pair{400.0f, 300.0f}, std::pair{10.0f, 590.0f}, std::pair{700.0f, 120.0f}}) {
    const Ray ray = camera.rayThrough(px, py, 800, 600);
    auto s = camera.project(ray.origin + ray.direction * camera.distance(), 800, 600);
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR((*s)[0], px, 0.05f);
    EXPECT_NEAR((*s)[1], py, 0.05f);
  }
  // The target is in the middle of the frame.
  auto centre = camera.project(camera.target(), 800, 600);
  ASSERT_TRUE(centre.has_value());
  EXPECT_NEAR((*centre)[0], 400, 0.05f);
  EXPECT_NEAR((*centre)[1], 300, 0.05f);
}

// Two regions sharing a border vertex; vertices born at levels 0, 1 and 2.
RegionMap twoRegions() {
  auto a = std::make_shared<RegionMesh>();
  a->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  a->normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  a->vertexIds = {VertexId(0, 0).packed(), VertexId(1, 8).packed(), VertexId(2, 30).packed()};
  a->triangles = {{0, 1, 2}};
  auto b = std::make_shared<RegionMesh>();
  b->positions = {{1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  b->normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, -1}};
  b->vertexIds = {VertexId(1, 8).packed(), VertexId(0, 3).packed(), VertexId(1, 12).packed()};
  b->triangles = {{0, 1, 2}};
  return {{1, a}, {2, b}};
}

TEST(ViewControlPoints, ALevelShowsVerticesBornAtOrAboveItOnceRenamedToIt) {
  const RegionMap regions = twoRegions();
  auto level0 = controlPoints(regions, 0);
  ASSERT_EQ(level0.size(), 2u);
  EXPECT_EQ(level0[0].id, VertexId(0, 0).packed());
  EXPECT_EQ(level0[1].id, VertexId(0, 3).packed());
  auto level1 = controlPoints(regions, 1);
  ASSERT_EQ(level1.size(), 4u);  // v1:8 is shared by both regions: once
  for (const ControlPoint& p : level1) EXPECT_EQ(VertexId::fromPacked(p.id).level(), 1);
  EXPECT_EQ(controlPoints(regions, 2).size(), 5u);
  V3 lo, hi;
  ASSERT_TRUE(bounds(regions, &lo, &hi));
  EXPECT_FLOAT_EQ(hi.x, 1);
  EXPECT_FLOAT_EQ(lo.z, 0);
}

TEST(ViewControlPoints, NeighboursAtALevelShownAtItOrOneFinerAndADottedEdge) {
  const RegionMap regions = twoRegions();
  const auto ids = [](std::initializer_list<VertexId> list) {
    std::vector<uint64_t> out;
    for (VertexId v : list) out.push_back(v.packed());
    return out;
  };
  // At level 1, v1:8 shares a triangle with v1:0 (region 1) and v1:3, v1:12
  // (region 2); v2:30 is not a level-1 vertex.
  EXPECT_EQ(levelNeighbours(regions, VertexId(1, 8).packed(), 1), ids({{1, 0}, {1, 3}, {1, 12}}));
  EXPECT_EQ(levelNeighbours(regions, VertexId(2, 0).packed(), 2), ids({{2, 8}, {2, 30}}));
  EXPECT_TRUE(levelNeighbours(regions, VertexId(1, 99).packed(), 1).empty());
  // Shown one level finer: v0:1 and v0:2 are joined through v1:20, the
  // vertex on their edge; v1:21 is no level-0 vertex.
  auto fine = std::make_shared<RegionMesh>();
  fine->positions.resize(4);
  fine->normals.resize(4);
  fine->vertexIds = {VertexId(0, 1).packed(), VertexId(1, 20).packed(), VertexId(1, 21).packed(),
                     VertexId(0, 2).packed()};
  fine->triangles = {{0, 1, 2}, {1, 3, 2}};
  const RegionMap finer = {{1, fine}};
  EXPECT_EQ(levelNeighbours(finer, VertexId(0, 1).packed(), 0), ids({{0, 2}}));
  EXPECT_EQ(levelNeighbours(finer, VertexId(0, 2).packed(), 0), ids({{0, 1}}));
  const auto dots = segmentPoints({0, 0, 0}, {2, 4, 0}, 5);
  ASSERT_EQ(dots.size(), 5u);
  EXPECT_FLOAT_EQ(dots[2].y, 2);
  EXPECT_FLOAT_EQ(dots[4].x, 2);
}

// The undo rule of docs/VIEWER.md: a step is a drag or one key's edit.
TEST(ViewUndoHistory, UndoesAndRedoesWholeStepsOnceAnswered) {
  UndoHistory h;
  EXPECT_FALSE(h.undo().isOk());
  const auto drag = h.open();
  for (int i = 0; i < 3; ++i) h.sent(drag);
  h.acked(drag, 10);
  h.acked(drag, 11);
  EXPECT_NE(h.undo().status().message().find("still being made"), std::string::npos);
  h.close(drag);
  EXPECT_NE(h.undo().status().message().find("1 edits of the last step await"), std::string::npos);
  h.dropped(drag);  // the third move was rejected
  auto undo = h.undo();
  ASSERT_TRUE(undo.isOk()) << undo.status().message();
  EXPECT_EQ(*undo, (std::vector<uint64_t>{11, 10}));  // newest first
  EXPECT_FALSE(h.undo().isOk());
  auto redo = h.redo();
  ASSERT_TRUE(redo.isOk());
  EXPECT_EQ(*redo, (std::vector<uint64_t>{10, 11}));  // oldest first

  // A key's edit is a step of its own; its first Ack drops what could be redone.
  ASSERT_TRUE(h.undo().isOk());
  EXPECT_EQ(h.redoable(), 1u);
  const auto key = h.open();
  h.sent(key);
  h.close(key);
  h.acked(key, 12);
  EXPECT_EQ(h.redoable(), 0u);
  EXPECT_EQ(*h.undo(), (std::vector<uint64_t>{12}));
  EXPECT_EQ(h.undoable(), 0u);

  // A step all of whose edits were refused, or a click without a move, is no step.
  const auto refused = h.open();
  h.sent(refused);
  h.close(refused);
  h.dropped(refused);
  h.close(h.open());
  EXPECT_EQ(h.undoable(), 0u);
  EXPECT_EQ(h.redoable(), 1u);
}

TEST(ViewControlPoints, PickingTakesTheNearestFrontFacingPointAndDragStaysInItsPlane) {
  OrbitCamera camera;
  camera.frame({0, 0, 0}, {1, 1, 0});
  const auto points = controlPoints(twoRegions(), 1);
  for (size_t i = 0; i < points.size(); ++i) {
    auto s = camera.project(points[i].position, 800, 600);
    ASSERT_TRUE(s.has_value());
    auto hit = pickPoint(points, camera, 800, 600, (*s)[0] + 2, (*s)[1] - 2, 10);
    if (points[i].id == VertexId(1, 12).packed()) {
      // Its normal faces away from the eye.
      EXPECT_TRUE(!hit || points[*hit].id != points[i].id);
      continue;
    }
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(points[*hit].id, points[i].id);
    // Dragging to the pixel it is on leaves it where it is.
    const V3 t = dragTarget(camera, points[i].position, (*s)[0], (*s)[1], 800, 600);
    EXPECT_NEAR(length(t - points[i].position), 0, 1e-3f);
  }
  EXPECT_FALSE(pickPoint(points, camera, 800, 600, -500, -500, 10).has_value());
}

}  // namespace
}  // namespace tessera::view

namespace tessera::view {
namespace {

// The coarse morph stream's surface (coarse_morph.h): vertices named as the
// server's regions name them (the control vertex at its birth level), crease
// copies by their original's id; malformed replies refused by name.
TEST(ViewCoarseMorph, VerticesCarryTheirBirthLevelIdsAndBadRepliesAreRefused) {
  wire::MorphControl c;
  const float cube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (const auto& p : cube)
    for (float x : p) c.add_points(x);
  const int faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                            {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  for (const auto& f : faces)
    for (int v : f) c.add_triangles(static_cast<uint32_t>(v));
  for (auto [a, b] : {std::pair{4, 5}, {5, 6}, {6, 7}, {7, 4}}) {
    c.add_crease_vertices(a), c.add_crease_vertices(b), c.add_crease_sharpness(10);
  }
  c.set_max_level(3);
  auto base = coarseMorphBase(c);
  ASSERT_TRUE(base.isOk()) << base.status().message();
  auto mesh = refineCoarseMorph(*base, c, 2);
  ASSERT_TRUE(mesh.isOk()) << mesh.status().message();
  // Level 2 of the cube: 8 base vertices, 18 born at level 1, 72 at level 2.
  const size_t n = 8 + 18 + 72;
  ASSERT_GT(mesh->positions.size(), n);  // and the crease copies after them
  for (size_t v = 0; v < n; ++v) {
    const VertexId id = VertexId::fromPacked(mesh->vertexIds[v]);
    EXPECT_EQ(id.index(), v);
    EXPECT_EQ(id.level(), v < 8 ? 0 : v < 26 ? 1 : 2) << v;
  }
  for (size_t v = n; v < mesh->positions.size(); ++v) {
    const uint64_t index = VertexId::fromPacked(mesh->vertexIds[v]).index();
    ASSERT_LT(index, n) << v;
    EXPECT_EQ(mesh->positions[v], mesh->positions[index]) << v;
  }
  wire::MorphControl bad = c;
  bad.set_triangles(5, 9);
  EXPECT_NE(coarseMorphBase(bad).status().message().find("triangle 1 names vertex 9 of 8"),
            std::string::npos);
  wire::MorphControl fewer = c;
  fewer.mutable_points()->RemoveLast();
  fewer.mutable_points()->RemoveLast();
  fewer.mutable_points()->RemoveLast();
  EXPECT_NE(refineCoarseMorph(*base, fewer, 2).status().message().find("7 points for 8 base vertices"),
            std::string::npos);
}

}  // namespace
}  // namespace tessera::view

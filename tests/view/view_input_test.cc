// tessera-view's real input path (docs/VIEWER.md "Controls"): the interactive viewer under
// Xvfb, driven by X input events from xdotool (XTEST, as a user's mouse and
// keyboard), not by the self-test scripts. A click on a control vertex picks
// it (collaborators see the selection), a drag edits the document, Ctrl+Z
// undoes the whole drag, and Q quits. An observer connection checks each
// step through the server.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "client/view/camera.h"
#include "client/view/connection.h"
#include "client/view/control_points.h"
#include "core/hierarchy/ids.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"
#include "view/cube_document.h"
#include "view/wait_for.h"
#include "view/x_display.h"

namespace tessera::view {
namespace {

using ::tessera::testing::viewOptionsFor;
using ::tessera::testing::waitFor;

TEST(ViewInput, RealMouseAndKeyEventsPickDragUndoAndQuit) {
  const auto xvfbBinary = testing::findProgram("Xvfb");
  const auto xdotoolBinary = testing::findProgram("xdotool");
  if (!xvfbBinary || !xdotoolBinary)
    GTEST_SKIP() << "Xvfb or xdotool is missing (deploy/install-deps.sh installs both)";
  const std::string dir = ::tessera::testing::makeTempDir("tessera-view-input");
  auto server = ::tessera::testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto created = ::tessera::testing::createCube(*server, false, 4);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  const uint64_t doc = *created;
  testing::Xvfb xvfb;
  ASSERT_TRUE(xvfb.start(*xvfbBinary, dir + "/xvfb.log")) << "Xvfb did not start; see " << dir << "/xvfb.log";

  // The observer sees what the viewer will see first, and frames it the same
  // way (OrbitCamera::fit to every region vertex, as Viewer::update does).
  constexpr int kWidth = 800, kHeight = 600, kLevel = 1;
  ViewOptions options = viewOptionsFor(*server, doc, 2, 2);
  options.name = "observer";
  options.hashSurfaces = true;
  auto observer = Connection::open(options);
  ASSERT_TRUE(observer.isOk()) << observer.status().message();
  ASSERT_TRUE(waitFor([&] { return (*observer)->stats().ready; }, 30));
  const uint64_t startHash = (*observer)->stats().surfaceHash;
  const RegionMap regions = (*observer)->regions();
  const std::vector<ControlPoint> points = controlPoints(regions, kLevel);
  std::vector<V3> surface;
  for (const auto& [id, mesh] : regions)
    for (const Vec3& p : mesh->positions)
      surface.push_back({static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])});
  ASSERT_FALSE(surface.empty());
  OrbitCamera camera;
  camera.fit(surface, static_cast<float>(kWidth) / kHeight);
  const auto hit = pickPoint(points, camera, kWidth, kHeight, kWidth / 2.0f, kHeight / 2.0f, 1e9f);
  ASSERT_TRUE(hit.has_value());
  const auto at = camera.project(points[*hit].position, kWidth, kHeight);
  ASSERT_TRUE(at.has_value());
  const int x = static_cast<int>(std::lround((*at)[0])), y = static_cast<int>(std::lround((*at)[1]));
  const uint64_t target = points[*hit].id;

  const pid_t viewer =
      testing::spawn({TESSERA_VIEW_PATH, "--connect", "127.0.0.1:" + std::to_string(server->port()),
                      "--token", server->adminToken(), "--document", std::to_string(doc), "--name",
                      "mouse-and-keys", "--base-level", "2", "--max-level", "2", "--level",
                      std::to_string(kLevel), "--size", "800x600", "--no-hud", "--control-points"},
                     testing::viewerEnvironment(xvfb.display()), dir + "/view.log");
  const std::string& display = xvfb.display();
  const std::string window = ::tessera::testing::xdotool(
      *xdotoolBinary, display,
      "search --sync --onlyvisible --name 'tessera-view: document " + std::to_string(doc) + "'");
  const std::string id = window.substr(0, window.find('\n'));
  ASSERT_FALSE(id.empty()) << "no viewer window: " << window
                           << ::tessera::testing::fileBytes(dir + "/view.log");
  ::tessera::testing::xdotool(*xdotoolBinary, display, "windowfocus --sync " + id);

  // A click on the vertex picks it once the viewer has its snapshot: until
  // then a click lands on nothing and changes nothing, so it is repeated.
  // The viewer polls the buttons once a frame, so each press is held.
  auto selectedByViewer = [&] {
    for (const Collaborator& c : (*observer)->collaborators())
      if (c.name == "mouse-and-keys" && c.selectedVertices == std::vector<uint64_t>{target}) return true;
    return false;
  };
  bool picked = false;
  for (int attempt = 0; attempt < 20 && !picked; ++attempt) {
    ::tessera::testing::xdotool(*xdotoolBinary, display,
                                "mousemove --window " + id + " " + std::to_string(x) + " " +
                                    std::to_string(y) + " sleep 0.1 mousedown 1 sleep 0.2 mouseup 1");
    picked = waitFor(selectedByViewer, 0.5);
  }
  ASSERT_TRUE(picked) << "a click at (" << x << ", " << y << ") did not pick "
                      << VertexId::fromPacked(target).toString() << ": "
                      << ::tessera::testing::fileBytes(dir + "/view.log");

  // A drag: press on the vertex, move in steps, release.
  std::string drag =
      "mousemove --window " + id + " " + std::to_string(x) + " " + std::to_string(y) + " mousedown 1";
  for (int step = 1; step <= 8; ++step) {
    drag += " sleep 0.05 mousemove --window " + id + " " + std::to_string(x + 6 * step) + " " +
            std::to_string(y - 6 * step);
  }
  drag += " sleep 0.1 mouseup 1";
  ::tessera::testing::xdotool(*xdotoolBinary, display, drag);
  ASSERT_TRUE(waitFor(
      [&] { return (*observer)->stats().version > 1 && (*observer)->stats().surfaceHash != startHash; }, 30))
      << "the drag made no edit: " << ::tessera::testing::fileBytes(dir + "/view.log");
  // Edits stop once the drag is over.
  uint64_t dragged = 0;
  ASSERT_TRUE(waitFor(
      [&] {
        const uint64_t v = (*observer)->stats().version;
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        dragged = (*observer)->stats().version;
        return v == dragged;
      },
      30));

  // Ctrl+Z takes the whole drag back with one undo per edit step: the
  // surface returns to its start.
  ::tessera::testing::xdotool(*xdotoolBinary, display, "key --clearmodifiers ctrl+z");
  EXPECT_TRUE(waitFor([&] { return (*observer)->stats().surfaceHash == startHash; }, 30))
      << "Ctrl+Z did not restore the surface (version " << (*observer)->stats().version << ", drag ended at "
      << dragged << "): " << ::tessera::testing::fileBytes(dir + "/view.log");
  EXPECT_GT((*observer)->stats().version, dragged);

  ::tessera::testing::xdotool(*xdotoolBinary, display, "key q");
  EXPECT_EQ(testing::waitBounded(viewer, 20), 0)
      << "Q did not quit the viewer: " << ::tessera::testing::fileBytes(dir + "/view.log");
}

}  // namespace
}  // namespace tessera::view

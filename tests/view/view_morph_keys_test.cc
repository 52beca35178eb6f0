// The morph keys of the interactive tessera-view (docs/VIEWER.md "Morph documents") under Xvfb,
// pressed as a user presses them (xdotool, XTEST), on a morph document of
// the real server. The server's count of encoded regions (StatsReply
// regions_encoded) shows what the viewer asked for: `.` steps t and
// subscribes at the new time (a morph view is built and encoded); `P`
// plays through the coarse stream (control points only: nothing is
// encoded); `P` again pauses at a time the view has not shown yet and
// subscribes there (encoded again); `Q` quits.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <sstream>
#include <thread>

#include "client/lib/session.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "integration/server_stat.h"
#include "support/test_meshes.h"
#include "view/cube_document.h"
#include "view/wait_for.h"
#include "view/x_display.h"

namespace tessera::view {
namespace {

using ::tessera::testing::waitFor;

double regionsEncoded(client::Session& s) {
  return ::tessera::testing::serverStat(s, "regions_encoded");
}

// The value once it has not changed for half a second.
double settled(client::Session& s) {
  double last = regionsEncoded(s);
  for (int i = 0; i < 40; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    const double now = regionsEncoded(s);
    if (now == last) return now;
    last = now;
  }
  return last;
}

TEST(ViewMorphKeys, StepPlayAndPauseAskTheServerForWhatTheyShow) {
  const auto xvfbBinary = ::tessera::testing::findProgram("Xvfb");
  const auto xdotoolBinary = ::tessera::testing::findProgram("xdotool");
  if (!xvfbBinary || !xdotoolBinary)
    GTEST_SKIP() << "Xvfb or xdotool is missing (deploy/install-deps.sh installs both)";
  const std::string dir = ::tessera::testing::makeTempDir("tessera-view-morph-keys");
  auto server = ::tessera::testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto created = ::tessera::testing::createCube(*server, true, 3);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  const uint64_t doc = *created;
  auto admin = client::Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  ASSERT_TRUE((*admin)->call(::tessera::testing::openDocument(doc), 10).isOk());
  // Key 1: the cube stretched along x.
  std::istringstream cube(::tessera::testing::fileBytes(::tessera::testing::sourceTestDataPath("cube.obj")));
  std::string key1;
  for (std::string line; std::getline(cube, line);) {
    double x = 0, y = 0, z = 0;
    if (std::sscanf(line.c_str(), "v %lf %lf %lf", &x, &y, &z) == 3) {
      key1 += "v " + std::to_string(1.8 * x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
    } else {
      key1 += line + "\n";
    }
  }
  wire::ClientMessage add;
  add.mutable_add_morph_key()->set_document_id(doc);
  add.mutable_add_morph_key()->set_mesh(key1);
  add.mutable_add_morph_key()->set_mesh_format(wire::MESH_FORMAT_OBJ);
  auto added = (*admin)->call(add, 30);
  ASSERT_TRUE(added.isOk() && added->has_ack()) << added->DebugString();

  ::tessera::testing::Xvfb xvfb;
  ASSERT_TRUE(xvfb.start(*xvfbBinary, dir + "/xvfb.log")) << "Xvfb did not start; see " << dir << "/xvfb.log";
  const double beforeViewer = regionsEncoded(**admin);
  const pid_t viewer = ::tessera::testing::spawn(
      {TESSERA_VIEW_PATH, "--connect", "127.0.0.1:" + std::to_string(server->port()), "--token",
       server->adminToken(), "--document", std::to_string(doc), "--base-level", "1", "--max-level", "2",
       "--morph-rate", "0.5", "--size", "640x480"},
      ::tessera::testing::viewerEnvironment(xvfb.display()), dir + "/view.log");
  const std::string& display = xvfb.display();
  const std::string window = ::tessera::testing::xdotool(
      *xdotoolBinary, display,
      "search --sync --onlyvisible --name 'tessera-view: document " + std::to_string(doc) + "'");
  const std::string id = window.substr(0, window.find('\n'));
  ASSERT_FALSE(id.empty()) << "no viewer window: " << window
                           << ::tessera::testing::fileBytes(dir + "/view.log");
  ::tessera::testing::xdotool(*xdotoolBinary, display, "windowfocus --sync " + id);
  // Key 0 live first: its view is built once the viewer subscribes.
  ASSERT_TRUE(waitFor([&] { return regionsEncoded(**admin) > beforeViewer; }, 30))
      << ::tessera::testing::fileBytes(dir + "/view.log");
  const double live = settled(**admin);

  // `.`: t = 0.05, the exact surface there.
  ::tessera::testing::xdotool(*xdotoolBinary, display, "key period");
  ASSERT_TRUE(waitFor([&] { return regionsEncoded(**admin) > live; }, 30))
      << "'.' asked for no surface at t = 0.05: " << ::tessera::testing::fileBytes(dir + "/view.log");
  const double stepped = settled(**admin);

  // `P`: playing, through the control points: the server encodes nothing.
  ::tessera::testing::xdotool(*xdotoolBinary, display, "key p");
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));
  EXPECT_EQ(regionsEncoded(**admin), stepped) << "playing asked for regions, not control points";
  // `P` again: paused at about t = 0.65, a time not shown yet: encoded.
  ::tessera::testing::xdotool(*xdotoolBinary, display, "key p");
  EXPECT_TRUE(waitFor([&] { return regionsEncoded(**admin) > stepped; }, 30))
      << "pausing asked for no surface: " << ::tessera::testing::fileBytes(dir + "/view.log");

  ::tessera::testing::xdotool(*xdotoolBinary, display, "key q");
  EXPECT_EQ(::tessera::testing::waitBounded(viewer, 20), 0)
      << "Q did not quit the viewer: " << ::tessera::testing::fileBytes(dir + "/view.log");
}

}  // namespace
}  // namespace tessera::view

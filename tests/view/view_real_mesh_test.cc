// tessera-view on a real mesh on a busy machine: fandisk from
// Debian's libcgal-demo with its sharp feature lines tagged as creases,
// rendered headless 20 times in a row, with no display (EGL surfaceless;
// no Xvfb, docs/VIEWER.md "Headless mode"), while two other processes keep both cores
// busy. Before the client's read path kept its bytes, a snapshot
// this size failed in 25 of 26 such runs ("no snapshot: timed out", or a
// frame announcing a garbage length) because the viewer polls with a 5 ms
// timeout and a timed-out read dropped what it had read.
#include <gtest/gtest.h>
#include <signal.h>
#include <stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "client/lib/session.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"
#include "view/feature_tags.h"
#include "view/x_display.h"

namespace tessera {
namespace {

// A process that spins until killed: the "other process loading the cores".
pid_t spinner() {
  const pid_t pid = fork();
  if (pid == 0) {
    volatile uint64_t x = 0;
    for (;;) x = x + 1;
  }
  return pid;
}

TEST(ViewRealMesh, FandiskWithItsCreasesRendersTwentyTimesOnABusyMachine) {
  const std::string dir = testing::makeTempDir("tessera-view-fandisk");
  const std::string off = testing::cgalMeshPath("fandisk.off");
  int creases = 0;
  const std::string tags = testing::featureTags(off, 40, creases);
  ASSERT_GT(creases, 500) << "fandisk's feature lines were not found";

  auto server = testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = client::Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk()) << admin.status().message();
  wire::ClientMessage create = testing::createDocument("fandisk", testing::fileBytes(off), tags, 4);
  create.mutable_create_document()->set_mesh_format(wire::MESH_FORMAT_OFF);
  auto created = (*admin)->call(create, 120);
  ASSERT_TRUE(created.isOk() && created->has_ack())
      << (created.isOk() ? created->DebugString() : created.status().message());
  const uint64_t doc = created->ack().document_id();

  const auto env = testing::headlessEnvironment();
  const pid_t load[2] = {spinner(), spinner()};
  int passed = 0;
  for (int run = 0; run < 20; ++run) {
    const std::string png = dir + "/fandisk-" + std::to_string(run) + ".png";
    const int code = testing::runBounded(
        {TESSERA_VIEW_PATH, "--connect", "127.0.0.1:" + std::to_string(server->port()), "--token",
         server->adminToken(), "--document", std::to_string(doc), "--base-level", "1", "--max-level", "2",
         "--screenshot", png, "--frames", "3", "--no-hud", "--timeout", "60"},
        env, dir + "/view.log", 120);
    EXPECT_EQ(code, 0) << "run " << run << " failed; see " << dir << "/view.log";
    if (code != 0) continue;
    int w = 0, h = 0, channels = 0;
    unsigned char* rgb = stbi_load(png.c_str(), &w, &h, &channels, 3);
    ASSERT_NE(rgb, nullptr) << png;
    // The model covers a real part of the frame (the corner is background).
    size_t covered = 0;
    for (int i = 0; i < w * h; ++i) {
      covered += std::abs(rgb[3 * i] - rgb[0]) + std::abs(rgb[3 * i + 1] - rgb[1]) +
                     std::abs(rgb[3 * i + 2] - rgb[2]) >
                 24;
    }
    stbi_image_free(rgb);
    EXPECT_GT(static_cast<double>(covered) / (w * h), 0.05) << png;
    ++passed;
  }
  for (pid_t pid : load) kill(pid, SIGKILL), waitpid(pid, nullptr, 0);
  EXPECT_EQ(passed, 20);
  EXPECT_EQ(server->stop(), 0);
}

}  // namespace
}  // namespace tessera

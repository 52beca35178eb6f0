// tessera-view end to end (docs/VIEWER.md): the real server, the real viewer
// rendering headless with no display (EGL on Mesa's surfaceless platform,
// llvmpipe), and the PNG read back.
// The object must be visible with a plausible silhouette, an edit made by
// another client must change the picture, and so must the viewer's own pick
// and drag of a control vertex (--drag, synthetic mouse input).
#include <gtest/gtest.h>
#include <signal.h>
#include <stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "client/lib/session.h"
#include "core/hierarchy/ids.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"
#include "view/cube_document.h"
#include "view/png_image.h"
#include "view/x_display.h"

namespace tessera {
namespace {

using testing::differ;
using testing::findProgram;
using testing::headlessEnvironment;
using testing::readPng;
using testing::runBounded;
using testing::viewerEnvironment;
using testing::Xvfb;

TEST(View, HeadlessScreenshotsShowTheSurfaceAnotherClientsEditAndADrag) {
  const std::string dir = testing::makeTempDir("tessera-view");
  auto server = testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = client::Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk()) << admin.status().message();
  auto created = (*admin)->call(
      testing::createDocument("cube", testing::fileBytes(testing::sourceTestDataPath("cube.obj")),
                              testing::fileBytes(testing::sourceTestDataPath("cube.tags")), 5),
      30);
  ASSERT_TRUE(created.isOk() && created->has_ack())
      << (created.isOk() ? created->DebugString() : created.status().message());
  const uint64_t doc = created->ack().document_id();
  auto granted = (*admin)->call(testing::grant(doc, wire::ROLE_VIEWER, "viewer-token-0123456789"), 10);
  ASSERT_TRUE(granted.isOk() && granted->has_ack());

  const testing::Environment env = headlessEnvironment();
  auto screenshot = [&](const std::string& png, const std::string& token = "viewer-token-0123456789",
                        std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {TESSERA_VIEW_PATH,
                                     "--connect",
                                     "127.0.0.1:" + std::to_string(server->port()),
                                     "--token",
                                     token,
                                     "--document",
                                     std::to_string(doc),
                                     "--base-level",
                                     "2",
                                     "--max-level",
                                     "3",
                                     "--screenshot",
                                     png,
                                     "--frames",
                                     "30",
                                     "--no-hud",
                                     "--timeout",
                                     "60"};
    args.insert(args.end(), extra.begin(), extra.end());
    return runBounded(args, env, dir + "/view.log", 120);
  };

  const std::string first = dir + "/a.png";
  ASSERT_EQ(screenshot(first), 0) << "tessera-view failed; see " << dir << "/view.log";
  auto a = readPng(first);
  ASSERT_TRUE(a.has_value()) << first << " is not a readable PNG";
  ASSERT_EQ(a->width, 800);
  ASSERT_EQ(a->height, 600);
  // The corner shows the background colour; the silhouette is everything else.
  const auto background = a->at(0, 0);
  size_t covered = 0;
  for (int y = 0; y < a->height; ++y)
    for (int x = 0; x < a->width; ++x) covered += differ(a->at(x, y), background);
  const double fraction = static_cast<double>(covered) / (a->width * a->height);
  EXPECT_GT(fraction, 0.02) << "the surface is not visible";
  EXPECT_LT(fraction, 0.80) << "the surface fills the frame";
  // Shaded, not flat: the lit surface shows more than a couple of colours.
  std::set<std::array<int, 3>> colours;
  for (int y = 0; y < a->height; y += 3)
    for (int x = 0; x < a->width; x += 3) colours.insert(a->at(x, y));
  EXPECT_GT(colours.size(), 20u);

  // Another client pulls a corner far out; a new screenshot must show it.
  auto editor = client::Session::connect(server->session("editor", server->adminToken()));
  ASSERT_TRUE(editor.isOk()) << editor.status().message();
  auto opened = (*editor)->call(testing::openDocument(doc), 10);
  ASSERT_TRUE(opened.isOk() && opened->has_ack());
  auto moved = (*editor)->call(testing::moveVertex(doc, VertexId(2, 0).packed(), 0.1, 0.2, 1.4), 10);
  ASSERT_TRUE(moved.isOk() && moved->has_ack())
      << (moved.isOk() ? moved->DebugString() : moved.status().message());

  const std::string second = dir + "/b.png";
  ASSERT_EQ(screenshot(second), 0) << "tessera-view failed; see " << dir << "/view.log";
  auto b = readPng(second);
  ASSERT_TRUE(b.has_value() && b->width == a->width && b->height == a->height);
  size_t changed = 0;
  for (int y = 0; y < a->height; ++y)
    for (int x = 0; x < a->width; ++x) changed += differ(a->at(x, y), b->at(x, y));
  EXPECT_GT(changed, static_cast<size_t>(a->width * a->height / 100))
      << "the edit did not change the picture";

  // The viewer's own pick and drag: a control vertex near the centre, dragged
  // 80 pixels up and right, becomes MoveVertex edits whose deltas come back.
  const std::string editorToken = "editor-token-0123456789";
  auto editorGrant = (*admin)->call(testing::grant(doc, wire::ROLE_EDITOR, editorToken), 10);
  ASSERT_TRUE(editorGrant.isOk() && editorGrant->has_ack());
  const std::string third = dir + "/c.png";
  ASSERT_EQ(screenshot(third, editorToken, {"--drag", "80,-80"}), 0)
      << "tessera-view failed; see " << dir << "/view.log";
  const std::string log = testing::fileBytes(dir + "/view.log");
  EXPECT_NE(log.find("dragged v0:"), std::string::npos) << log;
  EXPECT_NE(log.find(" 0 rejected"), std::string::npos) << log;
  EXPECT_EQ(log.find("edit to delta -1"), std::string::npos) << "no edit-to-delta latency measured: " << log;
  wire::ClientMessage list;
  list.mutable_list_documents();
  auto listed = (*admin)->call(list, 10);
  ASSERT_TRUE(listed.isOk() && listed->has_document_list());
  ASSERT_EQ(listed->document_list().documents_size(), 1);
  EXPECT_GT(listed->document_list().documents(0).version(), 2u) << "the drag made no edit";
  auto c = readPng(third);
  ASSERT_TRUE(c.has_value() && c->width == b->width && c->height == b->height);
  size_t dragged = 0;
  for (int y = 0; y < b->height; ++y)
    for (int x = 0; x < b->width; ++x) dragged += differ(b->at(x, y), c->at(x, y));
  EXPECT_GT(dragged, static_cast<size_t>(b->width * b->height / 200))
      << "the drag did not change the picture";

  // Client-side refinement: the same document refined with up to 2 splits
  // per edge still shows the object, with more triangles drawn than received.
  const std::string plain = dir + "/r0.png", refined = dir + "/r2.png";
  ASSERT_EQ(screenshot(plain), 0) << "tessera-view failed; see " << dir << "/view.log";
  ASSERT_EQ(screenshot(refined, "viewer-token-0123456789", {"--refine", "2"}), 0)
      << "tessera-view --refine 2 failed; see " << dir << "/view.log";
  auto r0 = readPng(plain), r2 = readPng(refined);
  ASSERT_TRUE(r0.has_value() && r2.has_value() && r2->width == r0->width && r2->height == r0->height);
  size_t refinedCovered = 0, refinedChanged = 0;
  for (int y = 0; y < r2->height; ++y) {
    for (int x = 0; x < r2->width; ++x) {
      refinedCovered += differ(r2->at(x, y), background);
      refinedChanged += differ(r2->at(x, y), r0->at(x, y));
    }
  }
  EXPECT_GT(refinedCovered, static_cast<size_t>(r2->width * r2->height / 50))
      << "the refined surface is not visible";
  EXPECT_LT(refinedCovered, static_cast<size_t>(r2->width * r2->height * 4 / 5));
  std::printf("--refine 2: %zu of %d pixels differ from the unrefined picture\n", refinedChanged,
              r2->width * r2->height);
  std::fflush(stdout);  // before the next fork copies the buffer
  // The "wrote PNG (..., N triangles)" lines of the two runs.
  const std::string logs = testing::fileBytes(dir + "/view.log");
  auto trianglesOf = [&](const std::string& png) -> long long {
    const size_t at = logs.find("wrote " + png + " ");
    const size_t end = at == std::string::npos ? at : logs.find(" triangles)", at);
    if (end == std::string::npos) return -1;
    return std::atoll(logs.c_str() + logs.rfind(' ', end - 1) + 1);
  };
  EXPECT_GT(trianglesOf(plain), 0) << logs;
  EXPECT_GT(trianglesOf(refined), 2 * trianglesOf(plain)) << logs;

  // The HUD (Dear ImGui) draws its window in the top-left corner.
  const std::string withHud = dir + "/hud.png";
  auto args = std::vector<std::string>{TESSERA_VIEW_PATH,
                                       "--connect",
                                       "127.0.0.1:" + std::to_string(server->port()),
                                       "--token",
                                       "viewer-token-0123456789",
                                       "--document",
                                       std::to_string(doc),
                                       "--base-level",
                                       "2",
                                       "--max-level",
                                       "3",
                                       "--screenshot",
                                       withHud,
                                       "--frames",
                                       "5",
                                       "--refine",  // the HUD's refinement line too
                                       "1"};
  ASSERT_EQ(runBounded(args, env, dir + "/view.log", 120), 0)
      << "tessera-view failed; see " << dir << "/view.log";
  auto h = readPng(withHud);
  ASSERT_TRUE(h.has_value() && h->width == c->width && h->height == c->height);
  size_t hud = 0;
  for (int y = 10; y < 60; ++y)
    for (int x = 10; x < 200; ++x) hud += differ(c->at(x, y), h->at(x, y));
  EXPECT_GT(hud, 500u) << "no HUD in the top-left corner";

  // Interactive mode (no --screenshot) keeps running until closed: a window,
  // so an X server.
  const auto xvfbBinary = findProgram("Xvfb");
  if (!xvfbBinary) {
    std::printf("Xvfb is not installed: the interactive window is not tried\n");
    EXPECT_EQ(server->stop(), 0);
    return;
  }
  Xvfb xvfb;
  ASSERT_TRUE(xvfb.start(*xvfbBinary, dir + "/xvfb.log")) << "Xvfb did not start; see " << dir << "/xvfb.log";
  const pid_t interactive = fork();
  if (interactive == 0) {
    for (const auto& [name, value] : viewerEnvironment(xvfb.display()))
      setenv(name.c_str(), value.c_str(), 1);
    FILE* out = std::freopen((dir + "/interactive.log").c_str(), "a", stderr);
    (void)out;
    execl(TESSERA_VIEW_PATH, TESSERA_VIEW_PATH, "--connect",
          ("127.0.0.1:" + std::to_string(server->port())).c_str(), "--token", "viewer-token-0123456789",
          "--document", std::to_string(doc).c_str(), "--wireframe", "--region-colours",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_GT(interactive, 0);
  std::this_thread::sleep_for(std::chrono::seconds(2));
  int status = 0;
  EXPECT_EQ(waitpid(interactive, &status, WNOHANG), 0)
      << "the interactive viewer exited early; see " << dir << "/interactive.log";
  kill(interactive, SIGTERM);
  waitpid(interactive, &status, 0);
  EXPECT_EQ(server->stop(), 0);
}

// "name=hash" pairs after "surface hashes:" in the --edit-keys line, in order.
std::vector<std::pair<std::string, std::string>> surfaceHashes(const std::string& log) {
  std::vector<std::pair<std::string, std::string>> out;
  const size_t at = log.find("surface hashes:");
  if (at == std::string::npos) return out;
  std::istringstream line(log.substr(at + 15, log.find(';', at) - at - 15));
  std::string token;
  while (line >> token) {
    const size_t eq = token.find('=');
    if (eq != std::string::npos) out.push_back({token.substr(0, eq), token.substr(eq + 1)});
  }
  return out;
}

// tessera-view --edit-keys on `doc`: level-1 control vertices over a
// uniform level-2 tessellation, a bounded run writing dir/keys.png; its exit
// code and log.
std::pair<int, std::string> runEditKeys(const testing::ServerProcess& server, uint64_t doc,
                                        const std::string& dir) {
  const int rc = runBounded({TESSERA_VIEW_PATH,
                             "--connect",
                             "127.0.0.1:" + std::to_string(server.port()),
                             "--token",
                             server.adminToken(),
                             "--document",
                             std::to_string(doc),
                             "--base-level",
                             "2",
                             "--max-level",
                             "2",
                             "--level",
                             "1",
                             "--edit-keys",
                             "--screenshot",
                             dir + "/keys.png",
                             "--frames",
                             "3",
                             "--no-hud",
                             "--timeout",
                             "30"},
                            headlessEnvironment(), dir + "/keys.log", 60);
  return {rc, testing::fileBytes(dir + "/keys.log")};
}

// The sharpness keys' hashes, "start" first: E, 2 and K each change the
// surface, three undos step back exactly, redo brings the sharp edge back.
void expectSharpnessKeys(const std::vector<std::pair<std::string, std::string>>& h, const std::string& log) {
  const std::vector<std::string> names = {"start", "E", "2", "K", "undo", "undo", "undo", "redo"};
  ASSERT_EQ(h.size(), names.size()) << log;
  for (size_t i = 0; i < names.size(); ++i) EXPECT_EQ(h[i].first, names[i]) << log;
  EXPECT_NE(h[1].second, h[0].second) << "E did not change the surface: " << log;
  EXPECT_NE(h[2].second, h[1].second) << "2 gave the same surface as E (+inf): " << log;
  EXPECT_NE(h[2].second, h[0].second) << "2 gave the smooth surface: " << log;
  EXPECT_NE(h[3].second, h[2].second) << "K did not change the surface: " << log;
  EXPECT_EQ(h[4].second, h[2].second) << "the first undo did not take back K alone: " << log;
  EXPECT_EQ(h[5].second, h[1].second) << "the second undo did not take back 2: " << log;
  EXPECT_EQ(h[6].second, h[0].second) << "the third undo did not restore the surface: " << log;
  EXPECT_EQ(h[7].second, h[1].second) << "redo did not bring the sharp edge back: " << log;
}

// --edit-keys: the I, =, E, 2, K, Ctrl+Z and Ctrl+Y keys go through the
// viewer's own key handling. I makes the vertex picked by click interpolating
// (docs/INTERPOLATION.md) and = doubles its tension, each changing the surface; I again
// brings plain Loop back exactly. E on the edge picked by click and
// shift+click, 2 (semi-sharp) and K change the surface; three undos restore
// it step by step; redo brings the sharp edge back.
TEST(View, HeadlessEditKeysSharpenAnEdgeAndUndoRestoresTheSurface) {
  const std::string dir = testing::makeTempDir("tessera-view-keys");
  auto server = testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  // No tags: every edge starts smooth.
  auto created = testing::createCube(*server, false, 4);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  const uint64_t doc = *created;
  // Level-1 control vertices over a uniform level-2 tessellation: a sharp
  // level-1 edge changes the level-2 vertex on it. (At the displayed level a
  // lone sharp edge changes no limit position: both its ends are darts.)
  const auto [rc, log] = runEditKeys(*server, doc, dir);
  ASSERT_EQ(rc, 0) << log;
  EXPECT_NE(log.find("keys: edge v1:"), std::string::npos) << log;
  EXPECT_NE(log.find("10 edits sent, 0 rejected"), std::string::npos) << log;
  auto all = surfaceHashes(log);
  ASSERT_EQ(all.size(), 11u) << log;
  const std::vector<std::string> first = {"start", "I", "tighter", "I-off"};
  for (size_t i = 0; i < first.size(); ++i) EXPECT_EQ(all[i].first, first[i]) << log;
  EXPECT_NE(all[1].second, all[0].second) << "I did not change the surface: " << log;
  EXPECT_NE(all[2].second, all[1].second) << "= did not change the surface: " << log;
  EXPECT_EQ(all[3].second, all[0].second) << "I again did not bring plain Loop back: " << log;
  // From here on, the sharpness keys ("start" is plain Loop again).
  std::vector<std::pair<std::string, std::string>> h = {all[0]};
  h.insert(h.end(), all.begin() + 4, all.end());
  expectSharpnessKeys(h, log);
  EXPECT_NE(log.find("document version 11,"), std::string::npos) << "ten keys, ten versions: " << log;
}

TEST(View, ExitsWithAnErrorWhenTheDocumentDoesNotExist) {
  const std::string dir = testing::makeTempDir("tessera-view-missing");
  auto server = testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  // Refused at open, before any window: no display needed.
  const int rc = runBounded(
      {TESSERA_VIEW_PATH, "--connect", "127.0.0.1:" + std::to_string(server->port()), "--token",
       server->adminToken(), "--document", "99", "--screenshot", dir + "/x.png", "--timeout", "10"},
      {}, dir + "/view.log", 60);
  EXPECT_EQ(rc, 1);
  EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
  EXPECT_EQ(runBounded({TESSERA_VIEW_PATH, "--document", "1"}, {}, dir + "/usage.log", 30), 2);
}

// The viewer on a Catmull-Clark document (the cube as six quads): its own
// pick and keys crease an edge (E, 2) and make a corner (K), undo and redo
// step through them; the interpolation keys (I, =), which are Loop's, are
// refused by the server and change nothing; a drag of a level-1 control
// vertex becomes accepted MoveVertex edits. The picture shows the surface.
TEST(View, HeadlessPickCreaseCornerAndDragOnACatmullClarkDocument) {
  const std::string dir = testing::makeTempDir("tessera-view-catmark");
  auto server = testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto created = testing::createFromTestData(*server, "good/cube_quads.obj", "", 4);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  const std::string doc = std::to_string(*created);
  const std::string connect = "127.0.0.1:" + std::to_string(server->port());
  auto [rc, log] = runEditKeys(*server, *created, dir);
  ASSERT_EQ(rc, 0) << log;
  EXPECT_NE(log.find("keys: edge v1:"), std::string::npos) << log;
  EXPECT_NE(log.find("10 edits sent, 3 rejected"), std::string::npos) << log;
  auto all = surfaceHashes(log);
  ASSERT_EQ(all.size(), 11u) << log;
  const std::vector<std::string> first = {"start", "I", "tighter", "I-off"};
  for (size_t i = 0; i < first.size(); ++i) EXPECT_EQ(all[i].first, first[i]) << log;
  for (size_t i : {1, 2, 3})
    EXPECT_EQ(all[i].second, all[0].second) << all[i].first << " changed the surface: " << log;
  std::vector<std::pair<std::string, std::string>> h = {all[0]};
  h.insert(h.end(), all.begin() + 4, all.end());
  expectSharpnessKeys(h, log);
  EXPECT_NE(log.find("document version 8,"), std::string::npos) << "seven accepted keys: " << log;

  rc = runBounded({TESSERA_VIEW_PATH,
                   "--connect",
                   connect,
                   "--token",
                   server->adminToken(),
                   "--document",
                   doc,
                   "--base-level",
                   "1",
                   "--max-level",
                   "4",
                   "--level",
                   "1",
                   "--control-points",
                   "--drag",
                   "80,-80",
                   "--screenshot",
                   dir + "/drag.png",
                   "--frames",
                   "3",
                   "--no-hud",
                   "--size",
                   "640x480",
                   "--timeout",
                   "30"},
                  headlessEnvironment(), dir + "/drag.log", 60);
  log = testing::fileBytes(dir + "/drag.log");
  ASSERT_EQ(rc, 0) << log;
  EXPECT_NE(log.find("dragged v1:"), std::string::npos) << log;
  EXPECT_NE(log.find(" 0 rejected"), std::string::npos) << log;
  const size_t version = log.find("document version ");
  ASSERT_NE(version, std::string::npos) << log;
  EXPECT_GT(std::stoi(log.substr(version + 17)), 8) << "the drag made no edit: " << log;
  auto picture = readPng(dir + "/drag.png");
  ASSERT_TRUE(picture.has_value());
  const auto background = picture->at(0, 0);
  size_t covered = 0;
  for (int y = 0; y < picture->height; ++y)
    for (int x = 0; x < picture->width; ++x) covered += differ(picture->at(x, y), background);
  EXPECT_GT(covered, static_cast<size_t>(picture->width * picture->height / 20))
      << "the surface is not visible";
}

}  // namespace
}  // namespace tessera

// tessera-view --codec (docs/VIEWER.md "Region codecs"): the real viewer,
// headless, against the real server. With a LOD profile on fandisk, --codec meshopt
// makes the server send meshopt regions (counted by the viewer from each
// decoded region's header) and shows the same surface as Draco: the same
// surface hash (docs/PROTOCOL.md 6.5), triangle count and picture. With a
// view, which the server sends in Draco only (docs/REGION_ENCODING.md
// "meshopt regions"), meshopt is refused at start naming the conflict.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "client/lib/session.h"
#include "client/view/connection.h"
#include "client/view/view_options.h"
#include "core/hierarchy/ids.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"
#include "view/cube_document.h"
#include "view/png_image.h"
#include "view/wait_for.h"
#include "view/x_display.h"

namespace tessera {
namespace {

// What one headless run printed: "wrote X (..., N triangles)" and
// "regions received: D draco, M meshopt; surface hash H".
struct Shown {
  long long triangles = -1;
  long long draco = -1, meshopt = -1;
  std::string hash;
};

Shown shownIn(const std::string& log) {
  Shown s;
  if (const size_t end = log.rfind(" triangles)"); end != std::string::npos)
    s.triangles = std::atoll(log.c_str() + log.rfind(' ', end - 1) + 1);
  const std::string key = "regions received: ";
  const size_t at = log.rfind(key);
  if (at == std::string::npos) return s;
  if (std::sscanf(log.c_str() + at + key.size(), "%lld draco, %lld meshopt", &s.draco, &s.meshopt) != 2)
    return s;
  const std::string hashKey = "; surface hash ";
  const size_t hashAt = log.find(hashKey, at);
  const size_t lineEnd = log.find('\n', at);
  if (hashAt != std::string::npos && hashAt < lineEnd)
    s.hash = log.substr(hashAt + hashKey.size(), lineEnd - hashAt - hashKey.size());
  return s;
}

std::vector<std::string> viewerArgs(const testing::ServerProcess& server, uint64_t doc) {
  return {TESSERA_VIEW_PATH,
          "--connect",
          "127.0.0.1:" + std::to_string(server.port()),
          "--token",
          server.adminToken(),
          "--document",
          std::to_string(doc),
          "--no-hud",
          "--timeout",
          "60"};
}

// fandisk from Debian's libcgal-demo as a document: many regions, unlike
// the cube's one. The document id, or what failed.
Expected<uint64_t> createFandisk(const testing::ServerProcess& server) {
  TESSERA_ASSIGN_OR_RETURN(std::unique_ptr<client::Session> admin,
                           client::Session::connect(server.session("admin", server.adminToken())));
  wire::ClientMessage create =
      testing::createDocument("fandisk", testing::fileBytes(testing::cgalMeshPath("fandisk.off")), "", 3);
  create.mutable_create_document()->set_mesh_format(wire::MESH_FORMAT_OFF);
  auto created = admin->call(create, 120);
  if (!created.isOk()) return created.status();
  if (!created->has_ack()) return internalError("creating fandisk: " + created->DebugString());
  return created->ack().document_id();
}

TEST(ViewCodec, MeshoptOnAProfileShowsTheSameSurfaceAsDraco) {
  const std::string dir = testing::makeTempDir("tessera-view-codec");
  auto server = testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto created = createFandisk(*server);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  const uint64_t doc = *created;

  const testing::Environment env = testing::headlessEnvironment();
  auto run = [&](const std::string& codec, Shown* shown) {
    std::vector<std::string> args = viewerArgs(*server, doc);
    const std::string png = dir + "/" + codec + ".png", log = dir + "/" + codec + ".log";
    args.insert(args.end(), {"--base-level", "1", "--max-level", "2", "--codec", codec, "--surface-hash",
                             "--screenshot", png, "--frames", "5"});
    const int rc = testing::runBounded(args, env, log, 120);
    *shown = shownIn(testing::fileBytes(log));
    return rc;
  };
  Shown draco, meshopt;
  ASSERT_EQ(run("draco", &draco), 0) << testing::fileBytes(dir + "/draco.log");
  ASSERT_EQ(run("meshopt", &meshopt), 0) << testing::fileBytes(dir + "/meshopt.log");
  const std::string logs = testing::fileBytes(dir + "/draco.log") + testing::fileBytes(dir + "/meshopt.log");

  // The server sent each viewer the codec it asked for.
  EXPECT_GT(draco.draco, 0) << logs;
  EXPECT_EQ(draco.meshopt, 0) << logs;
  EXPECT_EQ(meshopt.draco, 0) << "--codec meshopt received Draco regions: " << logs;
  EXPECT_GT(meshopt.meshopt, 0) << "--codec meshopt received no meshopt region: " << logs;
  EXPECT_EQ(meshopt.meshopt, draco.draco) << "the same regions in either codec: " << logs;
  // The same surface: hash, triangles drawn, picture.
  EXPECT_FALSE(draco.hash.empty()) << logs;
  EXPECT_EQ(meshopt.hash, draco.hash) << logs;
  EXPECT_GT(draco.triangles, 0) << logs;
  EXPECT_EQ(meshopt.triangles, draco.triangles) << logs;
  auto a = testing::readPng(dir + "/draco.png"), b = testing::readPng(dir + "/meshopt.png");
  ASSERT_TRUE(a.has_value() && b.has_value() && a->width == b->width && a->height == b->height);
  const auto background = a->at(0, 0);
  size_t covered = 0, changed = 0;
  for (int y = 0; y < a->height; ++y) {
    for (int x = 0; x < a->width; ++x) {
      covered += testing::differ(b->at(x, y), background);
      changed += testing::differ(a->at(x, y), b->at(x, y));
    }
  }
  const size_t pixels = static_cast<size_t>(a->width) * a->height;
  EXPECT_GT(covered, pixels / 50) << "the meshopt surface is not visible";
  // Bit-identical positions; the triangles' order may differ, which moves
  // at most a few anti-aliased silhouette pixels.
  EXPECT_LT(changed, pixels / 1000) << "the meshopt picture differs from Draco's";
  std::printf("[ measured ] draco and meshopt: %lld triangles, %lld regions, %zu of %zu pixels differ\n",
              draco.triangles, draco.draco, changed, pixels);
}

// A view is served in Draco only: --codec meshopt without a profile, or with
// --views, ends at start (exit 2, nothing rendered) with a message naming
// the conflict and what to pass instead.
TEST(ViewCodec, MeshoptWithAViewIsRefusedAtStartNamingTheProfileOptions) {
  const std::string dir = testing::makeTempDir("tessera-view-codec-views");
  auto server = testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto created = testing::createCube(*server, true, 4);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  for (const std::vector<std::string>& extra : {std::vector<std::string>{"--codec", "meshopt"},
                                                std::vector<std::string>{"--views", "--codec=meshopt"}}) {
    std::vector<std::string> args = viewerArgs(*server, *created);
    args.insert(args.end(), extra.begin(), extra.end());
    args.insert(args.end(), {"--screenshot", dir + "/x.png"});
    const std::string log = dir + "/refused.log";
    std::filesystem::remove(log);
    EXPECT_EQ(testing::runBounded(args, {}, log, 60), 2) << extra.back();
    const std::string said = testing::fileBytes(log);
    EXPECT_NE(said.find("--codec meshopt: the server sends a view-dependent subscription (--views, the "
                        "default) in Draco only"),
              std::string::npos)
        << said;
    EXPECT_NE(said.find("pass --profile"), std::string::npos) << said;
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
  }
  // The same check guards a Connection whose options are built in code.
  view::ViewOptions options = testing::viewOptionsFor(*server, *created, 2, 3);
  options.views = true;
  options.codec = RegionCodec::kMeshopt;
  auto connection = view::Connection::open(options);
  ASSERT_FALSE(connection.isOk());
  EXPECT_NE(connection.status().message().find("--codec meshopt"), std::string::npos)
      << connection.status().message();
}

// The Connection under the viewer: its edits' deltas and a new profile
// chosen in the HUD (changeProfile) come in meshopt too, and its surface
// hash follows a Draco connection's through them.
TEST(ViewCodec, AMeshoptConnectionKeepsItsCodecThroughEditsAndAProfileChange) {
  const std::string dir = testing::makeTempDir("tessera-view-codec-connection");
  auto server = testing::ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto created = testing::createCube(*server, true, 5);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  auto open = [&](RegionCodec codec) {
    view::ViewOptions options = testing::viewOptionsFor(*server, *created, 2, 3);
    options.codec = codec;
    options.hashSurfaces = true;
    return view::Connection::open(options);
  };
  auto draco = open(RegionCodec::kDraco), meshopt = open(RegionCodec::kMeshopt);
  ASSERT_TRUE(draco.isOk()) << draco.status().message();
  ASSERT_TRUE(meshopt.isOk()) << meshopt.status().message();
  view::Connection &d = **draco, &m = **meshopt;
  ASSERT_TRUE(testing::waitFor([&] { return d.stats().ready && m.stats().ready; }));
  const auto expectSame = [&](const char* when) {
    const view::ConnectionStats a = d.stats(), b = m.stats();
    EXPECT_EQ(b.surfaceHash, a.surfaceHash) << when;
    EXPECT_EQ(b.dracoRegions, 0u) << when;
    EXPECT_EQ(b.meshoptRegions, a.dracoRegions) << when;
    EXPECT_EQ(a.meshoptRegions, 0u) << when;
  };
  expectSame("first snapshot");
  const uint64_t firstRegions = m.stats().meshoptRegions;
  ASSERT_GT(firstRegions, 0u);

  m.moveVertex(VertexId(2, 0).packed(), Vec3(0.1, 0.2, 1.4));
  ASSERT_TRUE(testing::waitFor([&] { return d.stats().version == 2 && m.stats().version == 2; }));
  expectSame("after an edit");
  EXPECT_GT(m.stats().meshoptRegions, firstRegions) << "the edit's delta brought no meshopt region";

  d.changeProfile(1, 3, 10);
  m.changeProfile(1, 3, 10);
  ASSERT_TRUE(testing::waitFor([&] { return d.stats().snapshots == 2 && m.stats().snapshots == 2; }));
  expectSame("after a profile change");
}

TEST(ViewCodec, DracoIsTheDefaultAndMeshoptGoesWithTheProfile) {
  auto plain = view::parseViewOptions({"--connect", "h:1", "--document", "1"});
  ASSERT_TRUE(plain.isOk()) << plain.status().message();
  EXPECT_EQ(plain->codec, RegionCodec::kDraco);
  EXPECT_TRUE(plain->views);
  for (const char* profile : {"--profile", "--max-level=3", "--base-level=0", "--angle=10"}) {
    auto o = view::parseViewOptions({"--connect", "h:1", "--document", "1", "--codec", "meshopt", profile});
    ASSERT_TRUE(o.isOk()) << profile << ": " << o.status().message();
    EXPECT_EQ(o->codec, RegionCodec::kMeshopt);
    EXPECT_FALSE(o->views);
  }
  auto unknown =
      view::parseViewOptions({"--connect", "h:1", "--document", "1", "--profile", "--codec", "zstd"});
  ASSERT_FALSE(unknown.isOk());
  EXPECT_NE(unknown.status().message().find("--codec"), std::string::npos) << unknown.status().message();
  auto hashWithoutPicture = view::parseViewOptions({"--connect", "h:1", "--document", "1", "--surface-hash"});
  ASSERT_FALSE(hashWithoutPicture.isOk());
  EXPECT_NE(hashWithoutPicture.status().message().find("--surface-hash needs --screenshot"),
            std::string::npos);
}

}  // namespace
}  // namespace tessera

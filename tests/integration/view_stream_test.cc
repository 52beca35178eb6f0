// View-dependent subscriptions against the real server (docs/VIEWS.md "The
// server", docs/PROTOCOL.md "Views"): fifty viewers with distinct cameras
// assemble watertight surfaces whose hash matches the server's, and every
// tile is encoded once for all of them; an edit in view reaches a viewer,
// one out of view sends it nothing it did not hold; a zoom in and back
// ends on the picture it started from, each step sending only the tiles
// it lacked; bad views are refused by name, and
// a flood of views is absorbed while a bystander keeps its latency.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <future>
#include <numbers>
#include <random>
#include <set>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "client/lib/view_wire.h"
#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/view/tile_tree.h"
#include "integration/bystanded_server.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "integration/server_stat.h"
#include "integration/view_subscriber.h"
#include "support/cameras.h"
#include "support/test_meshes.h"
#include "support/tile_gaps.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::expectWatertight;
using testing::lookAt;
using testing::Model;
using testing::modelOf;
using testing::randomView;
using testing::ServerProcess;
using testing::subscribeViewer;
using testing::Viewer;

// One of CGAL's meshes as a local document, for its points and counts.
Document cgalDocument(const std::string& file, int maxLevel) {
  auto mesh = importMesh(testing::cgalMeshPath(file));
  EXPECT_TRUE(mesh.isOk()) << file;
  auto doc = Document::create(*mesh, {.maxLevel = maxLevel});
  EXPECT_TRUE(doc.isOk()) << file;
  return std::move(*doc);
}

Model handModel() {
  return modelOf(cgalDocument("hand.off", 1));
}

// One of CGAL's meshes as a document of the server (CreateDocument).
Expected<uint64_t> createFromCgal(Session& admin, const std::string& file, int maxLevel) {
  wire::ClientMessage create;
  auto* c = create.mutable_create_document();
  c->set_name(file);
  c->set_mesh(testing::fileBytes(testing::cgalMeshPath(file)));
  c->set_mesh_format(wire::MESH_FORMAT_OFF);
  c->set_max_level(static_cast<uint32_t>(maxLevel));
  TESSERA_ASSIGN_OR_RETURN(wire::ServerMessage created, admin.call(create, 60));
  if (!created.has_ack()) return invalidArgument("create " + file + ": " + created.DebugString());
  return created.ack().document_id();
}

struct Served {
  std::optional<ServerProcess> server;
  std::unique_ptr<Session> admin;
  uint64_t doc = 0;
};

void startWithHand(Served& s, const std::string& name, int maxLevel, std::vector<std::string> args = {}) {
  auto server = ServerProcess::start(testing::makeTempDir(name) + "/data", args);
  ASSERT_TRUE(server.isOk()) << server.status().message();
  s.server.emplace(std::move(*server));
  auto admin = Session::connect(s.server->session("admin", s.server->adminToken()));
  ASSERT_TRUE(admin.isOk()) << admin.status().message();
  s.admin = std::move(*admin);
  auto created = createFromCgal(*s.admin, "hand.off", maxLevel);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  s.doc = *created;
}

// Sparse evaluation (docs/VIEWS.md "Sparse evaluation"): fandisk held to
// level 8 is 848 million limit triangles evaluated whole, far more than the
// 2 GiB of address space the server may add to what it had at start. A
// camera close to the surface still gets level-8 tiles where it looks,
// watertight and hashed as the server's; a whole-document profile at that
// level is refused by the triangle limit, not attempted.
TEST(ViewStream, ADocumentTooLargeToEvaluateWholeIsShownAtItsFinestLevelWhereACameraLooks) {
  auto server =
      ServerProcess::start(testing::makeTempDir("tessera-view-sparse") + "/data", {"--max-level", "8"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  const auto statusKiB = [&](const std::string& field) {
    std::ifstream in("/proc/" + std::to_string(server->pid()) + "/status");
    for (std::string line; std::getline(in, line);)
      if (line.rfind(field + ":", 0) == 0) return std::stoll(line.substr(field.size() + 1));
    return -1LL;
  };
  const long long startKiB = statusKiB("VmSize");
  ASSERT_GT(startKiB, 0);
  const rlimit cap{.rlim_cur = static_cast<rlim_t>(startKiB + (2LL << 20)) * 1024,
                   .rlim_max = static_cast<rlim_t>(startKiB + (2LL << 20)) * 1024};
  ASSERT_EQ(::prlimit(server->pid(), RLIMIT_AS, &cap, nullptr), 0) << std::strerror(errno);

  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk()) << admin.status().message();
  auto created = createFromCgal(**admin, "fandisk.off", 8);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  const uint64_t doc = *created;

  const Document local = cgalDocument("fandisk.off", 8);
  const int64_t whole = static_cast<int64_t>(local.counts().faces(8));
  EXPECT_EQ(whole, 12946LL << 16);
  const Model m = modelOf(local);
  // Three thousandths of the model's size from base vertex 0, looking at it.
  const Vec3 target = local.basePoints()[0];
  View close = lookAt(m, target + 0.003 * (target - m.centre).normalized(), target, 390, 844);
  close.nearDistance = 1e-5;
  auto v = subscribeViewer(*server, doc, close, "close");
  ASSERT_TRUE(v.isOk()) << v.status().message();
  expectWatertight(*v, m, "close to fandisk");
  std::map<int, int> tilesByLevel;
  int64_t triangles = 0;
  for (const auto& [id, mesh] : v->view->regions()) {
    ++tilesByLevel[TileKey::fromRegionId(id).level];
    triangles += static_cast<int64_t>(mesh.triangles.size());
  }
  const long long peakKiB = statusKiB("VmHWM");
  std::printf(
      "[ measured ] level 8 held whole: %lld triangles; the view: %lld triangles in %zu tiles (%d at level "
      "8), "
      "server peak RSS %lld MiB, address space capped at %lld MiB\n",
      static_cast<long long>(whole), static_cast<long long>(triangles), v->view->regions().size(),
      tilesByLevel[8], peakKiB / 1024, (startKiB + (2LL << 20)) / 1024);
  EXPECT_GT(tilesByLevel[8], 0) << "the finest level where the camera looks";
  EXPECT_LT(triangles * 100, whole) << "a small part of the whole";
  // The server is alive and answers; a whole profile at level 8 is refused.
  ASSERT_TRUE((*admin)->call(testing::openDocument(doc), 30).isOk());
  auto refused = (*admin)->call(testing::subscribe(doc, 8, 8), 30);
  ASSERT_TRUE(refused.isOk()) << refused.status().message();
  ASSERT_TRUE(refused->has_reject()) << refused->DebugString();
  EXPECT_EQ(refused->reject().reason(), wire::REJECT_REASON_LIMIT_EXCEEDED) << refused->DebugString();
  EXPECT_TRUE(server->running());
  EXPECT_EQ(server->stop(), 0);
}

// The first picture of a large document (docs/VIEWS.md "The first
// picture"): fandisk's 12,946 level-0 triangles come as the surface's
// preview, one region of a few kilobytes; the view's tiles follow and the
// preview goes, leaving the watertight picture the camera needs.
TEST(ViewStream, ALargeDocumentsFirstPictureIsAPreviewOfAFewKilobytesThenItsTiles) {
  auto server = ServerProcess::start(testing::makeTempDir("tessera-view-preview") + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  auto created = createFromCgal(**admin, "fandisk.off", 4);
  ASSERT_TRUE(created.isOk()) << created.status().message();
  const uint64_t doc = *created;
  const Model m = modelOf(cgalDocument("fandisk.off", 1));
  std::mt19937 rng(7);
  for (int camera = 0; camera < 3; ++camera) {
    const std::string where = "camera " + std::to_string(camera);
    auto v = subscribeViewer(*server, doc, randomView(m, rng), "viewer-" + std::to_string(camera));
    ASSERT_TRUE(v.isOk()) << where << ": " << v.status().message();
    std::printf(
        "[ measured ] %s: first picture %lld bytes in %zu region(s); then %lld bytes in %lld payloads\n",
        where.c_str(), static_cast<long long>(v->snapshotBytes), v->snapshotIds.size(),
        static_cast<long long>(v->bytes - v->snapshotBytes),
        static_cast<long long>(v->payloads - static_cast<int64_t>(v->snapshotIds.size())));
    ASSERT_EQ(v->snapshotIds, std::vector<uint64_t>{TileKey::preview().regionId()}) << where;
    EXPECT_LT(v->snapshotBytes, 16 << 10) << where;
    bool removed = false;
    for (const wire::Delta& d : v->deltas)
      for (uint64_t id : d.removed_region_ids()) removed |= id == TileKey::preview().regionId();
    EXPECT_TRUE(removed) << where;
    EXPECT_FALSE(v->view->regions().count(TileKey::preview().regionId())) << where;
    EXPECT_GT(v->view->regions().size(), 1u) << where;
    expectWatertight(*v, m, where);
  }
  EXPECT_EQ(server->stop(), 0);
}

TEST(ViewStream, FiftyCamerasGetWatertightSurfacesFromTilesEncodedOnce) {
  Served s;
  startWithHand(s, "tessera-view-fifty", 3);
  if (::testing::Test::HasFatalFailure()) return;
  const Model m = handModel();
  std::mt19937 rng(32);
  std::vector<Viewer> viewers;
  std::set<uint64_t> distinct;
  int64_t payloads = 0;
  for (int i = 0; i < 50; ++i) {
    auto v = subscribeViewer(*s.server, s.doc, randomView(m, rng), "viewer-" + std::to_string(i));
    ASSERT_TRUE(v.isOk()) << "viewer " << i << ": " << v.status().message();
    expectWatertight(*v, m, "viewer " + std::to_string(i));
    distinct.insert(v->received.begin(), v->received.end());
    payloads += v->payloads;
    viewers.push_back(std::move(*v));
  }
  const double encoded = testing::serverStat(*s.admin, "tiles_encoded");
  const double hits = testing::serverStat(*s.admin, "tile_cache_hits");
  std::printf(
      "[ measured ] 50 viewers: %lld tile payloads received, %zu distinct tiles, %.0f encodings, %.0f cache "
      "hits\n",
      static_cast<long long>(payloads), distinct.size(), encoded, hits);
  // Every tile sent was encoded once: as many encodings as distinct tiles.
  EXPECT_EQ(encoded, static_cast<double>(distinct.size()));
  EXPECT_EQ(hits + encoded, static_cast<double>(payloads));
  EXPECT_GT(payloads, 5 * static_cast<int64_t>(distinct.size())) << "the viewers shared their tiles";
  EXPECT_EQ(testing::serverStat(*s.admin, "view_subscribers"), 50);
}

// Deep tiles: one face of level L - 5 each, their ids as lattice points.
TEST(ViewStream, TilesBelowLevelFiveArriveWatertightOnTheCreasedCube) {
  Served s;
  auto server = ServerProcess::start(testing::makeTempDir("tessera-view-cube") + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  s.server.emplace(std::move(*server));
  auto admin = Session::connect(s.server->session("admin", s.server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  auto created = (*admin)->call(
      testing::createDocument("cube", testing::fileBytes(testing::sourceTestDataPath("cube.obj")),
                              testing::fileBytes(testing::sourceTestDataPath("cube.tags")), 6),
      30);
  ASSERT_TRUE(created.isOk() && created->has_ack()) << (created.isOk() ? created->DebugString() : "");
  const Model m{Vec3(0.5, 0.5, 0.5), 0.87};
  // Close on a crease corner: the view needs level 6 there.
  View close = lookAt(m, Vec3(1.15, 1.1, 1.2), Vec3(1, 1, 1), 1920, 1080);
  auto viewer = subscribeViewer(*s.server, created->ack().document_id(), close, "close");
  ASSERT_TRUE(viewer.isOk()) << viewer.status().message();
  std::map<int, int> levels;
  for (const auto& [id, mesh] : viewer->view->regions()) ++levels[TileKey::fromRegionId(id).level];
  EXPECT_TRUE(levels.count(6)) << "close on the corner the view shows level 6";
  expectWatertight(*viewer, m, "creased cube");
}

TEST(ViewStream, AnEditInViewArrivesAndOneOutOfViewSendsNothingNew) {
  Served s;
  startWithHand(s, "tessera-view-edit", 4);
  if (::testing::Test::HasFatalFailure()) return;
  const Document local = cgalDocument("hand.off", 1);
  const Model m = modelOf(local);
  // Close on base vertex 0; the farthest base vertex is behind the eye.
  const Vec3 near = local.basePoints()[0];
  size_t far = 0;
  for (size_t i = 0; i < local.basePoints().size(); ++i)
    if ((local.basePoints()[i] - near).norm() > (local.basePoints()[far] - near).norm()) far = i;
  const Vec3 outward = (near - m.centre).normalized();
  const View camera = lookAt(m, near + 0.25 * m.radius * outward, near, 390, 844);
  auto viewer = subscribeViewer(*s.server, s.doc, camera, "close");
  ASSERT_TRUE(viewer.isOk()) << viewer.status().message();
  std::set<TileKey> held;
  int deepest = 0;
  for (const auto& [id, mesh] : viewer->view->regions()) {
    held.insert(TileKey::fromRegionId(id));
    deepest = std::max(deepest, TileKey::fromRegionId(id).level);
  }
  EXPECT_EQ(deepest, 4) << "close up, the view needs the deepest level";

  auto editor = Session::connect(s.server->session("editor", s.server->adminToken()));
  ASSERT_TRUE(editor.isOk());
  ASSERT_TRUE((*editor)->call(testing::openDocument(s.doc), 30)->has_ack());
  // In view: the vertex it looks at moves towards the eye.
  const Vec3 to = near + 0.02 * m.radius * outward;
  auto moved = (*editor)->call(testing::moveVertex(s.doc, VertexId(0, 0).packed(), to[0], to[1], to[2]), 30);
  ASSERT_TRUE(moved.isOk() && moved->has_ack()) << (moved.isOk() ? moved->DebugString() : "");
  viewer->deltas.clear();
  ASSERT_TRUE(viewer->untilComplete().isOk());
  int64_t inView = 0;
  for (const wire::Delta& d : viewer->deltas) inView += d.regions_size();
  EXPECT_GT(inView, 0) << "the edit in view reached the viewer";
  // The held tiles the edit reached come first, in the delta that spans the
  // versions, before the server measures them; it is not complete, since
  // the camera's walk read those tiles. A later delta completes the view at
  // the new version (docs/VIEWS.md "The server").
  ASSERT_GE(viewer->deltas.size(), 2u);
  const wire::Delta& first = viewer->deltas.front();
  EXPECT_LT(first.from_version(), first.to_version());
  EXPECT_GT(first.regions_size(), 0) << "the reached tiles come with the edit's delta";
  EXPECT_FALSE(first.view_complete()) << "complete before the reached tiles were measured";
  EXPECT_EQ(viewer->deltas.back().from_version(), first.to_version());
  EXPECT_EQ(viewer->deltas.back().to_version(), first.to_version());
  EXPECT_TRUE(viewer->view->verifySurface().isOk()) << viewer->view->verifySurface().message();

  // Out of view: the far vertex moves; the viewer gets no tile it did not hold.
  held.clear();
  for (const auto& [id, mesh] : viewer->view->regions()) held.insert(TileKey::fromRegionId(id));
  const Vec3 farPoint = local.basePoints()[far];
  const Vec3 farTo = farPoint + 0.02 * m.radius * (farPoint - m.centre).normalized();
  auto movedFar = (*editor)->call(
      testing::moveVertex(s.doc, VertexId(0, far).packed(), farTo[0], farTo[1], farTo[2]), 30);
  ASSERT_TRUE(movedFar.isOk() && movedFar->has_ack());
  viewer->deltas.clear();
  ASSERT_TRUE(viewer->untilComplete().isOk());
  for (const wire::Delta& d : viewer->deltas) {
    for (const wire::Region& r : d.regions()) {
      const TileKey k = TileKey::fromRegionId(r.region_id());
      EXPECT_TRUE(held.count(k)) << "an edit out of view sent " << k.toString()
                                 << ", which the viewer did not show";
    }
  }
  EXPECT_TRUE(viewer->view->verifySurface().isOk()) << viewer->view->verifySurface().message();
  expectWatertight(*viewer, m, "after the edits");
}

TEST(ViewStream, AZoomInAndBackEndsOnThePictureItStartedFrom) {
  Served s;
  startWithHand(s, "tessera-view-zoom", 4, {"--view-interval-ms", "0"});
  if (::testing::Test::HasFatalFailure()) return;
  const Model m = handModel();
  const Vec3 away = m.centre + Vec3(0, 0, 3 * m.radius);
  const View start = lookAt(m, away, m.centre, 390, 844);
  auto viewer = subscribeViewer(*s.server, s.doc, start, "zoomer");
  ASSERT_TRUE(viewer.isOk()) << viewer.status().message();
  const uint64_t startHash = viewer->view->surfaceHash();
  const std::map<uint64_t, RegionMesh> startTiles = viewer->view->regions();
  const int64_t startBytes = viewer->bytes;
  // In to a tenth of the distance, in eight steps, then out the same way.
  std::vector<double> path;
  for (int k = 1; k <= 8; ++k) path.push_back(1.0 - 0.9 * k / 8);
  for (int k = 7; k >= 0; --k) path.push_back(1.0 - 0.9 * k / 8);
  int64_t stepBytes = 0, afresh = 0;
  for (size_t i = 0; i < path.size(); ++i) {
    const View step = lookAt(m, m.centre + path[i] * (away - m.centre), m.centre, 390, 844);
    const int64_t before = viewer->bytes;
    ASSERT_TRUE(viewer->session->send(client::setView(s.doc, step)).isOk());
    Status done = viewer->untilComplete();
    ASSERT_TRUE(done.isOk()) << "step " << i << ": " << done.message();
    expectWatertight(*viewer, m, "step " + std::to_string(i));
    stepBytes += viewer->bytes - before;
    afresh += viewer->pictureBytes();
  }
  EXPECT_EQ(viewer->view->surfaceHash(), startHash) << "back where it started, the same picture";
  EXPECT_EQ(viewer->view->regions().size(), startTiles.size());
  std::printf(
      "[ measured ] zoom path: %lld bytes for the first picture, %lld for 16 steps, %lld had each step's "
      "picture been sent whole\n",
      static_cast<long long>(startBytes), static_cast<long long>(stepBytes), static_cast<long long>(afresh));
  // A step sends only the tiles its picture lacks: well under sending each picture whole.
  EXPECT_LT(stepBytes, afresh / 2);
}

TEST(ViewStream, BadViewsAreRefusedByNameAndAFloodIsAbsorbed) {
  testing::BystandedServer s;
  testing::startBystanded(s, "tessera-view-abuse", {});
  if (::testing::Test::HasFatalFailure()) return;
  const Model m = handModel();
  wire::ClientMessage create;
  auto* c = create.mutable_create_document();
  c->set_name("hand");
  c->set_mesh(testing::fileBytes(testing::cgalMeshPath("hand.off")));
  c->set_mesh_format(wire::MESH_FORMAT_OFF);
  c->set_max_level(3);
  auto created = s.admin->call(create, 60);
  ASSERT_TRUE(created.isOk() && created->has_ack());
  const uint64_t doc = created->ack().document_id();
  auto options = s.server->session("abuser", s.server->adminToken());
  options.localAddress = "127.0.0.1";
  auto abuser = Session::connect(options);
  ASSERT_TRUE(abuser.isOk());
  ASSERT_TRUE((*abuser)->call(testing::openDocument(doc), 30)->has_ack());
  const View good = lookAt(m, m.centre + Vec3(0, 0, 3 * m.radius), m.centre, 390, 844);
  // Moving a view it has not subscribed.
  auto early = (*abuser)->call(client::setView(doc, good), 10);
  ASSERT_TRUE(early.isOk() && early->has_reject());
  EXPECT_NE(early->reject().message().find("subscribe with a view first"), std::string::npos);
  struct Bad {
    std::string what, expect;
    View view;
  };
  std::vector<Bad> bad;
  bad.push_back({"NaN eye", "eye", good});
  bad.back().view.eye = Vec3(std::nan(""), 0, 0);
  bad.push_back({"infinite forward", "forward", good});
  bad.back().view.forward = Vec3(HUGE_VAL, 0, 0);
  bad.push_back({"zero viewport", "viewport", good});
  bad.back().view.width = 0;
  bad.push_back({"degenerate field of view", "field of view", good});
  bad.back().view.fovYRadians = std::numbers::pi;
  bad.push_back({"forward along up", "parallel", good});
  bad.back().view.up = bad.back().view.forward;
  bad.push_back({"tolerance zero", "tolerance", good});
  bad.back().view.tolerancePixels = 0;
  bad.push_back({"tolerance 1e9", "tolerance", good});
  bad.back().view.tolerancePixels = 1e9;
  for (const Bad& b : bad) {
    auto r = (*abuser)->call(client::subscribeWithView(doc, b.view), 10);
    ASSERT_TRUE(r.isOk()) << b.what;
    ASSERT_TRUE(r->has_reject()) << b.what << ": " << r->DebugString();
    EXPECT_NE(r->reject().message().find(b.expect), std::string::npos)
        << b.what << ": " << r->reject().message();
  }
  // Subscribed, then 10,000 views in about a second while the bystander edits.
  auto ok = (*abuser)->call(client::subscribeWithView(doc, good), 60);
  ASSERT_TRUE(ok.isOk() && ok->has_ack()) << (ok.isOk() ? ok->DebugString() : ok.status().message());
  auto flood = std::async(std::launch::async, [&] {
    std::mt19937 rng(9);
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < 10000; ++i) {
      if (!(*abuser)->send(client::setView(doc, randomView(m, rng))).isOk()) return false;
      if (i % 10 == 9) std::this_thread::sleep_until(t0 + std::chrono::microseconds(100 * (i + 1)));
    }
    return true;
  });
  testing::expectServed(*s.bystander, s.bystander->run(20), "during the view flood");
  EXPECT_TRUE(flood.get());
  // The session is still served: a ping comes back behind the flood's replies.
  auto pong = (*abuser)->call(testing::ping(), 60);
  EXPECT_TRUE(pong.isOk() && pong->has_pong())
      << (pong.isOk() ? pong->DebugString() : pong.status().message());
  const double received = testing::serverStat(*s.admin, "views_received");
  const double applied = testing::serverStat(*s.admin, "views_applied");
  std::printf("[ measured ] view flood: %.0f views reached a document, %.0f applied\n", received, applied);
  EXPECT_LT(applied, received / 10) << "views are applied at most once per interval";
}

}  // namespace
}  // namespace tessera

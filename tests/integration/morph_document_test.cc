// Morph documents (docs/PROTOCOL.md §14) through the service: a morph document on the real
// tessera-server (127.0.0.1, real store). AddMorphKey makes the creased cube
// a morph document; viewers subscribed at t = 0, 0.5 and 1 see the surface
// of key 0, of the halfway control mesh and of key 1, each checked against a
// document built locally from those control points alone (no morph code);
// edits name their key and reach the views they change; the coarse stream
// sends the control points at t; refusals name what is wrong; a restart
// (journal replay and a snapshot) keeps both keys.
#include <gtest/gtest.h>

#include <optional>
#include <sstream>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/surface_hash.h"
#include "core/tessellation/tessellation.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "integration/server_stat.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ServerProcess;

constexpr int kMaxLevel = 3;
constexpr uint32_t kBase = 1, kMax = 3;
constexpr double kAngle = 15;

// Key 1: every cube point moved by a map that is not affine (so the
// halfway mesh is not a scaled cube).
Vec3 keyOnePoint(const Vec3& p) {
  return Vec3(1.6 * p[0] + 0.3 * p[1] * p[2], p[1] + 0.2 * p[0] * p[0], 0.7 * p[2] + 0.1);
}

BaseMesh cubeMesh() {
  auto mesh = importMesh(testing::sourceTestDataPath("cube.obj"));
  EXPECT_TRUE(mesh.isOk());
  EXPECT_TRUE(applyTagFile(testing::sourceTestDataPath("cube.tags"), *mesh).isOk());
  return std::move(*mesh);
}

// cube.obj with its points replaced.
std::string objWith(const std::vector<Vec3>& points, bool otherDiagonal = false) {
  std::istringstream in(testing::fileBytes(testing::sourceTestDataPath("cube.obj")));
  std::ostringstream out;
  out.precision(17);
  size_t v = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) == 0) {
      out << "v " << points[v][0] << " " << points[v][1] << " " << points[v][2] << "\n";
      ++v;
    } else if (otherDiagonal && line == "f 5 6 7") {
      out << "f 5 6 8\n";  // the top's other diagonal
    } else if (otherDiagonal && line == "f 5 7 8") {
      out << "f 6 7 8\n";
    } else {
      out << line << "\n";
    }
  }
  return out.str();
}

// The surface hash (PROTOCOL 6.5) a server streams for the tagged cube
// topology on these control points, computed here without morph code.
uint64_t referenceHash(const std::vector<Vec3>& points) {
  BaseMesh mesh = cubeMesh();
  auto key0 = Document::create(mesh, {.maxLevel = kMaxLevel});
  EXPECT_TRUE(key0.isOk());
  auto grid = documentGrid(*key0);  // the document's grid comes from key 0
  auto doc = Document::create(key0->baseTopology(), points, {.maxLevel = kMaxLevel});
  EXPECT_TRUE(doc.isOk() && grid.isOk());
  LodProfile profile;
  profile.baseLevel = kBase;
  profile.maxLevel = kMax;
  profile.angleThresholdDegrees = kAngle;
  auto tessellation = Tessellation::build(*doc, profile);
  EXPECT_TRUE(tessellation.isOk());
  uint64_t sum = 0;
  for (const auto& [id, region] : tessellation->regions())
    sum += regionSurfaceHashOnGrid(region, *grid, true);
  return sum;
}

wire::ClientMessage addKey(uint64_t doc, const std::string& obj) {
  wire::ClientMessage m;
  auto* a = m.mutable_add_morph_key();
  a->set_document_id(doc);
  a->set_mesh(obj);
  a->set_mesh_format(wire::MESH_FORMAT_OBJ);
  a->set_file_name("key1.obj");
  return m;
}

wire::ClientMessage subscribeAt(uint64_t doc, double t) {
  wire::ClientMessage m = testing::subscribe(doc, kBase, kMax, kAngle);
  m.mutable_subscribe()->mutable_profile()->set_morph_t(t);
  return m;
}

wire::ClientMessage control(uint64_t doc, double t, bool topology) {
  wire::ClientMessage m;
  m.mutable_get_morph_control()->set_document_id(doc);
  m.mutable_get_morph_control()->set_t(t);
  m.mutable_get_morph_control()->set_with_topology(topology);
  return m;
}

void readUntil(Session& s, DocumentView& view, uint64_t version) {
  for (int i = 0; i < 400 && (!view.ready() || view.version() < version); ++i) {
    auto m = s.receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    Status ok = view.apply(*m);
    ASSERT_TRUE(ok.isOk()) << ok.message();
  }
  ASSERT_TRUE(view.ready());
  ASSERT_EQ(view.version(), version);
  ASSERT_TRUE(view.verifySurface().isOk());  // the server's hash is the decoded surface's
}

void expectRejected(Session& s, const wire::ClientMessage& m, const std::string& why) {
  auto r = s.call(m, 30);
  ASSERT_TRUE(r.isOk() && r->has_reject()) << (r.isOk() ? r->DebugString() : r.status().message());
  EXPECT_NE(r->reject().message().find(why), std::string::npos) << r->reject().message();
}

void expectAck(Session& s, const wire::ClientMessage& m) {
  auto r = s.call(m, 30);
  ASSERT_TRUE(r.isOk()) << r.status().message() << " for " << m.DebugString();
  ASSERT_TRUE(r->has_ack()) << r->DebugString();
}

struct Viewers {
  std::unique_ptr<Session> key0, at0, half, at1;
};

TEST(MorphDocument, ViewersSeeEachTimeAndEditsOfEitherKey) {
  const BaseMesh mesh = cubeMesh();
  const std::vector<Vec3> points0 = mesh.positions();
  std::vector<Vec3> points1, halfway;
  for (const Vec3& p : points0) {
    points1.push_back(keyOnePoint(p));
    halfway.push_back(0.5 * p + 0.5 * keyOnePoint(p));
  }

  const std::string dir = testing::makeTempDir("tessera-morph");
  // A snapshot every 3 versions: the restart below loads a morph snapshot
  // and replays the journal after it.
  auto server = ServerProcess::start(dir + "/data", {"--snapshot-every", "3", "--max-mesh-bytes", "4096"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  auto created = (*admin)->call(
      testing::createDocument("cube", testing::fileBytes(testing::sourceTestDataPath("cube.obj")),
                              testing::fileBytes(testing::sourceTestDataPath("cube.tags")), kMaxLevel),
      30);
  ASSERT_TRUE(created.isOk() && created->has_ack()) << created->DebugString();
  const uint64_t doc = created->ack().document_id();
  expectAck(**admin, testing::grant(doc, wire::ROLE_VIEWER, "viewer-token-0123456789"));
  expectAck(**admin, testing::openDocument(doc));

  // Before a second key: refusals that say so.
  expectRejected(**admin, subscribeAt(doc, 0.5),
                 "morph_t is set but document " + std::to_string(doc) + " has one key");
  expectRejected(**admin, control(doc, 0.5, false), "the document has one key");
  wire::ClientMessage onKey1 =
      testing::moveVertex(doc, VertexId(0, 2).packed(), 0, 0, 0.1, wire::MOVE_MODE_OFFSET);
  onKey1.mutable_move_vertex()->set_key(1);
  expectRejected(**admin, onKey1, "key 1 does not exist: the document has 1 key");
  // Another connectivity, by a viewer, a non-PNG image.
  expectRejected(
      **admin, addKey(doc, objWith(points1, /*otherDiagonal=*/true)),
      "triangle 2 is (4, 5, 6) in key 0 (document " + std::to_string(doc) + ") but (4, 5, 7) in key1.obj");
  auto viewerSession = Session::connect(server->session("viewer", "viewer-token-0123456789"));
  ASSERT_TRUE(viewerSession.isOk());
  expectAck(**viewerSession, testing::openDocument(doc));
  expectRejected(**viewerSession, addKey(doc, objWith(points1)), "needs the editor role");
  wire::ClientMessage notPng = addKey(doc, objWith(points1));
  notPng.mutable_add_morph_key()->set_image_from("GIF89a");
  notPng.mutable_add_morph_key()->set_image_to("GIF89a");
  expectRejected(**admin, notPng, "image_from is not a PNG");

  // A mesh over --max-mesh-bytes, as for CreateDocument.
  std::string padded = objWith(points1);
  padded += "# " + std::string(5000, 'x') + "\n";
  auto tooLarge = (*admin)->call(addKey(doc, padded), 30);
  ASSERT_TRUE(tooLarge.isOk() && tooLarge->has_reject()) << tooLarge->DebugString();
  EXPECT_EQ(tooLarge->reject().reason(), wire::REJECT_REASON_LIMIT_EXCEEDED);
  EXPECT_NE(tooLarge->reject().message().find("above the limit of 4096"), std::string::npos)
      << tooLarge->reject().message();

  // Key 1 far outside the document's grid (the cube around key 0): its
  // surface could not be encoded, so the key is refused and not kept.
  std::vector<Vec3> far = points1;
  for (Vec3& p : far) p = 100.0 * p;
  auto outside = (*admin)->call(addKey(doc, objWith(far)), 30);
  ASSERT_TRUE(outside.isOk() && outside->has_reject()) << outside->DebugString();
  EXPECT_EQ(outside->reject().reason(), wire::REJECT_REASON_LIMIT_EXCEEDED);
  EXPECT_NE(outside->reject().message().find("outside the document's bounds"), std::string::npos)
      << outside->reject().message();
  expectRejected(**admin, subscribeAt(doc, 0.5), "has one key");

  auto added = (*admin)->call(addKey(doc, objWith(points1)), 30);
  ASSERT_TRUE(added.isOk() && added->has_ack()) << added->DebugString();
  EXPECT_EQ(added->ack().version(), 2u);
  expectRejected(**admin, addKey(doc, objWith(points1)), "already has two keys");
  expectRejected(**admin, subscribeAt(doc, 1.5), "morph_t 1.500000 is not in [0, 1]");

  // Four viewers: key 0 as it is (incremental), and the morph at 0, 0.5, 1.
  Viewers v;
  std::vector<std::pair<Session*, wire::ClientMessage>> subs;
  for (auto [slot, t] : {std::pair{&v.key0, -1.0}, {&v.at0, 0.0}, {&v.half, 0.5}, {&v.at1, 1.0}}) {
    auto s = Session::connect(server->session("viewer", "viewer-token-0123456789"));
    ASSERT_TRUE(s.isOk());
    *slot = std::move(*s);
    expectAck(**slot, testing::openDocument(doc));
    auto subscribed =
        (*slot)->call(t < 0 ? testing::subscribe(doc, kBase, kMax, kAngle) : subscribeAt(doc, t), 30);
    ASSERT_TRUE(subscribed.isOk() && subscribed->has_ack()) << subscribed->DebugString();
  }
  DocumentView key0(doc), at0(doc), half(doc), at1(doc);
  readUntil(*v.key0, key0, 2);
  readUntil(*v.at0, at0, 2);
  readUntil(*v.half, half, 2);
  readUntil(*v.at1, at1, 2);
  const uint64_t hash0 = referenceHash(points0), hashHalf = referenceHash(halfway),
                 hash1 = referenceHash(points1);
  EXPECT_EQ(key0.surfaceHash(), hash0);
  EXPECT_EQ(at0.surfaceHash(), hash0);  // t = 0 is key 0 exactly
  EXPECT_EQ(half.surfaceHash(), hashHalf);
  EXPECT_EQ(at1.surfaceHash(), hash1);  // t = 1 is key 1 exactly
  EXPECT_NE(hashHalf, hash0);
  EXPECT_NE(hashHalf, hash1);

  // The coarse stream: the control points at t, as float32.
  auto coarse = (*viewerSession)->call(control(doc, 0.5, true), 10);
  ASSERT_TRUE(coarse.isOk() && coarse->has_morph_control()) << coarse->DebugString();
  const wire::MorphControl& c = coarse->morph_control();
  ASSERT_EQ(c.points_size(), static_cast<int>(3 * halfway.size()));
  for (size_t i = 0; i < halfway.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(c.points(static_cast<int>(3 * i + k)), static_cast<float>(halfway[i][k]));
  }
  EXPECT_EQ(c.triangles_size(), 36);
  EXPECT_EQ(c.crease_sharpness_size(), 12);
  EXPECT_EQ(c.version(), 2u);
  EXPECT_EQ(c.max_level(), static_cast<uint32_t>(kMaxLevel));
  auto plain = (*viewerSession)->call(control(doc, 1.0, false), 10);
  ASSERT_TRUE(plain.isOk() && plain->has_morph_control());
  EXPECT_EQ(plain->morph_control().triangles_size(), 0);
  EXPECT_EQ(plain->morph_control().points(0), static_cast<float>(points1[0][0]));
  expectRejected(**viewerSession, control(doc, -0.1, false), "morph time -0.100000 is not in [0, 1]");

  // An edit of key 1: the key-0 views keep their surface (a delta with no
  // region), the morph views at 0.5 and 1 change.
  auto moved = (*admin)->call(onKey1, 10);
  ASSERT_TRUE(moved.isOk() && moved->has_ack()) << moved->DebugString();
  ASSERT_EQ(moved->ack().version(), 3u);
  const uint64_t key1Edit = moved->ack().edit_id();
  readUntil(*v.key0, key0, 3);
  readUntil(*v.at0, at0, 3);
  readUntil(*v.half, half, 3);
  readUntil(*v.at1, at1, 3);
  EXPECT_EQ(key0.surfaceHash(), hash0);
  EXPECT_EQ(at0.surfaceHash(), hash0);
  EXPECT_NE(half.surfaceHash(), hashHalf);
  EXPECT_NE(at1.surfaceHash(), hash1);
  // Its offset is world z 0.1 at a base vertex: key 1's point moves by it.
  std::vector<Vec3> movedPoints1 = points1, movedHalf = halfway;
  movedPoints1[2] += Vec3(0, 0, 0.1);
  movedHalf[2] = 0.5 * points0[2] + 0.5 * movedPoints1[2];
  EXPECT_EQ(at1.surfaceHash(), referenceHash(movedPoints1));
  const uint64_t halfMoved = half.surfaceHash();

  // An edit of key 0 (key unset): every view but the one at t = 1 changes.
  auto moved0 = (*admin)->call(
      testing::moveVertex(doc, VertexId(0, 5).packed(), 0.05, 0, 0, wire::MOVE_MODE_OFFSET), 10);
  ASSERT_TRUE(moved0.isOk() && moved0->has_ack()) << moved0->DebugString();
  readUntil(*v.key0, key0, 4);
  readUntil(*v.at0, at0, 4);
  readUntil(*v.half, half, 4);
  readUntil(*v.at1, at1, 4);
  std::vector<Vec3> movedPoints0 = points0;
  movedPoints0[5] += Vec3(0.05, 0, 0);
  EXPECT_EQ(key0.surfaceHash(), referenceHash(movedPoints0));
  EXPECT_EQ(at0.surfaceHash(), key0.surfaceHash());
  EXPECT_EQ(at1.surfaceHash(), referenceHash(movedPoints1));
  EXPECT_NE(half.surfaceHash(), halfMoved);

  // Undo names its key: edit ids are per key.
  wire::ClientMessage undo;
  undo.mutable_undo()->set_document_id(doc);
  undo.mutable_undo()->set_edit_id(key1Edit);
  undo.mutable_undo()->set_key(1);
  auto undone = (*admin)->call(undo, 10);
  ASSERT_TRUE(undone.isOk() && undone->has_ack()) << undone->DebugString();
  readUntil(*v.at1, at1, 5);
  EXPECT_EQ(at1.surfaceHash(), hash1);
  const uint64_t halfAfterUndo = [&] {
    readUntil(*v.half, half, 5);
    return half.surfaceHash();
  }();

  // A restart: the snapshot (both keys) and the journal after it.
  const uint64_t key0Hash = key0.surfaceHash();
  v = {};
  viewerSession->reset();
  admin->reset();
  EXPECT_EQ(server->stop(), 0);
  auto restarted = ServerProcess::start(dir + "/data", {"--snapshot-every", "3", "--max-mesh-bytes", "4096"});
  ASSERT_TRUE(restarted.isOk()) << restarted.status().message();
  for (auto [t, expected] : {std::pair{0.5, halfAfterUndo}, {1.0, hash1}, {0.0, key0Hash}}) {
    auto again = Session::connect(restarted->session("viewer", "viewer-token-0123456789"));
    ASSERT_TRUE(again.isOk());
    expectAck(**again, testing::openDocument(doc));
    expectAck(**again, subscribeAt(doc, t));
    DocumentView reloaded(doc);
    readUntil(**again, reloaded, 5);
    EXPECT_EQ(reloaded.surfaceHash(), expected) << "t = " << t;
  }
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

double regionsEncoded(Session& s) {
  return testing::serverStat(s, "regions_encoded");
}

// A viewer playing a morph comes back to the times it showed: a view at a
// time nobody watches is kept (within --max-triangles) and its regions are
// not built and encoded again; a change of a key drops the kept views.
TEST(MorphDocument, ViewsAtATimeAreKeptForViewersComingBack) {
  const BaseMesh mesh = cubeMesh();
  std::vector<Vec3> points1;
  for (const Vec3& p : mesh.positions()) points1.push_back(keyOnePoint(p));
  const std::string dir = testing::makeTempDir("tessera-morph-keep");
  auto server = ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  auto created = (*admin)->call(
      testing::createDocument("cube", testing::fileBytes(testing::sourceTestDataPath("cube.obj")),
                              testing::fileBytes(testing::sourceTestDataPath("cube.tags")), kMaxLevel),
      30);
  ASSERT_TRUE(created.isOk() && created->has_ack());
  const uint64_t doc = created->ack().document_id();
  expectAck(**admin, testing::openDocument(doc));
  // A recorder (with_commands) hears of the second key, mesh as sent.
  auto recorder = Session::connect(server->session("recorder", server->adminToken()));
  ASSERT_TRUE(recorder.isOk());
  expectAck(**recorder, testing::openDocument(doc));
  wire::ClientMessage recording = testing::subscribe(doc, kBase, kMax, kAngle);
  recording.mutable_subscribe()->set_with_commands(true);
  expectAck(**recorder, recording);
  const std::string obj1 = objWith(points1);
  expectAck(**admin, addKey(doc, obj1));
  std::optional<wire::AppliedCommand> relayed;
  for (int i = 0; i < 50 && !relayed; ++i) {
    auto m = (*recorder)->receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    if (m->has_applied_command()) relayed = m->applied_command();
  }
  ASSERT_TRUE(relayed.has_value());
  EXPECT_EQ(relayed->version(), 2u);
  ASSERT_TRUE(relayed->has_add_morph_key());
  EXPECT_EQ(relayed->add_morph_key().mesh(), obj1);

  auto viewer = Session::connect(server->session("viewer", server->adminToken()));
  ASSERT_TRUE(viewer.isOk());
  expectAck(**viewer, testing::openDocument(doc));
  auto show = [&](double t) {
    expectAck(**viewer, subscribeAt(doc, t));
    DocumentView view(doc);
    readUntil(**viewer, view, view.version() == 0 ? 2 : view.version());
    return view.surfaceHash();
  };
  const double before = regionsEncoded(**admin);
  const uint64_t quarter = show(0.25);
  const double afterFirst = regionsEncoded(**admin);
  EXPECT_GT(afterFirst, before);
  show(0.75);
  const double afterSecond = regionsEncoded(**admin);
  EXPECT_GT(afterSecond, afterFirst);
  // Back at 0.25: the kept view, nothing encoded, the same surface.
  EXPECT_EQ(show(0.25), quarter);
  EXPECT_EQ(regionsEncoded(**admin), afterSecond);

  // An edit of key 1: the view at 0.25 is watched and rebuilt; the kept one
  // at 0.75 is dropped, so coming back to it builds it again.
  wire::ClientMessage onKey1 =
      testing::moveVertex(doc, VertexId(0, 3).packed(), 0, 0.1, 0, wire::MOVE_MODE_OFFSET);
  onKey1.mutable_move_vertex()->set_key(1);
  expectAck(**admin, onKey1);
  DocumentView followed(doc);
  const double beforeBack = regionsEncoded(**admin);
  expectAck(**viewer, subscribeAt(doc, 0.75));
  readUntil(**viewer, followed, 3);
  EXPECT_GT(regionsEncoded(**admin), beforeBack);
}

}  // namespace
}  // namespace tessera

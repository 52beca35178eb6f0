// Two region codecs on one document (docs/REGION_ENCODING.md, "meshopt
// regions"; PROTOCOL.md, Subscribe.codec) against a real tessera-server: a
// Draco and a meshopt subscriber of the same profile receive regions in
// their own codec (checked by each region's magic), and after every edit
// both decoded surfaces have the same regions, the same triangles over the
// same ids, and positions within the grid's quantization bound of each
// other; the server's surface hash holds for both. A codec the server does
// not know, and meshopt for a view, are refused naming the field.
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <string>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/hierarchy/ids.h"
#include "core/tessellation/region_codec.h"
#include "integration/cube_server.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/region_checks.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::CubeServer;
using testing::startWithCube;

// The cube's max level, the one the subscribers below ask for.
constexpr int kMaxLevel = 5;

// A subscriber that checks the magic of every region it receives.
struct Viewer {
  std::unique_ptr<Session> session;
  std::unique_ptr<DocumentView> view;
  std::string magic;  // "TSRG" or "TSRM"
  size_t regionsReceived = 0;
  size_t withLayoutIds = 0;  // payloads that leave the ids to the held copy (flag 2)
  std::optional<QuantizationGrid> grid;
};

void checkRegions(Viewer& v, const google::protobuf::RepeatedPtrField<wire::Region>& regions) {
  for (const wire::Region& r : regions) {
    ++v.regionsReceived;
    ASSERT_GE(r.draco().size(), 4u);
    EXPECT_EQ(r.draco().substr(0, 4), v.magic) << "region " << r.region_id();
    auto decoded = decodeRegion(r.draco());
    ASSERT_TRUE(decoded.isOk()) << decoded.status().message();
    if (!v.grid) v.grid = decoded->first.grid;
    if (!decoded->first.idsInline) ++v.withLayoutIds;
  }
}

void readUntil(Viewer& v, uint64_t version) {
  for (int i = 0; i < 400 && !(v.view->ready() && v.view->version() >= version); ++i) {
    auto m = v.session->receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    if (m->has_snapshot()) checkRegions(v, m->snapshot().regions());
    if (m->has_delta()) checkRegions(v, m->delta().regions());
    Status applied = v.view->apply(*m);
    ASSERT_TRUE(applied.isOk()) << applied.message();
  }
  ASSERT_TRUE(v.view->ready());
  ASSERT_EQ(v.view->version(), version);
}

Viewer subscribeWith(CubeServer& s, const std::string& name, wire::RegionCodec codec,
                     const std::string& magic) {
  Viewer v;
  auto session = Session::connect(s.process->session(name, s.process->adminToken()));
  EXPECT_TRUE(session.isOk()) << session.status().message();
  if (!session.isOk()) return v;
  v.session = std::move(*session);
  v.view = std::make_unique<DocumentView>(s.doc);
  v.magic = magic;
  EXPECT_TRUE(v.session->call(testing::openDocument(s.doc), 10)->has_ack());
  auto sub = testing::subscribe(s.doc, 2, 5, 10);
  if (codec != wire::REGION_CODEC_UNSPECIFIED) sub.mutable_subscribe()->set_codec(codec);
  auto subscribed = v.session->call(sub, 30);
  EXPECT_TRUE(subscribed.isOk() && subscribed->has_ack()) << subscribed->DebugString();
  return v;
}

// Both decoded surfaces agree: regions, triangles over ids, positions
// within the quantization bound of the vertex with the same id.
void expectSameSurface(const Viewer& draco, const Viewer& meshopt) {
  ASSERT_TRUE(draco.grid && meshopt.grid);
  ASSERT_EQ(*draco.grid, *meshopt.grid);
  const double bound = draco.grid->maxPositionError();
  const auto& a = draco.view->regions();
  const auto& b = meshopt.view->regions();
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [id, mesh] : a) {
    SCOPED_TRACE("region " + std::to_string(id));
    ASSERT_EQ(b.count(id), 1u);
    const RegionMesh& other = b.at(id);
    EXPECT_EQ(testing::trianglesOverIds(other), testing::trianglesOverIds(mesh));
    std::multimap<uint64_t, Vec3> byId;
    for (size_t i = 0; i < mesh.vertexIds.size(); ++i) byId.emplace(mesh.vertexIds[i], mesh.positions[i]);
    ASSERT_EQ(other.vertexIds.size(), other.positions.size());
    for (size_t i = 0; i < other.vertexIds.size(); ++i) {
      auto [first, last] = byId.equal_range(other.vertexIds[i]);
      ASSERT_NE(first, last) << VertexId::fromPacked(other.vertexIds[i]).toString();
      double nearest = 1e300;
      for (auto it = first; it != last; ++it)
        nearest = std::min(nearest, (it->second - other.positions[i]).norm());
      EXPECT_LE(nearest, bound) << VertexId::fromPacked(other.vertexIds[i]).toString();
    }
  }
  EXPECT_TRUE(draco.view->verifySurface().isOk());
  EXPECT_TRUE(meshopt.view->verifySurface().isOk());
  EXPECT_EQ(draco.view->announcedSurfaceHash(), meshopt.view->announcedSurfaceHash());
}

TEST(RegionCodecStream, DracoAndMeshoptSubscribersDecodeTheSameSurfaceThroughEdits) {
  CubeServer s;
  startWithCube(s, "tessera-codec-stream", kMaxLevel);
  if (::testing::Test::HasFatalFailure()) return;
  Viewer draco = subscribeWith(s, "draco", wire::REGION_CODEC_UNSPECIFIED, "TSRG");
  Viewer meshopt = subscribeWith(s, "meshopt", wire::REGION_CODEC_MESHOPT, "TSRM");
  if (::testing::Test::HasFailure()) return;
  readUntil(draco, 1);
  readUntil(meshopt, 1);
  if (::testing::Test::HasFatalFailure()) return;
  EXPECT_GT(meshopt.regionsReceived, 0u);
  expectSameSurface(draco, meshopt);

  // Small offsets of level-2 control points (deltas that keep most
  // layouts: their ids are adopted from the held copy), large moves of
  // limit positions at levels 2, 0 and 1 (new layouts).
  struct Move {
    VertexId vertex;
    Vec3 target;
    wire::MoveMode mode;
  };
  const auto offset = wire::MOVE_MODE_OFFSET, direct = wire::MOVE_MODE_DIRECT_MANIPULATION;
  const std::vector<Move> moves = {{VertexId(2, 40), {0.001, -0.0005, 0.0008}, offset},
                                   {VertexId(2, 0), {0.1, 0.05, 1.2}, direct},
                                   {VertexId(2, 17), {-0.3, 0.4, 0.9}, direct},
                                   {VertexId(2, 41), {-0.0007, 0.001, 0.0004}, offset},
                                   {VertexId(0, 3), {0.2, -0.1, 0.3}, direct},
                                   {VertexId(2, 0), {0.12, 0.02, 1.25}, direct},
                                   {VertexId(1, 20), {0.5, 0.5, -0.2}, direct},
                                   {VertexId(2, 60), {0.0006, 0.0006, -0.001}, offset}};
  uint64_t version = 1;
  for (const auto& [vertex, target, mode] : moves) {
    auto moved =
        s.admin->call(testing::moveVertex(s.doc, vertex.packed(), target[0], target[1], target[2], mode), 10);
    ASSERT_TRUE(moved.isOk() && moved->has_ack()) << moved->DebugString();
    version = moved->ack().version();
    readUntil(draco, version);
    readUntil(meshopt, version);
    if (::testing::Test::HasFatalFailure()) return;
    SCOPED_TRACE("after moving " + vertex.toString() + ", version " + std::to_string(version));
    expectSameSurface(draco, meshopt);
  }
  EXPECT_EQ(draco.view->gaps(), 0u);
  EXPECT_EQ(meshopt.view->gaps(), 0u);
  // The moves sent regions without ids, which the meshopt viewer adopted.
  EXPECT_GT(meshopt.withLayoutIds, 0u);
  EXPECT_EQ(meshopt.withLayoutIds, draco.withLayoutIds);

  // A late meshopt subscriber gets a snapshot of the same surface.
  Viewer late = subscribeWith(s, "late", wire::REGION_CODEC_MESHOPT, "TSRM");
  readUntil(late, version);
  if (::testing::Test::HasFatalFailure()) return;
  expectSameSurface(draco, late);
}

TEST(RegionCodecStream, AnUnknownCodecIsRefusedNamingTheField) {
  CubeServer s;
  startWithCube(s, "tessera-codec-reject", kMaxLevel);
  if (::testing::Test::HasFatalFailure()) return;
  auto sub = testing::subscribe(s.doc, 2, 5, 10);
  sub.mutable_subscribe()->set_codec(static_cast<wire::RegionCodec>(7));
  auto refused = s.admin->call(sub, 10);
  ASSERT_TRUE(refused.isOk()) << refused.status().message();
  ASSERT_TRUE(refused->has_reject()) << refused->DebugString();
  EXPECT_EQ(refused->reject().reason(), wire::REJECT_REASON_INVALID_ARGUMENT);
  EXPECT_NE(refused->reject().message().find("Subscribe.codec"), std::string::npos) << refused->DebugString();
  EXPECT_NE(refused->reject().message().find("unknown value 7"), std::string::npos) << refused->DebugString();

  // meshopt is not served to view-dependent subscriptions: refused too.
  auto viewSub = testing::subscribe(s.doc, 2, 5, 10);
  auto* view = viewSub.mutable_subscribe()->mutable_view();
  view->mutable_eye()->set_z(5);
  view->mutable_forward()->set_z(-1);
  view->mutable_up()->set_y(1);
  view->set_fov_y_radians(1.0);
  view->set_near_distance(0.1);
  view->set_width(640);
  view->set_height(480);
  view->set_tolerance_pixels(1);
  viewSub.mutable_subscribe()->set_codec(wire::REGION_CODEC_MESHOPT);
  refused = s.admin->call(viewSub, 10);
  ASSERT_TRUE(refused.isOk()) << refused.status().message();
  ASSERT_TRUE(refused->has_reject()) << refused->DebugString();
  EXPECT_EQ(refused->reject().reason(), wire::REJECT_REASON_INVALID_ARGUMENT);
  EXPECT_NE(refused->reject().message().find("Subscribe.codec"), std::string::npos) << refused->DebugString();

  // The session is still usable: the same subscription with Draco works.
  auto ok = testing::subscribe(s.doc, 2, 5, 10);
  ok.mutable_subscribe()->set_codec(wire::REGION_CODEC_DRACO);
  auto subscribed = s.admin->call(ok, 30);
  ASSERT_TRUE(subscribed.isOk());
  EXPECT_TRUE(subscribed->has_ack()) << subscribed->DebugString();
}

}  // namespace
}  // namespace tessera

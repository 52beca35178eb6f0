// View-dependent subscriptions to a Catmull-Clark document against the real
// server (docs/VIEWS.md "Catmull-Clark documents"): CGAL's quad double torus,
// created without a scheme (so Catmull-Clark, as its faces call for).
// Cameras all round it assemble watertight surfaces whose hash is the
// server's, from tiles encoded once for all of them; a camera close to the
// surface gets one-face tiles below level 5, whose ids travel as quad
// lattice points; a drag in view reaches it, with the dragged vertex's
// limit at its target, and the picture stays watertight.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "client/lib/view_wire.h"
#include "core/schemes/polygon_reader.h"
#include "core/tessellation/quantization_grid.h"
#include "core/view/tile_tree.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "integration/server_stat.h"
#include "integration/view_subscriber.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::Session;
using testing::ServerProcess;

constexpr int kMaxLevel = 6;

TEST(CatmarkViewStream, CamerasGetWatertightTilesEncodedOnceAndADragInViewArrives) {
  const std::string path = testing::cgalMeshPath("double-torus-example.off");
  auto polygons = schemes::importPolygonMesh(path, "");
  ASSERT_TRUE(polygons.isOk()) << polygons.status().message();
  const testing::Model m = testing::modelOf(polygons->points);

  auto server = ServerProcess::start(testing::makeTempDir("tessera-catmark-view") + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk()) << admin.status().message();
  wire::ClientMessage create =
      testing::createDocument("double torus", testing::fileBytes(path), "", kMaxLevel);
  create.mutable_create_document()->set_mesh_format(wire::MESH_FORMAT_OFF);
  auto created = (*admin)->call(create, 60);
  ASSERT_TRUE(created.isOk() && created->has_ack()) << (created.isOk() ? created->DebugString() : "");
  ASSERT_EQ(created->ack().scheme(), wire::SUBDIVISION_SCHEME_CATMULL_CLARK);
  const uint64_t doc = created->ack().document_id();

  // Cameras all round, from close to far. Each viewer stays: the tiles are
  // the loaded document's, and a document nobody holds open is unloaded,
  // its tiles with it (docs/VIEWS.md "The server").
  std::mt19937 rng(33);
  std::vector<testing::Viewer> viewers;
  std::set<uint64_t> distinct;
  int64_t payloads = 0;
  for (int i = 0; i < 12; ++i) {
    auto v =
        testing::subscribeViewer(*server, doc, testing::randomView(m, rng), "viewer-" + std::to_string(i));
    ASSERT_TRUE(v.isOk()) << "viewer " << i << ": " << v.status().message();
    testing::expectWatertight(*v, m, "viewer " + std::to_string(i));
    distinct.insert(v->received.begin(), v->received.end());
    payloads += v->payloads;
    viewers.push_back(std::move(*v));
  }
  const double encoded = testing::serverStat(**admin, "tiles_encoded");
  std::printf(
      "[ measured ] 12 viewers of a catmull-clark document: %lld tile payloads, %zu distinct, %.0f "
      "encodings\n",
      static_cast<long long>(payloads), distinct.size(), encoded);
  EXPECT_EQ(encoded, static_cast<double>(distinct.size())) << "every tile sent was encoded once";
  EXPECT_GT(payloads, static_cast<int64_t>(distinct.size())) << "the viewers shared their tiles";

  // Close on base vertex 0: tiles of levels 5 and 6, one face each.
  const Vec3 near = polygons->points[0];
  const Vec3 outward = (near - m.centre).normalized();
  const View close = testing::lookAt(m, near + 0.05 * m.radius * outward, near, 1920, 1080);
  auto viewer = testing::subscribeViewer(*server, doc, close, "close");
  ASSERT_TRUE(viewer.isOk()) << viewer.status().message();
  int deepest = 0;
  for (const auto& [id, mesh] : viewer->view->regions())
    deepest = std::max(deepest, TileKey::fromRegionId(id).level);
  EXPECT_GE(deepest, 5) << "close up, one-face tiles below level 5";
  testing::expectWatertight(*viewer, m, "close");
  // A drag of the vertex it looks at: its limit goes to the target.
  auto editor = Session::connect(server->session("editor", server->adminToken()));
  ASSERT_TRUE(editor.isOk());
  ASSERT_TRUE((*editor)->call(testing::openDocument(doc), 30)->has_ack());
  const Vec3 target = near + 0.01 * m.radius * outward;
  auto moved =
      (*editor)->call(testing::moveVertex(doc, VertexId(0, 0).packed(), target[0], target[1], target[2]), 30);
  ASSERT_TRUE(moved.isOk() && moved->has_ack()) << (moved.isOk() ? moved->DebugString() : "");
  viewer->deltas.clear();
  ASSERT_TRUE(viewer->untilComplete().isOk());
  int64_t arrived = 0;
  for (const wire::Delta& d : viewer->deltas) arrived += d.regions_size();
  EXPECT_GT(arrived, 0) << "the drag in view reached the viewer";
  double landed = 1e9;
  for (const auto& [id, mesh] : viewer->view->regions()) {
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      if (mesh.vertexIds[v] == VertexId(0, 0).packed())
        landed = std::min(landed, (mesh.positions[v] - target).norm());
    }
  }
  // The stream's grid errs by at most this fraction of the base diagonal
  // (core/tessellation/document_grid.h).
  EXPECT_LE(landed, kDefaultMaxErrorFraction * 2 * m.radius * (1 + 1e-9))
      << "v0:0's streamed limit is not at its target";
  testing::expectWatertight(*viewer, m, "after the drag");
  EXPECT_EQ(server->stop(), 0);
}

}  // namespace
}  // namespace tessera

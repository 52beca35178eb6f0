// A new viewer's first picture on a large document (docs/VIEWS.md "The
// first picture"): the surface's preview is made from the document's
// level-0 faces, so the host sends it before it builds the tile tree and
// chooses the view's tiles, which take most of the first second on a large
// mesh. Nothing about time is asserted: the order is. The io_context is
// polled on this thread, so each step's work is done when it returns.
#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <memory>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/view/tile_tree.h"
#include "integration/messages.h"
#include "server/document/document_host.h"
#include "support/decoding_inbox.h"
#include "support/host_only_store.h"
#include "support/test_meshes.h"

namespace tessera::server {
namespace {

using Inbox = testing::DecodingInbox;

class ViewFirstPicture : public ::testing::Test {
 protected:
  void SetUp() override {
    // fandisk: 12,946 level-0 triangles, more than a preview's 2,048 times
    // four (previewPays).
    auto mesh = importMesh(testing::cgalMeshPath("fandisk.off"));
    ASSERT_TRUE(mesh.isOk()) << mesh.status().message();
    auto doc = Document::create(*mesh, {.maxLevel = 3});
    ASSERT_TRUE(doc.isOk()) << doc.status().message();
    host_ = std::make_shared<DocumentHost>(store::DocumentId{1}, "fandisk", KeyedDocument(std::move(*doc)), 1,
                                           io_.get_executor(), io_.get_executor(), store_, config_, stats_);
    viewer_->note = [this] { return stats_.tilesBuilt.load(); };
    host_->join(viewer_, "viewer", wire::ROLE_VIEWER);
    poll();
  }
  void TearDown() override {
    host_.reset();
    poll();
  }
  void poll() {
    io_.restart();
    while (io_.poll() > 0) io_.restart();
  }
  // The whole model on a phone-sized screen, tolerance 1 px; `budget`
  // triangles (0: the server's limit).
  wire::Subscribe viewSubscription(uint64_t budget) {
    wire::Subscribe s;
    s.set_document_id(1);
    s.mutable_profile()->set_triangle_budget(budget);
    wire::View* v = s.mutable_view();
    v->mutable_eye()->set_z(3);
    v->mutable_forward()->set_z(-1);
    v->mutable_up()->set_y(1);
    v->set_fov_y_radians(0.8);
    v->set_near_distance(0.1);
    v->set_width(390);
    v->set_height(844);
    v->set_tolerance_pixels(1);
    return s;
  }

  // What the viewer got from index `from` on, with the tiles built when
  // each was sent; presence messages (on their own timer) left out.
  struct Got {
    wire::ServerMessage message;
    int64_t tilesBuilt = 0;
  };
  std::vector<Got> gotFrom(size_t from) const {
    std::vector<Got> got;
    for (size_t i = from; i < viewer_->received.size(); ++i) {
      if (!viewer_->received[i].has_presence()) got.push_back({viewer_->received[i], viewer_->noted[i]});
    }
    return got;
  }

  ServerConfig config_;
  ServerStats stats_;
  testing::HeldStore store_;
  boost::asio::io_context io_;
  std::shared_ptr<DocumentHost> host_;
  std::shared_ptr<Inbox> viewer_ = std::make_shared<Inbox>(2);
};

TEST_F(ViewFirstPicture, ThePreviewGoesBeforeAnyTileIsBuilt) {
  const size_t before = viewer_->received.size();
  host_->subscribe(viewer_, viewSubscription(0), 5, false);
  poll();
  const std::vector<Got> got = gotFrom(before);
  ASSERT_GE(got.size(), 3u) << "an Ack, the preview and the tiles";
  ASSERT_TRUE(got[0].message.has_ack()) << got[0].message.DebugString();
  EXPECT_EQ(got[0].message.ack().client_seq(), 5u);
  const wire::ServerMessage& first = got[1].message;
  ASSERT_TRUE(first.has_snapshot()) << first.DebugString();
  ASSERT_EQ(first.snapshot().regions_size(), 1);
  EXPECT_EQ(first.snapshot().regions(0).region_id(), TileKey::preview().regionId());
  // Sent before the tile tree was walked: no tile was built yet.
  EXPECT_EQ(got[1].tilesBuilt, 0) << "tiles built before the first picture went";
  // Then the view's tiles, built after it, and the preview goes.
  bool removed = false;
  int deltas = 0;
  for (size_t i = 2; i < got.size(); ++i) {
    if (!got[i].message.has_delta()) continue;
    ++deltas;
    EXPECT_GT(got[i].tilesBuilt, 0);
    for (uint64_t id : got[i].message.delta().removed_region_ids())
      removed |= id == TileKey::preview().regionId();
  }
  EXPECT_GT(deltas, 0);
  EXPECT_TRUE(removed) << "the preview was replaced by the view's tiles";
  EXPECT_GT(stats_.tilesBuilt.load(), 0);
  // The first viewer's tiles, the preview included, were each looked up in
  // the cache once, to be encoded: no lookup found one there.
  EXPECT_EQ(stats_.tileCacheHits.load(), 0) << "a tile asked of the cache twice for one viewer";
  EXPECT_GT(stats_.tilesEncoded.load(), 1);
}

// A budget below the level-0 surface may be too small for the view's
// coarsest tiles: the tiles are chosen first, so the refusal is the only
// answer, never one that follows an Ack.
TEST_F(ViewFirstPicture, ABudgetBelowTheCoarsestTilesIsRefusedWithoutAnAck) {
  const size_t before = viewer_->received.size();
  host_->subscribe(viewer_, viewSubscription(100), 6, false);
  poll();
  const std::vector<Got> got = gotFrom(before);
  ASSERT_EQ(got.size(), 1u) << "one answer, then " << got.back().message.DebugString();
  const wire::ServerMessage& answer = got[0].message;
  ASSERT_TRUE(answer.has_reject()) << answer.DebugString();
  EXPECT_EQ(answer.reject().client_seq(), 6u);
  EXPECT_EQ(answer.reject().reason(), wire::REJECT_REASON_LIMIT_EXCEEDED) << answer.DebugString();
  EXPECT_NE(answer.reject().message().find("budget of 100"), std::string::npos) << answer.reject().message();
}

}  // namespace
}  // namespace tessera::server
